// Tests for distribution.hpp: the 1D and 2D piecewise-constant distributions sample their own
// pdf (chi-square), the pdf integrates to one, bins of weight zero are never sampled, and the
// last bin is safe in float.
#include <zraka/app/chi_square.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/distribution.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

using namespace zraka;

namespace {
constexpr int tests = 2;  // chi-square tests in this file (Sidak)
}

TEST_CASE("distribution: 1D samples follow their pdf (chi-square), zero bins never sampled") {
  const std::vector<double> w = {0, 3, 0.5, 0, 0, 8, 1, 0};
  const distribution_1d d(w);
  CHECK(d.integral() == doctest::Approx(12.5 / 8));
  rng g(7, 0, 0);
  const grid2 grid{32, 1, 0, 1, 0, 1};
  const auto r = chi_square_2d(
      [&]() -> std::optional<vec2> {
        double pdf = 0;
        std::size_t bin = 0;
        const double x = d.sample(g.uniform(), pdf, bin);
        REQUIRE(w[bin] > 0);
        REQUIRE(pdf == doctest::Approx(d.pdf(x)));
        return vec2(x, 0.5);
      },
      [&](double x, double) { return d.pdf(x); }, 200000, grid);
  MESSAGE("1D: X^2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
  CHECK(r.impossible == 0);
  CHECK(r.p_value > sidak_level(0.01, tests));
  double integral = 0;
  for (int i = 0; i < 8000; ++i) integral += d.pdf((i + 0.5) / 8000) / 8000;
  CHECK(integral == doctest::Approx(1).epsilon(1e-12));
}

TEST_CASE_TEMPLATE("distribution: u at the top of [0,1) stays in the last weighted bin, below 1", T, float, double) {
  const distribution_1d d(std::vector<double>{1, 2, 5, 0, 0});
  for (T u : {one_minus_epsilon<T>, T(1), std::nextafter(T(1), T(0))}) {
    double pdf = 0;
    std::size_t bin = 0;
    const T x = d.sample(u, pdf, bin);
    CHECK(bin == 2);
    CHECK(x < T(1));
    CHECK(x <= T(0.6));
    CHECK(pdf == doctest::Approx(5.0 * 5 / 8));
  }
  double pdf = 0;
  std::size_t bin = 9;
  CHECK(d.sample(T(0), pdf, bin) == T(0));
  CHECK(bin == 0);
}

TEST_CASE("distribution: all-zero weights sample uniformly; bad weights are refused") {
  const distribution_1d d(std::vector<double>{0, 0, 0});
  double pdf = 0;
  std::size_t bin = 0;
  const double x = d.sample(0.5, pdf, bin);
  CHECK(x == doctest::Approx(0.5));
  CHECK(pdf == 1);
  CHECK_THROWS_WITH(distribution_1d(std::vector<double>{1, -1}), doctest::Contains("negative"));
  CHECK_THROWS_WITH(distribution_1d(std::vector<double>{1, std::nan("")}), doctest::Contains("not finite"));
  CHECK_THROWS_WITH(distribution_1d(std::vector<double>{}), doctest::Contains("no bins"));
  CHECK_THROWS_WITH(distribution_2d(std::vector<double>{1, 2, 3}, 2, 2), doctest::Contains("3 weights"));
}

TEST_CASE("distribution: 2D samples follow their pdf (chi-square) with zero rows and columns") {
  // 6 columns x 4 rows, one row and one column all zero, a bright cell.
  const std::size_t nu = 6, nv = 4;
  std::vector<double> w(nu * nv);
  for (std::size_t v = 0; v < nv; ++v)
    for (std::size_t u = 0; u < nu; ++u) w[v * nu + u] = (v == 1 || u == 4) ? 0.0 : 1.0 + double(u * v);
  w[3 * nu + 2] = 40;
  const distribution_2d d(w, nu, nv);
  rng g(11, 0, 0);
  const grid2 grid{24, 16, 0, 1, 0, 1};
  long zero_cells = 0;
  const auto r = chi_square_2d(
      [&]() -> std::optional<vec2> {
        double pdf = 0;
        const vec2 p = d.sample(vec2(g.uniform2()), pdf);
        const std::size_t u = std::size_t(p.x * nu), v = std::size_t(p.y * nv);
        if (w[v * nu + u] == 0) ++zero_cells;
        REQUIRE(pdf == doctest::Approx(d.pdf(p.x, p.y)));
        return p;
      },
      [&](double x, double y) { return d.pdf(x, y); }, 300000, grid);
  MESSAGE("2D: X^2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
  CHECK(zero_cells == 0);
  CHECK(r.impossible == 0);
  CHECK(r.p_value > sidak_level(0.01, tests));
  double integral = 0;
  for (int j = 0; j < 400; ++j)
    for (int i = 0; i < 600; ++i) integral += d.pdf((i + 0.5) / 600, (j + 0.5) / 400) / (600.0 * 400.0);
  CHECK(integral == doctest::Approx(1).epsilon(1e-9));
  // In float, too: the same bins.
  double pf = 0;
  const vec2_t<float> pf2 = d.sample(vec2_t<float>(one_minus_epsilon<float>, one_minus_epsilon<float>), pf);
  CHECK(pf2.x < 1.0f);
  CHECK(pf2.y < 1.0f);
  CHECK(pf > 0);
}

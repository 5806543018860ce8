#include <zraka/media/medium.hpp>
#include <zraka/sampling/estimator.hpp>

#include <doctest/doctest.h>

#include <cmath>

using namespace zraka;

namespace {

// A smooth heterogeneous box: the noise cloud of medium.hpp over [-1, 1]^3.
std::shared_ptr<const density_grid> cloud() {
  return std::make_shared<density_grid>(density_grid::noise(aabb{vec3(-1), vec3(1)}, 24, 2.5, 7));
}
// The optical-depth integral D = integral of d along r over (0, t), by a very fine midpoint rule.
double fine_D(const density_grid& d, const ray& r, double t) {
  const int n = 200000;
  double D = 0;
  for (int i = 0; i < n; ++i) D += d.at(r.at((i + 0.5) * t / n)) * t / n;
  return D;
}

}  // namespace

TEST_CASE_TEMPLATE("medium: Beer-Lambert transmittance is exp(-sigma_t t), tiny and huge", T, float, double) {
  medium m;
  m.name = "test";
  for (const float s : {0.0f, 1e-30f, 1e-6f, 0.5f, 3.0f, 1e6f, 1e30f}) {
    m.sigma_a = rgb(s, 0.5f * s, 0.0f);
    m.sigma_s = rgb(0.0f, 0.5f * s, s);
    for (const double t : {0.0, 1e-20, 1e-3, 1.0, 40.0, 1e20}) {
      rng g(1);
      const rgb tr = segment_transmittance(m, ray_t<T>(vec3_t<T>(0), vec3_t<T>(0, 0, 1)), T(t), g, {});
      const double want = std::exp(-double(s) * double(T(t)));
      CAPTURE(s);
      CAPTURE(t);
      CHECK(tr.x == doctest::Approx(want).epsilon(1e-6));
      CHECK(tr.y == doctest::Approx(want).epsilon(1e-6));
      CHECK(tr.z == doctest::Approx(want).epsilon(1e-6));
    }
  }
  // No medium at all along an infinite ray: 0 inf is 0 optical depth, not NaN.
  CHECK(beer_lambert(rgb(0), infinity<double>) == rgb(1));
  CHECK(beer_lambert(rgb(1), infinity<double>) == rgb(0));
}

TEST_CASE_TEMPLATE("medium: free flight through a chromatic medium: pass weight x P = T_r, scatter weight mean = integral",
                   T, float, double) {
  // E[pass ? weight : 0] = T_r(t_max) per channel, and E[scattered ? weight : 0] =
  // integral_0^t_max sigma_s T_r dt = albedo (1 - T_r): the one-sample MIS over channels is unbiased.
  medium m;
  m.name = "milk";
  m.sigma_a = rgb(0.2f, 0.5f, 2.0f);
  m.sigma_s = rgb(1.0f, 0.1f, 0.0f);
  const double t_max = 1.3;
  estimator_t<double> pass[3], scat[3];
  for (int i = 0; i < 200000; ++i) {
    rng g(3, 0, std::uint32_t(i));
    const auto f = sample_flight(m, ray_t<T>(vec3_t<T>(0), vec3_t<T>(1, 0, 0)), T(t_max), g, {});
    REQUIRE(is_finite(f.weight));
    for (int c = 0; c < 3; ++c) {
      pass[c].add(f.scattered ? 0.0 : double(f.weight[c]));
      scat[c].add(f.scattered ? double(f.weight[c]) : 0.0);
    }
  }
  for (int c = 0; c < 3; ++c) {
    const double st = double(m.sigma_t()[c]), tr = std::exp(-st * t_max);
    CAPTURE(c);
    CHECK(std::abs(pass[c].mean() - tr) <= 4 * pass[c].standard_error() + 1e-12);
    const double want = double(m.sigma_s[c]) / st * (1 - tr);
    CHECK(std::abs(scat[c].mean() - want) <= 4 * scat[c].standard_error() + 1e-12);
  }
}

TEST_CASE("medium: ratio tracking of the density grid agrees with a fine quadrature") {
  medium m;
  m.name = "cloud";
  m.sigma_a = rgb(1.0f);
  m.sigma_s = rgb(2.0f);
  m.density = cloud();
  for (const auto& r : {ray({-2, 0.1, 0.2}, {1, 0.1, -0.05}), ray({0.3, -3, 0.5}, {-0.2, 1, 0.1})}) {
    const double t = 6;
    const double want = std::exp(-3.0 * fine_D(*m.density, r, t));
    estimator_t<double> e;
    medium_options o;
    for (int i = 0; i < 100000; ++i) {
      rng g(5, 0, std::uint32_t(i));
      e.add(double(segment_transmittance(m, r, t, g, o).x));
    }
    MESSAGE("ratio tracking " << e.mean() << " +- " << e.standard_error() << ", quadrature " << want);
    CHECK(want > 0.05);
    CHECK(want < 0.95);
    CHECK(std::abs(e.mean() - want) <= 4 * e.standard_error());
  }
}

TEST_CASE("medium: delta tracking's distances follow sigma_t T_r (collision-before-t probability)") {
  medium m;
  m.name = "cloud";
  m.sigma_s = rgb(3.0f);
  m.density = cloud();
  const ray r({-2, 0.1, 0.2}, {1, 0.1, -0.05});
  // P(collision before t) = 1 - exp(-sigma_t D(t)), for a few t.
  for (const double t : {1.5, 2.0, 2.5, 4.0}) {
    estimator_t<double> e;
    for (int i = 0; i < 50000; ++i) {
      rng g(9, 0, std::uint32_t(i));
      const auto f = sample_flight(m, r, 6.0, g, {});
      e.add(f.scattered && f.t < t ? 1.0 : 0.0);
    }
    const double want = 1 - std::exp(-3.0 * fine_D(*m.density, r, t));
    CAPTURE(t);
    CHECK(std::abs(e.mean() - want) <= 4 * e.standard_error() + 1e-9);
  }
}

TEST_CASE("medium: the marching bias falls with the step (as step^2 once it resolves the grid)") {
  medium m;
  m.name = "cloud";
  m.sigma_a = rgb(20.0f);  // T_r about 0.57 along this ray
  m.density = cloud();
  const ray r({-2, 0.1, 0.2}, {1, 0.1, -0.05});
  const double want = std::exp(-20.0 * fine_D(*m.density, r, 6));
  medium_options march;
  march.estimator = media_estimator::march;
  double last = 1;
  for (const double step : {0.4, 0.1, 0.025}) {
    march.step = step;
    rng g(1);
    const double err = std::abs(double(segment_transmittance(m, r, 6.0, g, march).x) - want);
    MESSAGE("march step " << step << ": |T_r - reference| = " << err << " (reference " << want << ")");
    CHECK(err < last / 4);  // step / 4: step^2 gives 16x, the grid's kinks less at coarse steps
    last = err;
  }
  CHECK(last < 1e-4);
}

TEST_CASE("medium: bad coefficients are refused by name") {
  medium m;
  m.name = "bad";
  m.sigma_a = rgb(-1.0f);
  CHECK_THROWS_WITH_AS(m.check(), doctest::Contains("medium 'bad': sigma_a"), error);
  m.sigma_a = rgb(0.0f);
  m.sigma_s = rgb(std::nanf(""));
  CHECK_THROWS_WITH_AS(m.check(), doctest::Contains("sigma_s"), error);
  m.sigma_s = rgb(1.0f);
  m.g = 1;
  CHECK_THROWS_WITH_AS(m.check(), doctest::Contains("g must be in (-1, 1)"), error);
  CHECK_THROWS_AS(density_grid(aabb{vec3(0), vec3(1)}, 2, std::vector<float>(8, 2.0f)), error);
}

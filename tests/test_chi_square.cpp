// The chi-square machinery itself: the incomplete gamma function against known values, the
// corrections for repeated tests, pooling, calibration under a correct sampler, and rejection
// of wrong samplers.
#include <doctest/doctest.h>

#include <sstream>
#include <zraka/app/chi_square.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/sampling.hpp>

using namespace zraka;

TEST_CASE("gamma_q matches closed forms") {
  // Q(1, x) = e^-x; relative 1e-12 (a few roundings of the series/fraction), including the far
  // tail x = 700, where 1 - P would be 0 and only the continued fraction keeps the digits.
  for (double x : {1e-3, 0.1, 0.5, 1.0, 1.9, 2.1, 5.0, 30.0, 700.0})
    CHECK(gamma_q(1, x) == doctest::Approx(std::exp(-x)).epsilon(1e-12));
  // Q(1/2, x) = erfc(sqrt x) (the chi-square tail with 1 degree of freedom).
  for (double x : {1e-4, 0.3, 1.0, 1.5, 4.0, 20.0})
    CHECK(gamma_q(0.5, x) == doctest::Approx(std::erfc(std::sqrt(x))).epsilon(1e-12));
  // Integer a: Q(n, x) = e^-x sum_{k<n} x^k/k!.
  for (double x : {0.5, 3.0, 7.0, 12.0, 40.0}) {
    double term = 1, sum = 1;
    for (int k = 1; k < 7; ++k) sum += (term *= x / k);
    CHECK(gamma_q(7, x) == doctest::Approx(std::exp(-x) * sum).epsilon(1e-11));
  }
  CHECK(gamma_q(3, 0) == 1);
  CHECK(gamma_q(3, infinity<double>) == 0);
  CHECK(std::isnan(gamma_q(0, 1)));
  CHECK(std::isnan(gamma_q(1, -1)));
}

TEST_CASE("chi-square p-values at tabulated critical values") {
  // Critical values of the chi-square distribution at p = 0.05 and 0.01 (6-7 significant digits
  // in the tables, hence relative 1e-5).
  struct row {
    double x, dof, p;
  };
  for (const row& r : {row{3.841459, 1, 0.05}, row{6.634897, 1, 0.01}, row{5.991465, 2, 0.05},
                       row{18.307038, 10, 0.05}, row{23.209251, 10, 0.01},
                       row{124.342113, 100, 0.05}, row{135.806723, 100, 0.01}})
    CHECK(chi_square_p_value(r.x, r.dof) == doctest::Approx(r.p).epsilon(1e-5));
  // The mean of chi-square(k) is k: for large k the p-value there tends to 1/2 from below.
  CHECK(chi_square_p_value(1000, 1000) == doctest::Approx(0.4940).epsilon(1e-3));
}

TEST_CASE("Sidak and Bonferroni levels") {
  CHECK(sidak_level(0.01, 1) == doctest::Approx(0.01).epsilon(1e-14));
  // k tests at the Sidak level together reject with probability alpha.
  const double s = sidak_level(0.01, 30);
  CHECK(1 - std::pow(1 - s, 30) == doctest::Approx(0.01).epsilon(1e-12));
  CHECK(bonferroni_level(0.01, 30) < s);  // Bonferroni is the stricter (smaller) level
  CHECK(sidak_level(1e-12, 1000) > 0);    // no cancellation for tiny alpha (log1p / expm1)
  CHECK(sidak_level(1e-12, 1000) == doctest::Approx(1e-15).epsilon(1e-6));
}

TEST_CASE("bins expecting fewer than 5 are pooled; samples where the pdf is zero fail") {
  // Five bins expecting 1 each pool into one bin expecting 5; the two 10s stay: 3 bins, dof 2.
  const auto r = chi_square_test({1, 1, 1, 1, 1, 10, 10}, {1, 1, 1, 1, 1, 10, 10});
  CHECK(r.bins == 3);
  CHECK(r.dof == 2);
  CHECK(r.statistic == 0);
  CHECK(r.p_value == 1);
  // A leftover pool (expected 2 < 5) joins the smallest regular bin.
  const auto l = chi_square_test({2, 10, 20}, {2, 10, 20});
  CHECK(l.bins == 2);
  // Zero-expected bins: empty ones are ignored, a sample in one is impossible.
  CHECK(chi_square_test({0, 50, 50}, {0, 50, 50}).dof == 1);
  const auto bad = chi_square_test({1, 49, 50}, {0, 50, 50});
  CHECK(bad.impossible == 1);
  CHECK(bad.p_value == 0);
}

TEST_CASE("under a correct sampler the p-values are uniform") {
  // 200 independent small tests of the cosine sampler: the fraction with p < 0.1 is binomial
  // (200, 0.1), mean 20, sd 4.2; accept 8..34 (beyond 3 sd happens with probability ~0.3%,
  // and the seeds are fixed).
  int below = 0;
  for (std::uint32_t seed = 0; seed < 200; ++seed) {
    rng g(seed + 1000);
    const auto r = chi_square_directions([&] { return sample_cosine_hemisphere(g.uniform2()); },
                                         [](const vec3& w) { return cosine_hemisphere_pdf(w); },
                                         2000, direction_grid(4, 4));
    below += r.p_value < 0.1;
  }
  MESSAGE("tests with p < 0.1: " << below << " of 200 (expected 20)");
  CHECK(below >= 8);
  CHECK(below <= 34);
}

TEST_CASE("wrong samplers are rejected") {
  const double level = sidak_level(0.01, 4);
  // Uniform hemisphere directions tested against the cosine pdf.
  {
    rng g(1);
    const auto r = chi_square_directions([&] { return sample_uniform_hemisphere(g.uniform2()); },
                                         [](const vec3& w) { return cosine_hemisphere_pdf(w); },
                                         100000, direction_grid(20, 40));
    MESSAGE("uniform hemisphere vs cosine pdf: X^2 = " << r.statistic << ", p = " << r.p_value);
    CHECK(r.p_value < level);
  }
  // A subtle slip: sin(theta) = u0 instead of sqrt(u0) in the cosine sampler.
  {
    rng g(2);
    const auto r = chi_square_directions(
        [&] {
          const vec2 u = g.uniform2();
          const double s = u.x, phi = 2 * pi<double> * u.y;
          return vec3(s * std::cos(phi), s * std::sin(phi), std::sqrt(1 - s * s));
        },
        [](const vec3& w) { return cosine_hemisphere_pdf(w); }, 100000, direction_grid(20, 40));
    MESSAGE("sin = u instead of sqrt(u): p = " << r.p_value);
    CHECK(r.p_value < level);
  }
  // The cone's pdf with the naive 1 - cos(theta_max) computed in float for a small cone
  // (r/d = 1e-3: cancellation makes 1 - cos 7% too large) is detected.
  {
    const float s = 1e-3f;
    const float naive = 1.0f - std::sqrt(1.0f - s * s);  // 5.36e-7 instead of 5.00e-7
    const float good = cone_one_minus_cos(1e-3f, 1.0f);
    rng g(3);
    // Bin h = 1 - cos(theta) over [0, naive], the naive pdf's support, where it is uniform in h.
    CHECK(naive > 1.07f * good);
    const auto r = chi_square_2d(
        [&]() -> std::optional<vec2> {
          const vec3f w = sample_cone(vec2_t<float>(g.uniform_float(), g.uniform_float()), good);
          const double h = double(w.x * w.x + w.y * w.y) / (1 + double(w.z));
          return vec2(h, 0.5);
        },
        [&](double, double) { return 1 / double(naive); }, 100000,
        grid2{10, 1, 0, double(naive), 0, 1});
    MESSAGE("cone with cancelled 1 - cos: p = " << r.p_value);
    CHECK(r.p_value < level);
  }
  // A mixture whose pdf forgets the weights (sums the two pdfs) fails; the right one passes.
  {
    const mixture_t<cosine_hemisphere_t<double>, uniform_sphere_t<double>> m{
        cosine_hemisphere_t<double>(vec3(0, 0, 1)), {}, 0.5};
    rng g(4);
    const auto wrong = chi_square_directions([&] { return m.sample(g.uniform2()); },
                                             [&](const vec3& w) { return m.a.pdf(w) + m.b.pdf(w); },
                                             100000, direction_grid(20, 20));
    CHECK(wrong.p_value < level);
  }
}

#include <zraka/app/chi_square.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/media/phase.hpp>

#include <doctest/doctest.h>

#include <string>
#include <type_traits>

using namespace zraka;

TEST_CASE_TEMPLATE("phase: isotropic and Henyey-Greenstein integrate to one and have mean cosine g", T, float, double) {
  for (const double g : {-0.9, 0.0, 0.5, 0.99}) {
    // Over cos theta in [-1, 1] (2 pi from phi): midpoint rule, fine near the forward peak.
    double total = 0, mean_cos = 0;
    const int n = 2000000;
    for (int i = 0; i < n; ++i) {
      const double mu = -1 + (i + 0.5) * 2.0 / n;
      const double p = g == 0 ? 1 / (4 * pi<double>) : double(henyey_greenstein(T(mu), T(g)));
      total += 2 * pi<double> * p * 2.0 / n;
      mean_cos += 2 * pi<double> * p * mu * 2.0 / n;
    }
    CAPTURE(g);
    CHECK(total == doctest::Approx(1).epsilon(std::is_same_v<T, float> ? 2e-3 : 1e-4));
    CHECK(mean_cos == doctest::Approx(g).epsilon(2e-3).scale(1));
  }
}

TEST_CASE_TEMPLATE("phase: sample() follows eval() (chi-square) at g = -0.9, 0, 0.5, 0.99; pdf = value", T, float, double) {
  const double level = sidak_level(0.01, 8);  // 4 values of g, 2 types
  const vec3_t<T> wo = glm::normalize(vec3_t<T>(0.3, -0.5, 0.8));
  std::uint64_t seed = std::is_same_v<T, float> ? 100 : 200;
  for (const double g : {-0.9, 0.0, 0.5, 0.99}) {
    const phase_t<T> ph{T(g)};
    rng gen(++seed);
    bool pdf_is_value = true;
    // Bins around the peak (forward for g > 0, backward for g < 0). A strong peak (|g| >= 0.9:
    // most of the light within a few degrees) gets a finely binned cap, the rest of the sphere
    // being the extra bin.
    const onb_t<T> frame(g < 0 ? wo : -wo);
    const grid2 grid = std::abs(g) >= 0.9 ? direction_grid(40, 20, std::abs(g)) : direction_grid(20, 40);
    const auto r = chi_square_directions(
        [&]() {
          const auto s = ph.sample(wo, vec2_t<T>(T(gen.uniform()), T(gen.uniform())));
          pdf_is_value = pdf_is_value && std::abs(double(s.pdf - ph.eval(wo, s.wi))) <= 1e-6 * double(s.pdf);
          return frame.to_local(s.wi);
        },
        [&](const vec3& local) { return double(ph.eval(wo, frame.to_world(vec3_t<T>(local)))); }, 200000, grid, 32);
    std::string label = "g = " + std::to_string(g);
    label += std::is_same_v<T, float> ? " <float>" : " <double>";
    MESSAGE(label << ": X^2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.p_value);
    CHECK(pdf_is_value);
    CHECK(r.impossible == 0);
    CHECK(r.p_value > level);
  }
}

TEST_CASE("phase: sample_hg_cos stays in [-1, 1] at the ends of u and near g = 0") {
  for (const double g : {-0.999, -1e-4, 1e-4, 1e-3, 0.999})
    for (const double u : {0.0, 1e-17, 0.5, one_minus_epsilon<double>}) {
      const double c = sample_hg_cos(u, g);
      CHECK(c >= -1);
      CHECK(c <= 1);
    }
  CHECK(sample_hg_cos(0.0, 0.5) == doctest::Approx(-1));
  CHECK(sample_hg_cos(one_minus_epsilon<double>, 0.5) == doctest::Approx(1));
}

// bxdf.hpp: the clamped Phong and Blinn-Phong terms (erratum A6), and the BRDFs' energy (white
// furnace), sampling (chi-square against pdf()), reciprocity and path weights.
#include <doctest/doctest.h>

#include <sstream>
#include <zraka/app/chi_square.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/bxdf.hpp>

using namespace zraka;

namespace {

template <class T>
constexpr T eps = std::numeric_limits<T>::epsilon();

template <class T>
vec2_t<T> uniform2(rng& g) {
  if constexpr (std::is_same_v<T, float>)
    return {g.uniform_float(), g.uniform_float()};
  else
    return g.uniform2();
}

// wo at angle theta from a tilted normal n (the frame is arbitrary, so nothing relies on +z).
template <class T>
vec3_t<T> direction_at(const vec3_t<T>& n, double theta, double phi) {
  const onb frame{vec3(n)};
  return vec3_t<T>(frame.to_world(
      vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta))));
}

// Monte Carlo albedo a(wo) = int f cos dw = E[f cos / pdf] with the BRDF's own sampling (a
// rejected sample contributes 0), for the first colour channel; returns mean and standard error.
template <class T, class B>
std::pair<double, double> albedo(const B& f, const vec3_t<T>& wo, const vec3_t<T>& n, int count,
                                 std::uint64_t seed) {
  rng g(seed);
  double sum = 0, sum2 = 0;
  for (int i = 0; i < count; ++i) {
    const auto s = f.sample(wo, n, uniform2<T>(g));
    const double w = s ? double(s->weight.x) : 0.0;
    sum += w;
    sum2 += w * w;
  }
  const double mean = sum / count, var = std::max(0.0, sum2 / count - mean * mean);
  return {mean, std::sqrt(var / count)};
}

}  // namespace

TEST_CASE_TEMPLATE("Phong and Blinn-Phong terms are clamped (erratum A6)", T, float, double) {
  const vec3_t<T> n(0, 0, 1);
  const vec3_t<T> l = glm::normalize(vec3_t<T>(1, 0, 1));
  const vec3_t<T> v_mirror = glm::normalize(vec3_t<T>(-1, 0, 1));
  // At the mirror configuration R = V and H = N: both highlights are 1; the diffuse term is cos 45.
  for (const auto& k :
       {phong_terms(n, l, v_mirror, T(17)), blinn_phong_terms(n, l, v_mirror, T(17))}) {
    CHECK(double(k.diffuse) == doctest::Approx(std::sqrt(0.5)).epsilon(1e-6));
    CHECK(double(k.specular) == doctest::Approx(1).epsilon(1e-5));
  }
  // Light behind the surface: nothing, not negative light and no highlight.
  const vec3_t<T> behind = glm::normalize(vec3_t<T>(1, 0, -1));
  for (const auto& k :
       {phong_terms(n, behind, v_mirror, T(2)), blinn_phong_terms(n, behind, v_mirror, T(2))}) {
    CHECK(k.diffuse == T(0));
    CHECK(k.specular == T(0));
  }
  // Viewer opposite the mirror direction (V.R < 0): an odd exponent must not give negative
  // light and an even one must not give a spurious highlight.
  const vec3_t<T> v_away = glm::normalize(vec3_t<T>(1, 0, -0.2));
  CHECK(phong_terms(n, l, v_away, T(3)).specular == T(0));
  CHECK(phong_terms(n, l, v_away, T(2)).specular == T(0));
  // Light exactly opposite the viewer: H is zero, no highlight, no NaN.
  CHECK(blinn_phong_terms(n, l, -l, T(8)).specular == T(0));
  // Assembling I = I_a rho_a + I (rho_d N.L + rho_s (V.R)^p), with scalars and with colours.
  const phong_material_t<T, T> m{T(0.1), T(0.6), T(0.3), T(17)};
  const auto k = phong_terms(n, l, v_mirror, m.p);
  CHECK(double(phong_shade(m, k, T(2), T(0.5))) ==
        doctest::Approx(0.5 * 0.1 + 2 * (0.6 * std::sqrt(0.5) + 0.3)).epsilon(1e-5));
  const phong_material_t<T> mc;
  const vec3_t<T> c = phong_shade(mc, k, vec3_t<T>(1), vec3_t<T>(0));
  CHECK(c.x == c.y);
}

TEST_CASE("the unnormalised Phong lobe of the thesis does not conserve energy (erratum C3)") {
  // Its albedo at normal incidence, int rho_s cos^p(alpha) cos(theta) dw = 2 pi rho_s / (p+2):
  // above 1 for p < 2 pi - 2 with rho_s = 1, and almost nothing for shiny surfaces.
  for (double p : {1.0, 2.0, 4.0, 10.0, 100.0}) {
    const int m = 20000;
    double a = 0;  // midpoint rule over cos(theta) in [0,1]
    for (int i = 0; i < m; ++i) {
      const double c = (i + 0.5) / m;
      a += std::pow(c, p) * c * 2 * pi<double> / m;
    }
    MESSAGE("unnormalised Phong, p = " << p << ": albedo at normal incidence = " << a);
    CHECK(a == doctest::Approx(2 * pi<double> / (p + 2)).epsilon(1e-6));
  }
}

TEST_CASE_TEMPLATE("Lambert: f = rho/pi, the weight with cosine sampling is exactly rho", T, float,
                   double) {
  const vec3_t<T> n = glm::normalize(vec3_t<T>(0.3, -0.2, 1));
  const lambert_brdf_t<T> f{vec3_t<T>(0.2, 0.5, 0.9)};
  const vec3_t<T> wo = direction_at(n, 0.7, 1.0);
  rng g(1);
  for (int i = 0; i < 1000; ++i) {
    const auto s = f.sample(wo, n, uniform2<T>(g));
    REQUIRE(s);
    CHECK(s->weight == f.rho);  // exactly, by construction
    // Recomputed: f cos / pdf = rho within 4 ulps (a dot product shared by cos and pdf, and
    // the 1/pi that cancels).
    const vec3_t<T> w = f.eval(s->wi, wo, n) * glm::dot(s->wi, n) / f.pdf(s->wi, wo, n);
    for (int c = 0; c < 3; ++c) CHECK(std::abs(w[c] - f.rho[c]) <= 4 * eps<T> * f.rho[c]);
    CHECK(s->pdf == f.pdf(s->wi, wo, n));
  }
  CHECK(f.eval(-wo, wo, n) == vec3_t<T>(0));           // no transmission
  CHECK(!f.sample(-n, n, vec2_t<T>(T(0.5), T(0.5))));  // viewer below the surface
}

TEST_CASE_TEMPLATE(
    "the normalised Phong BRDF: reciprocal, rho_s at normal incidence, pdf consistent", T, float,
    double) {
  const vec3_t<T> n = glm::normalize(vec3_t<T>(-0.4, 0.1, 1));
  rng g(2);
  for (T s : {T(1), T(10), T(1000)}) {
    const phong_brdf_t<T> f{vec3_t<T>(0.8), s};
    for (int i = 0; i < 200; ++i) {
      const vec3_t<T> a = direction_at(n, 1.5 * g.uniform(), 6.28 * g.uniform());
      const vec3_t<T> b = direction_at(n, 1.5 * g.uniform(), 6.28 * g.uniform());
      // Helmholtz reciprocity f(a, b) = f(b, a). cos^s turns an absolute rounding error of
      // 8 eps in cos(alpha) into a relative error s 8 eps / cos(alpha) in f.
      const double fab = double(f.eval(a, b, n).x), fba = double(f.eval(b, a, n).x);
      const double c = std::max(1e-3, double(glm::dot(a, reflect(-b, n))));
      CHECK(std::abs(fab - fba) <= double(s) * 8 * eps<T> / c * std::max(fab, fba));
    }
    // The sample's pdf and f are those of pdf() and eval(); the weight is f cos / pdf.
    const vec3_t<T> wo = direction_at(n, 0.5, 2.0);
    for (int i = 0; i < 200; ++i) {
      const auto r = f.sample(wo, n, uniform2<T>(g));
      if (!r) continue;
      CHECK(r->pdf == f.pdf(r->wi, wo, n));
      CHECK(r->f == f.eval(r->wi, wo, n));
      CHECK(double(r->weight.x) ==
            doctest::Approx(double(r->f.x * glm::dot(r->wi, n) / r->pdf)).epsilon(1e-4));
    }
  }
}

TEST_CASE_TEMPLATE("white furnace: every BRDF reflects at most what arrives", T, float, double) {
  // rho = 1 (white). The albedo int f cos dw is estimated with the BRDF's own sampling,
  // 20000 samples per configuration; the check allows 4 standard errors (the estimates are
  // averages of bounded weights, so the normal approximation holds). Sweep: shininess 1..1e4,
  // view angles 0..89 degrees.
  const vec3_t<T> n = glm::normalize(vec3_t<T>(0.2, 0.1, 1));
  const int count = 20000;
  std::uint64_t seed = 100;
  std::ostringstream table;
  const double angles[] = {0, 30, 60, 80, 89};
  const double shininess[] = {1, 2, 5, 10, 100, 1e3, 1e4};

  // Lambert: every weight is exactly rho, so the estimate is exactly 1.
  {
    const lambert_brdf_t<T> f{vec3_t<T>(1)};
    double worst = 0;
    for (double deg : angles) {
      const auto [a, se] =
          albedo<T>(f, direction_at(n, deg * pi<double> / 180, 0.3), n, count, seed++);
      worst = std::max(worst, a);
      CHECK(a == 1);
    }
    table << "Lambert rho=1: max albedo " << worst << "\n";
  }
  // Normalised Phong: albedo <= 1 everywhere, = 1 at normal incidence for every shininess.
  {
    double worst = 0;
    for (double s : shininess) {
      const phong_brdf_t<T> f{vec3_t<T>(1), T(s)};
      for (double deg : angles) {
        const auto [a, se] =
            albedo<T>(f, direction_at(n, deg * pi<double> / 180, 0.3), n, count, seed++);
        worst = std::max(worst, a);
        CHECK(a <= 1 + 4 * se + 1e-6);
        if (deg == 0) CHECK(a == doctest::Approx(1).epsilon(4 * se + 1e-4));
      }
    }
    table << "normalised Phong rho_s=1, s=1..1e4: max albedo " << worst << "\n";
  }
  // Lambert + Phong with rho_d + rho_s = 1.
  {
    double worst = 0;
    for (double rd : {0.1, 0.5, 0.9})
      for (double s : shininess) {
        const lambert_phong_brdf_t<T> f{lambert_brdf_t<T>{vec3_t<T>(T(rd))},
                                        phong_brdf_t<T>{vec3_t<T>(T(1 - rd)), T(s)}};
        for (double deg : angles) {
          const auto [a, se] =
              albedo<T>(f, direction_at(n, deg * pi<double> / 180, 0.3), n, count, seed++);
          worst = std::max(worst, a);
          CHECK(a <= 1 + 4 * se + 1e-6);
          if (deg == 0) CHECK(a == doctest::Approx(1).epsilon(4 * se + 1e-4));
        }
      }
    table << "Lambert + Phong, rho_d + rho_s = 1: max albedo " << worst << "\n";
  }
  MESSAGE(table.str());
}

TEST_CASE_TEMPLATE(
    "an independent estimate of the Phong albedo agrees with the importance-sampled one", T, float,
    double) {
  // Uniform hemisphere sampling knows nothing of the lobe: int f cos dw = E[2 pi f cos]. Its
  // variance grows with the shininess, so this runs for s <= 20 with 200000 samples; the two
  // estimates must agree within 4 combined standard errors.
  const vec3_t<T> n(0, 0, 1);
  for (double s : {1.0, 5.0, 20.0})
    for (double deg : {0.0, 45.0, 80.0}) {
      const phong_brdf_t<T> f{vec3_t<T>(1), T(s)};
      const vec3_t<T> wo = direction_at(n, deg * pi<double> / 180, 0.0);
      const auto [a, se] = albedo<T>(f, wo, n, 200000, 7);
      rng g(8);
      double sum = 0, sum2 = 0;
      const int m = 200000;
      for (int i = 0; i < m; ++i) {
        const vec3_t<T> wi = sample_uniform_hemisphere(uniform2<T>(g));
        const double w = double(f.eval(wi, wo, n).x) * double(wi.z) * 2 * pi<double>;
        sum += w;
        sum2 += w * w;
      }
      const double b = sum / m, se_b = std::sqrt(std::max(0.0, sum2 / m - b * b) / m);
      CHECK(std::abs(a - b) <= 4 * std::hypot(se, se_b));
    }
}

TEST_CASE_TEMPLATE("each BRDF's sample() follows its pdf() (chi-square)", T, float, double) {
  // 4 tests per type, 8 in all: Sidak level for 1% overall. Directions are binned in the
  // normal's frame over the whole sphere; samples a BRDF rejects (below the surface) form one
  // more bin, expected to hold the probability the pdf puts below the horizon.
  const double level = sidak_level(0.01, 8);
  const vec3_t<T> n = glm::normalize(vec3_t<T>(0.3, 0.2, 1));
  const onb_t<T> frame(n);
  auto run = [&](const char* what, const auto& f, double theta_o, std::uint64_t seed) {
    const vec3_t<T> wo = direction_at(n, theta_o, 0.5);
    rng g(seed);
    const auto r = chi_square_directions(
        [&]() -> std::optional<vec3_t<T>> {
          const auto s = f.sample(wo, n, uniform2<T>(g));
          if (!s) return std::nullopt;
          return frame.to_local(s->wi);
        },
        [&](const vec3& local) { return double(f.pdf(frame.to_world(vec3_t<T>(local)), wo, n)); },
        200000, direction_grid(20, 40), 16);
    std::string label = what;  // appended, not "+": GCC 12's -Warray-bounds misfires on the temporary
    label += std::is_same_v<T, float> ? " <float>" : " <double>";
    MESSAGE(label << ": X^2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.p_value);
    CHECK(r.impossible == 0);
    CHECK(r.p_value > level);
  };
  run("Lambert", lambert_brdf_t<T>{vec3_t<T>(0.7)}, 0.4, 10);
  run("Phong s=1, 30 deg", phong_brdf_t<T>{vec3_t<T>(0.7), T(1)}, 0.52, 11);
  run("Phong s=20, 70 deg (lobe cut by the horizon)", phong_brdf_t<T>{vec3_t<T>(0.7), T(20)}, 1.22,
      12);
  run("Lambert + Phong s=20, 45 deg",
      lambert_phong_brdf_t<T>{lambert_brdf_t<T>{vec3_t<T>(0.5)},
                              phong_brdf_t<T>{vec3_t<T>(0.4), T(20)}},
      0.785, 13);
}

// A Lambertian material's BRDF is a lambert_phong_brdf_t without a glossy part (material.hpp's
// brdf_at); eval and pdf then skip the lobe. The shortcut must give the full formula's bits: the
// diffuse term plus a zero lobe, and the mixture with the lobe's weight 0.
TEST_CASE_TEMPLATE("bxdf: lambert_phong without a glossy part is the mixture's numbers exactly", T, float, double) {
  const lambert_phong_brdf_t<T> f{lambert_brdf_t<T>{vec3_t<T>(T(0.73), T(0.5), T(0.1))},
                                  phong_brdf_t<T>{vec3_t<T>(0), T(32)}};
  const vec3_t<T> n = normalize_or_zero(vec3_t<T>(T(0.2), T(1), T(-0.3)));
  rng g(11);
  for (int i = 0; i < 2000; ++i) {
    const vec3_t<T> wo = normalize_or_zero(vec3_t<T>(vec3(g.uniform(), g.uniform(), g.uniform()) - 0.5));
    const vec3_t<T> wi = normalize_or_zero(vec3_t<T>(vec3(g.uniform(), g.uniform(), g.uniform()) - 0.5));
    CHECK(f.eval(wi, wo, n) == f.diffuse.eval(wi, wo, n) + f.glossy.eval(wi, wo, n));
    const T full = same_hemisphere(wi, wo, n) ? f.density(wo, n).pdf(wi) : T(0);
    CHECK(f.pdf(wi, wo, n) == full);
  }
}

// reflect, fuzzy_mirror, refract, Fresnel and Schlick (optics.hpp): Snell's law, unit and
// coplanar directions, total internal reflection exactly where eta sin(theta) > 1, energy
// R + T = 1 with R in [0,1], the extremes (normal, grazing, critical +- 1e-6 rad and a few ulps,
// eta = 1e-4 .. 1e4), and the popular "diffuse" shortcuts' true distributions (book 1.7).
#include <doctest/doctest.h>

#include <iomanip>
#include <sstream>
#include <zraka/app/chi_square.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/sampling/sampling.hpp>

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

// A unit incident direction making angle theta with -n, in a random plane containing n.
template <class T>
vec3_t<T> incident(const onb& frame, double theta, double phi) {
  const vec3 local(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi),
                   -std::cos(theta));
  return vec3_t<T>(frame.to_world(local));
}

// sin of the angle between a direction and the normal's line, |w x n| / (|w| |n|), in long
// double: products of floats and doubles are then (nearly) exact, and the cross product has no
// cancellation near the normal, where sqrt(1 - cos^2) would lose everything.
template <class T>
long double sin_to_normal(const vec3_t<T>& w, const vec3_t<T>& n) {
  using L = long double;
  const L cx = L(w.y) * n.z - L(w.z) * n.y, cy = L(w.z) * n.x - L(w.x) * n.z,
          cz = L(w.x) * n.y - L(w.y) * n.x;
  const L lw = std::sqrt(L(w.x) * w.x + L(w.y) * w.y + L(w.z) * w.z);
  const L ln = std::sqrt(L(n.x) * n.x + L(n.y) * n.y + L(n.z) * n.z);
  return std::sqrt(cx * cx + cy * cy + cz * cz) / (lw * ln);
}

}  // namespace

TEST_CASE_TEMPLATE("reflect flips the normal component and keeps the rest", T, float, double) {
  rng g(1);
  for (int i = 0; i < 1000; ++i) {
    const vec3_t<T> n = sample_uniform_sphere(uniform2<T>(g));
    const vec3_t<T> d = sample_uniform_sphere(uniform2<T>(g));
    const vec3_t<T> r = reflect(d, n);
    // 8 eps: a dot product, a multiply-add and the unit inputs' own rounding.
    CHECK(std::abs(glm::length(r) - T(1)) <= 8 * eps<T>);
    CHECK(std::abs(glm::dot(r, n) + glm::dot(d, n)) <= 8 * eps<T>);
    CHECK(glm::length(reflect(r, n) - d) <= 16 * eps<T>);  // an involution
    CHECK(glm::length(reflect(d, -n) - r) <= 8 * eps<T>);  // either side of the normal
    CHECK(glm::length((r - glm::dot(r, n) * n) - (d - glm::dot(d, n) * n)) <= 16 * eps<T>);
  }
  // Normal incidence returns straight back.
  CHECK(reflect(vec3_t<T>(0, 0, -1), vec3_t<T>(0, 0, 1)) == vec3_t<T>(0, 0, 1));
}

TEST_CASE_TEMPLATE("fuzzy_mirror: fuzz 0 is the mirror, never below the surface, always unit", T,
                   float, double) {
  const vec3_t<T> n(0, 0, 1);
  rng g(2);
  int none = 0;
  for (int i = 0; i < 4000; ++i) {
    const vec3_t<T> d = incident<T>(onb(vec3(0, 0, 1)), (i % 90) * pi<double> / 180, i * 0.1);
    const vec2_t<T> a = uniform2<T>(g);
    const vec3_t<T> ball = sample_unit_ball(vec3_t<T>(a.x, a.y, uniform2<T>(g).x));
    const auto m0 = fuzzy_mirror(d, n, T(0), ball);
    if (d.z < T(0)) {
      REQUIRE(m0);
      CHECK(glm::length(*m0 - reflect(d, n)) <= 8 * eps<T>);
    }
    const auto m = fuzzy_mirror(d, n, T(1), ball);
    if (!m) {
      ++none;
      continue;
    }
    CHECK(glm::dot(*m, n) > T(0));  // B8: the thesis's version can point into the surface
    CHECK(std::abs(glm::length(*m) - T(1)) <= 4 * eps<T>);
  }
  MESSAGE("fuzz 1, incidence 0..89 deg: " << none << " of 4000 below the surface (absorbed)");
  CHECK(none > 0);  // they exist, especially near grazing incidence
  // fuzz 0 at grazing incidence (d in the surface) has no reflection: none, not a tangent ray.
  CHECK(!fuzzy_mirror(vec3_t<T>(1, 0, 0), n, T(0), vec3_t<T>(0)));
}

TEST_CASE("the 'diffuse' shortcuts and their true distributions (book 1.7, erratum C1)") {
  // chi-square against the Lambertian (cosine) pdf; 4 tests, Sidak level for 1%.
  const double level = sidak_level(0.01, 4);
  const vec3 n(0, 0, 1);
  auto test = [&](const char* what, auto sample, bool lambertian) {
    rng g(3);
    double mean_cos = 0;
    const long count = 100000;
    const auto r = chi_square_directions(
        [&]() -> std::optional<vec3> {
          const auto w = sample(g);
          if (w) mean_cos += w->z / count;
          return w;
        },
        [](const vec3& w) { return cosine_hemisphere_pdf(w); }, count, direction_grid(20, 20));
    MESSAGE(std::string(what) << ": mean cos(theta) = " << mean_cos
                              << " (Lambertian: 2/3), p = " << r.p_value);
    if (lambertian)
      CHECK(r.p_value > level);
    else
      CHECK(r.p_value < level);
  };
  auto ball = [](rng& g) { return sample_unit_ball(vec3(g.uniform(), g.uniform(), g.uniform())); };
  // RTIOW's Lambertian: normal + a random *unit* vector is exactly cosine-distributed.
  test(
      "normal + random unit vector",
      [](rng& g) -> std::optional<vec3> {
        const vec3 w = normalize_or_zero(vec3(0, 0, 1) + sample_uniform_sphere(g.uniform2()));
        return length2(w) > 0 ? std::optional<vec3>(w) : std::nullopt;
      },
      true);
  // normal + a random point *in* the ball: more peaked towards the normal than cosine.
  test(
      "normal + random in unit ball",
      [&](rng& g) -> std::optional<vec3> {
        const vec3 w = normalize_or_zero(vec3(0, 0, 1) + ball(g));
        return length2(w) > 0 ? std::optional<vec3>(w) : std::nullopt;
      },
      false);
  // The thesis's "diffuse" (fuzzy mirror, fuzz 1) at 45 degrees: centred on the mirror direction.
  const vec3 d45 = glm::normalize(vec3(1, 0, -1));
  test(
      "fuzzy mirror, fuzz 1, 45 deg", [&](rng& g) { return fuzzy_mirror(d45, n, 1.0, ball(g)); },
      false);
  // Even at normal incidence, where it is centred on n, it is not Lambertian.
  test(
      "fuzzy mirror, fuzz 1, normal incidence",
      [&](rng& g) { return fuzzy_mirror(vec3(0, 0, -1), n, 1.0, ball(g)); }, false);
}

TEST_CASE_TEMPLATE("refract obeys Snell's law over a sweep of angles and eta from 1e-4 to 1e4", T,
                   float, double) {
  rng g(4);
  int transmitted = 0, tir = 0;
  for (double eta : {1e-4, 0.5, 1 / 1.5, 1.0, 1.33, 1.5, 2.4, 1e4}) {
    const T e = T(eta);
    // 0 .. 90 deg in half degrees, then for eta > 1 twenty angles below the critical one
    // (for eta = 1e4 all transmission happens within 0.006 deg of the normal).
    for (int k = 0; k <= 200; ++k) {
      if (k > 180 && eta <= 1) break;
      const vec3 nd = sample_uniform_sphere(g.uniform2());
      const vec3_t<T> n(nd);
      const onb frame{vec3(n)};
      const double theta = k > 180    ? std::asin((k - 180) / (21 * eta))
                           : k == 180 ? pi<double> / 2
                                      : k * pi<double> / 360;
      const vec3_t<T> d = incident<T>(frame, theta, 7.0 * k);
      const long double s_i = sin_to_normal(d, n);
      const long double x = (long double)e * s_i;  // eta sin(theta_i), from the actual inputs
      const auto t = refract(d, n, e);
      const T cos_i = -glm::dot(d, n);
      const T R = fresnel_dielectric(cos_i, e);
      REQUIRE(std::isfinite(R));
      CHECK(R >= T(0));
      CHECK(R <= T(1));
      // Away from the critical angle (|x - 1| above a few roundings scaled by eta) the decision
      // must be exact; right at it, see the next test.
      const long double margin = 16.0L * eps<T> * (1 + eta);
      if (x > 1 + margin) {
        CHECK(!t);
        CHECK(R == T(1));  // all light is reflected: T = 1 - R = 0
        ++tir;
        continue;
      }
      if (x < 1 - margin) REQUIRE(t);
      if (!t) continue;
      ++transmitted;
      // The transmitted direction: unit (it is renormalised: 4 eps), on the far side,
      // in the plane of d and n, and sin(theta_t) = eta sin(theta_i) (Snell), within
      // 16 eps (1 + eta): sin(theta_i) carries the inputs' rounding, and eta magnifies it.
      CHECK(is_finite(*t));
      CHECK(std::abs(glm::length(*t) - T(1)) <= 4 * eps<T>);
      CHECK(glm::dot(*t, n) <= 4 * eps<T>);  // at grazing with eta = 1, t lies in the surface
      const long double tol = 16.0L * eps<T> * (1 + eta);
      CHECK(std::abs(sin_to_normal(*t, n) - x) <= tol);
      const vec3 cr = glm::cross(vec3(d), vec3(n));
      CHECK(std::abs(glm::dot(cr, vec3(*t))) <= double(tol));
      // Energy: R + T = 1 with T = 1 - R in [0,1]; reciprocity (Stokes): the reflectance is
      // the same seen from the other side at the transmitted angle (1e-4: float rounding
      // amplified near grazing).
      const T cos_t = -glm::dot(*t, n);
      if (eta >= 1e-3 && eta <= 1e3 && cos_i > T(1e-3) && cos_t > T(1e-3))
        CHECK(double(fresnel_dielectric(cos_t, T(1) / e)) ==
              doctest::Approx(double(R)).epsilon(1e-4).scale(1));
    }
  }
  MESSAGE("transmitted " << transmitted << ", total internal reflection " << tir);
  CHECK(tir > 0);
}

TEST_CASE_TEMPLATE("normal incidence, eta = 1 and grazing incidence", T, float, double) {
  const vec3_t<T> n(0, 0, 1), down(0, 0, -1);
  for (T eta : {T(1e-4), T(1) / T(1.5), T(1), T(1.5), T(1e4)}) {
    const auto t = refract(down, n, eta);
    REQUIRE(t);
    CHECK(*t == down);  // straight through, any eta
    // R at normal incidence: ((1 - eta)/(1 + eta))^2 (relative 1e-5 for float).
    const double r0 = std::pow((1 - double(eta)) / (1 + double(eta)), 2);
    CHECK(double(fresnel_dielectric(T(1), eta)) == doctest::Approx(r0).epsilon(1e-5));
    CHECK(double(fresnel_schlick(T(1), eta)) == doctest::Approx(r0).epsilon(1e-5));
  }
  // Matching media: no bending, no reflection, at every angle including grazing.
  rng g(5);
  for (int i = 0; i <= 90; ++i) {
    const vec3_t<T> d =
        incident<T>(onb(vec3(n)), (i == 90 ? pi<double> / 2 : i * pi<double> / 180), 0.3 * i);
    const auto t = refract(d, n, T(1));
    REQUIRE(t);
    CHECK(glm::length(*t - d) <= 8 * eps<T>);
    CHECK(fresnel_dielectric(-glm::dot(d, n), T(1)) == T(0));
  }
  // Grazing (d in the surface): into a denser medium the ray bends to the critical angle,
  // sin(theta_t) = eta; out of it, total internal reflection; R = 1 in both limits.
  const vec3_t<T> graze(1, 0, 0);
  const auto in = refract(graze, n, T(1) / T(1.5));
  REQUIRE(in);
  CHECK(double(std::hypot(in->x, in->y)) == doctest::Approx(1 / 1.5).epsilon(1e-6));
  CHECK(!refract(graze, n, T(1.5)));
  CHECK(fresnel_dielectric(T(0), T(1) / T(1.5)) == T(1));
  CHECK(fresnel_dielectric(T(0), T(1.5)) == T(1));
  CHECK(fresnel_schlick(T(0), T(1) / T(1.5)) == T(1));
  // A cos(theta_i) a rounding above one (or below zero) is clamped, not passed to sqrt.
  CHECK(refract(vec3_t<T>(0, 0, -1) * (T(1) + eps<T>), n, T(1.5)).has_value());
  CHECK(std::isfinite(fresnel_dielectric(T(1) + eps<T>, T(1.5))));
  CHECK(fresnel_dielectric(T(-0.1), T(1.5)) == T(1));  // treated as grazing
}

TEST_CASE_TEMPLATE("the critical angle: 41.8 deg for glass to air, TIR exactly beyond it", T, float,
                   double) {
  const T eta = T(1.5);
  const auto crit = critical_angle(eta);
  REQUIRE(crit);
  CHECK(double(*crit) * 180 / pi<double> == doctest::Approx(41.8103).epsilon(1e-5));
  CHECK(!critical_angle(T(1)));
  CHECK(!critical_angle(T(1) / T(1.5)));
  const vec3_t<T> n(0, 0, 1);
  const double tc = std::asin(1 / 1.5);
  auto dir = [](double theta) { return vec3_t<T>(T(std::sin(theta)), 0, T(-std::cos(theta))); };
  // 1e-6 rad either side: eta sin(theta) - 1 = +-1.1e-6, far above the rounding (a few 1e-8).
  CHECK(refract(dir(tc - 1e-6), n, eta).has_value());
  CHECK(!refract(dir(tc + 1e-6), n, eta).has_value());
  const auto just = refract(dir(tc - 1e-6), n, eta);
  REQUIRE(just);
  CHECK(std::abs(glm::length(*just) - T(1)) <= 4 * eps<T>);
  CHECK(just->z <= T(0));
  CHECK(just->z > T(-0.01));  // almost tangent: theta_t = 90 deg - 0.1 deg or so
  CHECK(fresnel_dielectric(T(std::cos(tc + 1e-6)), eta) == T(1));
  CHECK(fresnel_dielectric(T(std::cos(tc - 1e-6)), eta) > T(0.9));  // R rises steeply to 1
  // A few ulps either side of the critical direction: the answer agrees with eta sin(theta)
  // computed exactly from the actual (rounded) input, up to the rounding of that product.
  vec3_t<T> d = dir(tc);
  for (int k = -4; k <= 4; ++k) {
    vec3_t<T> dk = d;
    for (int j = 0; j < std::abs(k); ++j) dk.x = std::nextafter(dk.x, k > 0 ? T(1) : T(0));
    const long double x = 1.5L * sin_to_normal(dk, n);
    const auto t = refract(dk, n, eta);
    if (t) {
      CHECK(x <= 1 + 8.0L * eps<T>);
      CHECK(is_finite(*t));
      CHECK(std::abs(glm::length(*t) - T(1)) <= 4 * eps<T>);
    } else {
      CHECK(x >= 1 - 8.0L * eps<T>);
    }
  }
}

TEST_CASE_TEMPLATE(
    "a slab: in through the front face, out through the back, the direction is restored", T, float,
    double) {
  // The slab's outward normals are +z (top) and -z (bottom); the hit record's face flag and
  // facing_normal() give the normal and relative_ior() the eta at each face.
  rng g(6);
  for (int i = 0; i < 200; ++i) {
    const vec3_t<T> d = incident<T>(onb(vec3(0, 0, 1)), 1.5 * g.uniform(), 6.28 * g.uniform());
    hit_t<T> top;
    top.normal = vec3_t<T>(0, 0, 1);
    top.set_face(d);
    REQUIRE(top.front_face);
    const auto inside = refract(d, top.facing_normal(), relative_ior(top.front_face, T(1.5)));
    REQUIRE(inside);  // entering the denser medium never reflects totally
    hit_t<T> bottom;
    bottom.normal = vec3_t<T>(0, 0, -1);
    bottom.set_face(*inside);
    REQUIRE(!bottom.front_face);
    const auto out =
        refract(*inside, bottom.facing_normal(), relative_ior(bottom.front_face, T(1.5)));
    REQUIRE(out);  // parallel faces: the inside angle is below the critical angle
    // 64 eps: two refractions, each magnifying the direction's rounding by up to
    // cos(theta_i)/cos(theta_t) (about 7 at 86 deg).
    CHECK(glm::length(*out - d) <= 64 * eps<T>);
  }
  CHECK(relative_ior(true, 1.5) == doctest::Approx(1 / 1.5));
  CHECK(relative_ior(false, 1.5) == 1.5);
  CHECK(relative_ior(true, 1.5, 1.33) == doctest::Approx(1.33 / 1.5));
}

TEST_CASE("Schlick's approximation against the exact Fresnel reflectance") {
  // Max |Schlick - exact| over 0..90 deg in 1e-3 degree steps. "naive" uses cos(theta_i) also
  // when leaving the denser medium, as many renderers do: it misses TIR altogether.
  std::ostringstream table;
  table << std::fixed << std::setprecision(4)
        << "eta = n_i/n_t      | max |Schlick - exact| | at theta_i | naive (cos_i) max error\n";
  double worst_in = 0, worst_out = 0;
  for (double eta : {1 / 1.5, 1.5}) {
    double err = 0, at = 0, naive_err = 0;
    const int steps = 90000;
    for (int k = 0; k <= steps; ++k) {
      const double theta = k * (pi<double> / 2) / steps, c = std::cos(theta);
      const double exact = fresnel_dielectric(c, eta);
      const double e = std::abs(fresnel_schlick(c, eta) - exact);
      const double r0 = std::pow((1 - eta) / (1 + eta), 2);
      const double naive = r0 + (1 - r0) * std::pow(1 - c, 5);
      if (e > err) err = e, at = theta * 180 / pi<double>;
      naive_err = std::max(naive_err, std::abs(naive - exact));
    }
    table << (eta < 1 ? "1/1.5 (air->glass) | " : "1.5 (glass->air)   | ") << std::setw(21) << err
          << " | " << std::setw(6) << at << " deg | " << naive_err << "\n";
    (eta < 1 ? worst_in : worst_out) = err;
  }
  MESSAGE(table.str());
  // Measured: 0.0357 both ways (into glass near grazing, out of it just below the critical
  // angle: the same function of the angle on the air side). Guard it so that a regression
  // (e.g. the naive cosine, error 0.96) is caught.
  CHECK(worst_in < 0.04);
  CHECK(worst_out < 0.04);
}

// Assignment 03 tests: the Oren–Nayar BRDF as a zraka::custom_bsdf, in a white furnace. Built
// twice by book/assignments/CMakeLists.txt, against student/oren_nayar.hpp (must fail) and
// solution/oren_nayar.hpp (must pass).
#include "oren_nayar.hpp"

#include <zraka/app/testing.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/materials/material.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>

using namespace zraka;
using course::oren_nayar;
namespace zt = zraka::testing;

namespace {

const vec3 up(0, 0, 1);  // the normal of the local frame
const bsdf_frame F = bsdf_frame::around(vec3(0), vec2(0), up, true);  // the frame around it

vec3 at_angle(double theta_degrees) {
  const double t = theta_degrees * pi<double> / 180;
  return vec3(std::sin(t), 0, std::cos(t));
}

// The directional albedo a(wo) = integral over the hemisphere of f(wo, wi) cos(theta_i) dwi, of
// the red channel (rho = 1), by the midpoint rule on 100 x 32 bins (x 64 points each).
double albedo(const oren_nayar& f, const vec3& wo) {
  return zt::pdf_integral_over_directions(
      [&](const vec3& wi) { return f.eval(F, wo, wi).x * std::max(0.0, wi.z); }, 100, 32, 0.0);
}

double A_of(double sigma) { return 1 - sigma * sigma / (2 * (sigma * sigma + 0.33)); }
double B_of(double sigma) { return 0.45 * sigma * sigma / (sigma * sigma + 0.09); }

const double angles[] = {0, 30, 60, 80, 89.9};

}  // namespace

TEST_CASE("oren-nayar: white furnace on the BRDF, sigma = 0 is Lambert and loses nothing") {
  // rho = 1, sigma = 0: f = 1/pi, the albedo is 1 at every angle. The midpoint rule integrates
  // cos exactly; 1e-3 leaves room for nothing but rounding.
  const oren_nayar f(vec3(1), 0.0);
  for (double t : angles) {
    const double a = albedo(f, at_angle(t));
    CHECK_MESSAGE(std::abs(a - 1) < 1e-3, "theta_o " << t << " deg: albedo " << a << ", expected 1");
  }
  CHECK_MESSAGE(f.eval(F, at_angle(40), at_angle(-70)).x == doctest::Approx(1 / pi<double>),
                "f must be rho/pi for sigma = 0");
}

TEST_CASE("oren-nayar: white furnace on the BRDF for sigma > 0") {
  // What the model promises for sigma > 0 (rho = 1):
  //  - at normal incidence (theta_o = 0) the B term vanishes (tan beta = 0): albedo = A exactly;
  //  - the B term only adds, and sin(alpha) tan(beta) cos(theta_i) <= sin(theta_i), so
  //    A <= albedo <= A + B/2, the upper bound reached at grazing theta_o;
  //  - the albedo grows towards grazing (rough surfaces look flatter: back-scattering), and at
  //    normal incidence it falls as sigma grows.
  //  - albedo <= 1 for sigma >= 0.5. This qualitative form is not energy conserving
  //    everywhere: for small sigma (0.1 to 0.3) at grazing theta_o it exceeds 1 by up to 1.5%
  //    (A + B/2 > 1 there), so "<= 1" is checked only where the model keeps it.
  // Quadrature tolerance 1e-3: the integrand has kinks (max(0, cos dphi), theta_i = theta_o)
  // inside bins; against 1600 x 256 bins the measured error is under 3e-5.
  const double tol = 1e-3;
  double previous_normal = 2;
  for (double sigma : {0.1, 0.2, 0.5, 1.0, 3.0}) {
    const oren_nayar f(vec3(1), sigma);
    const double A = A_of(sigma), B = B_of(sigma);
    double previous = 0;
    for (double t : angles) {
      const double a = albedo(f, at_angle(t));
      INFO("sigma " << sigma << ", theta_o " << t << " deg: albedo " << a << " (A = " << A
                    << ", A + B/2 = " << A + B / 2 << ")");
      if (t == 0) CHECK(std::abs(a - A) < tol);
      CHECK(a > A - tol);
      CHECK(a < A + B / 2 + tol);
      if (sigma >= 0.5) CHECK(a < 1 + tol);
      CHECK(a > previous - tol);  // non-decreasing towards grazing
      previous = a;
      if (t == 0) {
        CHECK(a < previous_normal);
        previous_normal = a;
      }
    }
    CHECK_MESSAGE(previous > A + B / 2 - 0.02, "sigma " << sigma << ": at 89.9 deg the albedo "
                  << previous << " should be near A + B/2 = " << A + B / 2);
  }
}

TEST_CASE("oren-nayar: sample() follows pdf() (chi-square), and weight = f cos / pdf") {
  rng g(7);
  for (double sigma : {0.0, 0.5}) {
    const oren_nayar f(vec3(0.8, 0.5, 0.2), sigma);
    for (double t : {10.0, 75.0}) {
      const vec3 wo = at_angle(t);
      const auto r = zt::directions_follow_pdf(
          [&]() -> std::optional<vec3> {
            const auto s = f.sample(F, wo, vec3(g.uniform2(), g.uniform()));
            return s ? std::optional<vec3>(s->wi) : std::nullopt;
          },
          [&](const vec3& wi) { return f.pdf(F, wo, wi); }, 50000, direction_grid(16, 16),
          sidak_level(0.01, 4));
      CHECK_MESSAGE(r.ok, "sigma " << sigma << ", theta_o " << t << ": " << r.message);
      // The weight is f cos / pdf (1e-9 relative: a few double roundings).
      int bad = 0;
      for (int i = 0; i < 1000; ++i) {
        const auto s = f.sample(F, wo, vec3(g.uniform2(), g.uniform()));
        if (!s) { ++bad; continue; }
        const vec3 expected = f.eval(F, wo, s->wi) * s->wi.z / s->pdf;
        if (!(s->pdf > 0) || glm::length(s->weight - expected) > 1e-9 * (1 + glm::length(expected))) ++bad;
      }
      CHECK_MESSAGE(bad == 0, "sigma " << sigma << ", theta_o " << t << ": " << bad
                    << " of 1000 samples lost or with weight != f cos / pdf");
    }
  }
}

TEST_CASE("oren-nayar: no NaN or infinity at grazing angles and at the normal") {
  // Grazing wo, wi on the horizon, wo or wi along the normal: tan(beta) and the azimuth are the
  // places a formula with angles divides by zero.
  const oren_nayar f(vec3(1), 1.0);
  const vec3 dirs[] = {up, at_angle(89.999999), at_angle(90), vec3(0, 1, 1e-300),
                       glm::normalize(vec3(1, 1, 1e-9)), at_angle(-89.999999), at_angle(45)};
  rng g(3);
  for (const vec3& wo : dirs)
    for (const vec3& wi : dirs) {
      const vec3 v = f.eval(F, wo, wi);
      CHECK_MESSAGE(is_finite(v), "eval(" << wo.x << "," << wo.y << "," << wo.z << " ; " << wi.x
                    << "," << wi.y << "," << wi.z << ") is not finite");
      CHECK(v.x >= 0);
      CHECK(std::isfinite(f.pdf(F, wo, wi)));
      if (wo.z > 0)
        for (int i = 0; i < 100; ++i)
          if (const auto s = f.sample(F, wo, vec3(g.uniform2(), g.uniform())))
            CHECK_MESSAGE(is_finite(s->weight), "sample weight not finite at wo.z = " << wo.z);
    }
  // A f cos bounded by rho/pi (A + B) at the worst grazing pair.
  const vec3 graze = at_angle(89.999999);
  CHECK(f.eval(F, graze, graze).x * graze.z <= (A_of(1) + B_of(1)) / pi<double> + 1e-12);
}

namespace {

// The white furnace of path.hpp's tests (tests/test_path.cpp): the camera inside a unit sphere of the material
// that glows with Le = 1 from both faces. Every bounce sees Le, so L = Le sum of products of
// albedos; a constant albedo a gives Le / (1 - a).
scene furnace(std::shared_ptr<const custom_bsdf> f) {
  scene sc;
  material m = material::custom(std::move(f));
  m.radiance = rgb(1);
  m.two_sided = true;
  sc.add(sphere{vec3(0), 1.0}, sc.add_material(m));
  return sc;
}

estimator furnace_estimate(const scene& sc, integrator method) {
  path_options o;
  o.method = method;
  o.max_depth = 40;  // the tail a^41 is 5e-13 for a = 1/2
  const path_tracer tracer(sc, o);
  estimator e;
  std::uint64_t rays = 0;
  for (int i = 0; i < 20000; ++i) {
    rng g(11, 0, std::uint32_t(i));
    const ray r(vec3(0.2, -0.1, 0.3), sample_uniform_sphere(g.uniform2()));
    e.add(double(tracer(r, g, rays).x));
  }
  return e;
}

}  // namespace

TEST_CASE("oren-nayar: path-traced furnace (naive and mis) gives Le / (1 - a)") {
  // sigma = 0, rho = 1/2: a = 1/2 everywhere, L = 2. Checked within 5 standard errors (a correct
  // estimator fails 1 run in 2 million) and, in case the standard error were wrongly tiny, 2%.
  const scene lossless = furnace(std::make_shared<oren_nayar>(vec3(0.5), 0.0));
  for (integrator m : {integrator::naive, integrator::mis}) {
    const estimator e = furnace_estimate(lossless, m);
    const auto r = zt::mean_within(e, 2.0, 5);
    CHECK_MESSAGE(r.ok, std::string(name(m)) << ", sigma 0: " << r.message);
    CHECK_MESSAGE(std::abs(e.mean() - 2.0) < 0.04, std::string(name(m)) << ": mean " << e.mean());
  }
  // sigma = 0.5: the albedo depends on the direction, but each bounce's lies in
  // [rho A, rho (A + B/2)], so L lies in [1/(1 - rho A), 1/(1 - rho (A + B/2))] = [1.645, 1.905].
  const double A = A_of(0.5), B = B_of(0.5);
  const double lo = 1 / (1 - 0.5 * A), hi = 1 / (1 - 0.5 * (A + B / 2));
  const scene rough = furnace(std::make_shared<oren_nayar>(vec3(0.5), 0.5));
  for (integrator m : {integrator::naive, integrator::mis}) {
    const estimator e = furnace_estimate(rough, m);
    const double mean = e.mean(), se = e.standard_error();
    CHECK_MESSAGE((mean > lo - 5 * se && mean < hi + 5 * se),
                  std::string(name(m)) << ", sigma 0.5: " << mean << " +- " << se << ", expected in [" << lo
                          << ", " << hi << "]");
  }
}

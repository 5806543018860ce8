#pragma once
// A course's own kinds, written as an instructor would against zraka (not part of the library):
// a torus shape (a user shape: the ray meets it where a quartic vanishes) and a matte material
// (a Lambertian custom BSDF that may glow), registered by name for scene files:
//   objects:   - {type: torus, center: [x, y, z], major: R, minor: r, material: NAME}   (axis +y)
//   materials: NAME: {type: matte, albedo: colour, radiance: colour}
// Used by tests/test_course_program.cpp and the installed-package check's course binary
// (tests/consumer/course.cpp), both of which hand the registry to zraka::pathtrace_main.
#include <zraka/core/error.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/aabb.hpp>
#include <zraka/geometry/user_shape.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/materials/custom_bsdf.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/sampling/sampling.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace course {

// The real roots in [lo, hi] of c[0] + c[1] s + ... + c[n] s^n (c[n] != 0), ascending, into out
// (room for n). Between neighbouring roots of the derivative (and the ends) the polynomial is
// monotone, so each such piece holds at most one root, found by bisection to the last bit.
inline int poly_roots(const double* c, int n, double lo, double hi, double* out) {
  if (n == 1) {
    const double s = -c[0] / c[1];
    if (s >= lo && s <= hi) out[0] = s;
    return s >= lo && s <= hi ? 1 : 0;
  }
  double d[4];  // the derivative, degree n - 1
  for (int i = 0; i < n; ++i) d[i] = (i + 1) * c[i + 1];
  double ends[6];
  int m = 0;
  ends[m++] = lo;
  m += poly_roots(d, n - 1, lo, hi, ends + m);
  ends[m++] = hi;
  auto f = [&](double s) {
    double v = c[n];
    for (int i = n - 1; i >= 0; --i) v = v * s + c[i];
    return v;
  };
  int k = 0;
  auto add = [&](double s) {
    if (k == 0 || out[k - 1] != s) out[k++] = s;
  };
  for (int i = 0; i + 1 < m; ++i) {
    double a = ends[i], b = ends[i + 1];
    double fa = f(a);
    const double fb = f(b);
    if (fa == 0) {
      add(a);
      continue;
    }
    if (fb == 0 || (fa < 0) == (fb < 0)) continue;  // a root at b is the next piece's a
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (a + b);
      if (mid <= a || mid >= b) break;
      const double fm = f(mid);
      if ((fm < 0) == (fa < 0)) a = mid, fa = fm;
      else b = mid;
    }
    add(0.5 * (a + b));
  }
  if (f(hi) == 0) add(hi);
  return k;
}

// The torus of points at distance `minor` from the circle of radius `major` about `center` in
// the plane y = center.y.
class torus final : public zraka::user_shape {
 public:
  torus(const zraka::vec3& center, double major, double minor) : c_(center), R_(major), r_(minor) {
    if (!(minor > 0 && major > minor && std::isfinite(major)))
      throw zraka::error("torus: need 0 < minor < major, both finite");
  }
  std::string name() const override { return "torus"; }

  // |q|^2 + R^2 - r^2 = 2 R sqrt(qx^2 + qz^2) squared, along the ray, is a quartic in t. It is
  // solved in s = t - t0 about the point of the line nearest the centre (so the coefficients stay
  // of the torus's size, however far the camera is), within the torus's bounding sphere.
  bool intersect(const zraka::ray& ray, double t_min, double t_max, zraka::hit& h) const override {
    const zraka::vec3 d = ray.direction;  // unit
    const double t0 = glm::dot(c_ - ray.origin, d);
    const zraka::vec3 o = ray.origin + t0 * d - c_;
    const double oo = glm::dot(o, o), extent = R_ + r_;
    if (oo > extent * extent) return false;
    const double w = std::sqrt(extent * extent - oo);
    const double lo = std::max(t_min - t0, -w), hi = std::min(t_max - t0, w);
    if (!(lo < hi)) return false;
    const double k = oo + R_ * R_ - r_ * r_, R4 = 4 * R_ * R_;
    const double c[5] = {k * k - R4 * (o.x * o.x + o.z * o.z), -2 * R4 * (o.x * d.x + o.z * d.z),
                         2 * k - R4 * (d.x * d.x + d.z * d.z), 0, 1};
    double s[4];
    const int n = poly_roots(c, 4, lo, hi, s);
    for (int i = 0; i < n; ++i) {
      const double t = t0 + s[i];
      if (!(t > t_min && t < t_max)) continue;
      // The point put back on the surface: the nearest point of the tube to the computed one.
      const zraka::vec3 q = ray.origin + t * d - c_;
      const zraka::vec3 ring = R_ * glm::normalize(zraka::vec3(q.x, 0, q.z));
      const zraka::vec3 n_out = glm::normalize(q - ring);
      h.t = t;
      h.p = c_ + ring + r_ * n_out;
      h.normal = n_out;
      // The root is found to the last bit of s, but the quartic's own rounding moves it by about
      // 1e-15 of the torus's size; 1e-9 of it keeps new rays clear of the surface they leave.
      h.p_error = zraka::vec3(1e-9 * (extent + std::max({std::abs(c_.x), std::abs(c_.y), std::abs(c_.z)})));
      h.uv = zraka::vec2(std::atan2(q.z, q.x) / (2 * zraka::pi<double>) + 0.5,
                         std::atan2(n_out.y, glm::dot(n_out, ring) / R_) / (2 * zraka::pi<double>) + 0.5);
      h.set_face(d);
      return true;
    }
    return false;
  }
  zraka::aabb bounds() const override {
    const zraka::vec3 e(R_ + r_, r_, R_ + r_);
    return zraka::aabb{c_ - e, c_ + e};
  }
  // No area() or sample_area(): a glowing torus is found by the rays that hit it, not sampled.

 private:
  zraka::vec3 c_;
  double R_, r_;
};

// Lambert as a custom BSDF: f = albedo / pi, cosine-weighted sampling.
class matte final : public zraka::custom_bsdf {
 public:
  explicit matte(const zraka::vec3& albedo) : a_(albedo) {}
  std::string name() const override { return "matte"; }
  zraka::vec3 eval(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    return glm::dot(wo, f.n) > 0 && glm::dot(wi, f.n) > 0 ? a_ / zraka::pi<double> : zraka::vec3(0);
  }
  std::optional<zraka::custom_sample> sample(const zraka::bsdf_frame& f, const zraka::vec3& wo,
                                             const zraka::vec3& u) const override {
    if (!(glm::dot(wo, f.n) > 0)) return std::nullopt;
    const zraka::vec3 i = zraka::sample_cosine_hemisphere(zraka::vec2(u.x, u.y));
    if (!(i.z > 0)) return std::nullopt;
    return zraka::custom_sample{f.to_world(i), a_, i.z / zraka::pi<double>};
  }
  double pdf(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const double ci = glm::dot(wi, f.n);
    return glm::dot(wo, f.n) > 0 && ci > 0 ? ci / zraka::pi<double> : 0;
  }

 private:
  zraka::vec3 a_;
};

// [listing course-register]
inline void register_types(zraka::scene_registry& reg) {
  reg.add_shape("torus", {"center", "major", "minor"}, [](const zraka::scene_node& n) {
    const double R = n.number("major", 1.0), r = n.number("minor", 0.25);
    if (!(r > 0)) n.fail("minor", "must be positive");
    if (!(R > r)) n.fail("major", "must be larger than minor");
    return std::make_shared<const torus>(n.point("center", zraka::vec3(0)), R, r);
  });
  reg.add_material("matte", {"albedo", "radiance"}, [](const zraka::scene_node& n) {
    const zraka::rgb a = n.colour("albedo", zraka::rgb(0.5f));
    if (a.x > 1 || a.y > 1 || a.z > 1) n.fail("albedo", "must not exceed 1 (the surface would make light)");
    zraka::material m = zraka::material::custom(std::make_shared<const matte>(zraka::vec3(a)));
    m.radiance = n.colour("radiance", zraka::rgb(0));
    return m;
  });
}
// [end]

}  // namespace course

#pragma once
// A sphere S = { x : ||x - c|| = r } (book 1.2) and its intersection with a ray (book 1.5).
//
// Substituting R(t) = O + tD gives a t^2 + 2 b t + c = 0 with f = O - C, a = D.D, b = f.D,
// c = f.f - r^2. Two textbook steps lose all precision and are replaced here:
//  * the discriminant b^2 - a c cancels catastrophically for a small sphere far away (b^2 and
//    a c agree in almost every digit). We use the distance from the centre to the ray's line,
//    l = f - (b/a) D, for which b^2 - a c = a (r^2 - l.l) exactly, and l.l has no cancellation;
//  * -b + sqrt(...) cancels for the root nearer zero; we take q = -(b + sign(b) sqrt(disc)) and
//    the roots q/a and c/q (Press et al., Numerical Recipes, section 5.6).
// After Hearn & Baker and Haines et al., "Precision Improvements for Ray/Sphere Intersection",
// Ray Tracing Gems (2019), chapter 7.
// Range: f.f and r*r must not overflow, so coordinates and radii stay below about 1e153
// (double) or 1e18 (float); tests/test_sphere.cpp measures the accuracy inside that range.
#include <zraka/core/hit.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>

#include <optional>

namespace zraka {

// [listing sphere]
template <class T> struct sphere_t {
  vec3_t<T> center{T(0)};
  T radius = T(1);

  bool contains_point(const vec3_t<T>& x, T tolerance) const {
    return std::abs(glm::length(x - center) - radius) <= tolerance;
  }
  // A sphere with a negative, zero, NaN or infinite radius or centre is never hit.
  bool valid() const { return radius > T(0) && std::isfinite(radius) && is_finite(center); }
};
// [end]

using sphere = sphere_t<double>;

// The root a ray meets first in the open interval (t_min, t_max); `entering` when it is the
// smaller of the two (the ray enters the sphere there). Inlined by force, as quad.hpp's
// quad_root and for the same reason.
template <class T> struct sphere_root_t {
  T t;
  bool entering;
};

// [listing sphere-intersect]
template <class T>
ZRAKA_FORCE_INLINE std::optional<sphere_root_t<T>> sphere_root(const sphere_t<T>& s, const ray_t<T>& r, T t_min, T t_max) {
  if (!s.valid()) return std::nullopt;
  const vec3_t<T> f = r.origin - s.center;
  const vec3_t<T> D = r.direction;
  const T a = glm::dot(D, D);  // 1 for a valid ray, 0 for an invalid one
  if (!(a > T(0))) return std::nullopt;
  const T b = glm::dot(f, D);
  const T c = glm::dot(f, f) - s.radius * s.radius;
  const vec3_t<T> l = f - (b / a) * D;  // centre-to-line offset
  const T disc = a * (s.radius - glm::length(l)) * (s.radius + glm::length(l));
  if (!(disc >= T(0))) return std::nullopt;  // also for NaN

  const T q = -(b + std::copysign(std::sqrt(disc), b));
  T t0 = c / q, t1 = q / a;  // q == 0 only when both roots are 0: t0 is NaN, rejected below
  if (t0 > t1) std::swap(t0, t1);
  if (t0 > t_min && t0 < t_max) return sphere_root_t<T>{t0, true};
  if (t1 > t_min && t1 < t_max) return sphere_root_t<T>{t1, false};
  return std::nullopt;
}
// [end]

// The nearest hit with t in the open interval (t_min, t_max); fills `rec` only on a hit.
template <class T>
bool intersect(const sphere_t<T>& s, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec) {
  const auto root = sphere_root(s, r, t_min, t_max);
  if (!root) return false;
  const T t = root->t;
  const vec3_t<T> f = r.origin - s.center;
  const vec3_t<T> D = r.direction;
  rec.t = t;
  // Reproject onto the surface: the radial error of f + tD is removed, and what is left is
  // bounded as in pbrt (gamma(5) relative to the centre, plus one rounding for adding c back).
  // A sphere below the resolution of its coordinates can give local = 0; then the hit is
  // taken head-on (against D when entering, along D when leaving) instead of dividing by 0.
  vec3_t<T> local = f + t * D;
  const T len = glm::length(local);
  if (!(len > T(0)) || !std::isfinite(len)) local = root->entering ? -D : D;
  const vec3_t<T> on = local * (s.radius / glm::length(local));
  rec.p = s.center + on;
  rec.p_error = gamma<T>(6) * (abs3(on) + abs3(rec.p));
  rec.normal = on / s.radius;
  rec.set_face(D);
  // uv: longitude phi/(2 pi) in [0,1], latitude theta/pi from -y (0) to +y (1).
  const T phi = std::atan2(-rec.normal.z, rec.normal.x) + pi<T>;
  const T theta = std::acos(std::clamp(-rec.normal.y, T(-1), T(1)));
  rec.uv = {phi / (T(2) * pi<T>), theta / pi<T>};
  return true;
}

// Shadow rays only ask whether anything is in the way.
template <class T> bool occludes(const sphere_t<T>& s, const ray_t<T>& r, T t_min, T t_max) {
  return sphere_root(s, r, t_min, t_max).has_value();  // the hit point, normal and uv are not needed
}

}  // namespace zraka

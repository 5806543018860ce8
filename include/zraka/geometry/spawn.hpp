#pragma once
// Spawning a new ray from a hit point without hitting the same surface again ("shadow acne").
// Instead of a magic epsilon, the origin moves off the surface along the normal by exactly the
// bound on the hit point's floating-point error (hit.p_error, filled in by each intersection
// routine), and then one more ulp away, after pbrt's "offset ray origin" (Pharr, Jakob, Humphreys,
// Physically Based Rendering, 3rd ed., section 3.9). The new ray then needs no t_min: (0, t_max).
#include <zraka/core/hit.hpp>
#include <zraka/core/ray.hpp>

namespace zraka {

// gamma(n) = n eps / (1 - n eps) bounds the relative error of n chained roundings.
template <class T> constexpr T gamma(int n) {
  constexpr T eps = std::numeric_limits<T>::epsilon() / 2;  // unit roundoff
  return (T(n) * eps) / (T(1) - T(n) * eps);
}

// [listing offset]
template <class T>
vec3_t<T> offset_origin(const vec3_t<T>& p, const vec3_t<T>& p_error, const vec3_t<T>& n,
                        const vec3_t<T>& w) {
  const T d = glm::dot(abs3(n), p_error);
  vec3_t<T> offset = d * n;
  if (glm::dot(w, n) < T(0)) offset = -offset;  // leave on the side w points to
  vec3_t<T> po = p + offset;
  for (int i = 0; i < 3; ++i)  // round away from p, so that rounding cannot pull po back
    if (offset[i] > T(0)) po[i] = std::nextafter(po[i], infinity<T>);
    else if (offset[i] < T(0)) po[i] = std::nextafter(po[i], -infinity<T>);
  return po;
}
// [end]

template <class T> ray_t<T> spawn_ray(const hit_t<T>& h, const vec3_t<T>& w) {
  return {offset_origin(h.p, h.p_error, h.normal, w), w};
}

// A segment from a hit towards a target point (a shadow ray): test it on (0, t_max).
template <class T> struct segment_t {
  ray_t<T> ray;
  T t_max;
};

// t_max stops short of the target by its own rounding error, so that a surface at the target
// (a light's) is not counted as an occluder of itself.
template <class T> segment_t<T> spawn_segment(const hit_t<T>& h, const vec3_t<T>& target) {
  const vec3_t<T> o = offset_origin(h.p, h.p_error, h.normal, target - h.p);
  const vec3_t<T> d = target - o;
  const T dist = std::sqrt(glm::dot(d, d));
  return {ray_t<T>(o, d), dist * (T(1) - gamma<T>(16))};
}

}  // namespace zraka

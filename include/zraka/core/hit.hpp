#pragma once
// What an intersection routine reports: where, at which t, the surface's orientation there,
// and how far the computed point may be from the true one (used by spawn.hpp).
#include <zraka/core/vec.hpp>

namespace zraka {

template <class T> struct hit_t {
  T t = infinity<T>;            // ray parameter of the hit (a distance: directions are unit)
  vec3_t<T> p{T(0)};            // the hit point
  vec3_t<T> p_error{T(0)};      // bound on |computed p - true p|, per component
  vec3_t<T> normal{T(0)};       // unit outward geometric normal
  vec2_t<T> uv{T(0)};           // surface coordinates (sphere: longitude, latitude in [0,1])
  bool front_face = true;       // the ray came from the outside: dot(direction, normal) < 0

  // The normal turned to face the incoming ray, as shading and refraction want it.
  vec3_t<T> facing_normal() const { return front_face ? normal : -normal; }
  void set_face(const vec3_t<T>& direction) { front_face = glm::dot(direction, normal) < T(0); }
};

using hit = hit_t<double>;

}  // namespace zraka

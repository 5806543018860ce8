#pragma once
// Assignment 01, reference solution: a finite cylinder with caps, about any axis.
//
// In the cylinder's own frame (onb around the axis, origin at the centre of the bottom cap) the
// side is x^2 + y^2 = r^2 for 0 <= z <= h and the caps are the discs z = 0 and z = h. The side
// is the sphere's quadratic with z dropped, and the same two precautions apply (sphere.hpp):
// the discriminant from the distance of the ray's line to the axis, and the stable root pair.
// Watertight rim: each part accepts its boundary with a margin of its own rounding error, so a
// ray through the rim is taken by the side or by a cap, never by neither.
#include <zraka/core/hit.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>

namespace course {

template <class T> struct cylinder_t {
  zraka::vec3_t<T> base{T(0)};               // centre of the bottom cap
  zraka::vec3_t<T> axis{T(0), T(0), T(1)};   // unit vector from the bottom cap to the top cap
  T radius = T(1);
  T height = T(1);

  bool valid() const {
    return radius > T(0) && height > T(0) && std::isfinite(radius) && std::isfinite(height) &&
           zraka::is_finite(base) && std::abs(glm::length(axis) - T(1)) < T(1e-3);
  }
};
using cylinder = cylinder_t<double>;

// The nearest hit with t in (t_min, t_max); fills rec (t, p, p_error, outward normal, uv,
// front_face) only on a hit.
template <class T>
bool intersect(const cylinder_t<T>& cyl, const zraka::ray_t<T>& r, T t_min, T t_max,
               zraka::hit_t<T>& rec) {
  using V = zraka::vec3_t<T>;
  if (!cyl.valid() || !r.valid()) return false;
  const zraka::onb_t<T> frame(cyl.axis);
  const V o = frame.to_local(r.origin - cyl.base);
  const V d = frame.to_local(r.direction);
  const T R = cyl.radius, H = cyl.height;

  T t_best = t_max;
  int part = -1;  // 0 side, 1 bottom cap, 2 top cap
  // Side: (o_xy + t d_xy)^2 = R^2.
  const T a = d.x * d.x + d.y * d.y;
  if (a > T(0)) {
    const T b = o.x * d.x + o.y * d.y;
    const T rho = std::hypot(o.x, o.y);
    const T c = (rho - R) * (rho + R);  // no cancellation for an origin near the side
    const T lx = o.x - (b / a) * d.x, ly = o.y - (b / a) * d.y;  // axis-to-line offset
    const T l = std::hypot(lx, ly);
    const T disc = a * (R - l) * (R + l);
    if (disc >= T(0)) {
      const T q = -(b + std::copysign(std::sqrt(disc), b));
      T t0 = c / q, t1 = q / a;
      if (t0 > t1) std::swap(t0, t1);
      for (const T t : {t0, t1}) {
        if (!(t > t_min && t < t_best)) continue;
        const T z = o.z + t * d.z;
        const T margin = zraka::gamma<T>(8) * (std::abs(o.z) + std::abs(t * d.z) + H);
        if (z >= -margin && z <= H + margin) {
          t_best = t;
          part = 0;
          break;
        }
      }
    }
  }
  // Caps: z = 0 and z = H.
  if (d.z != T(0)) {
    for (int k = 0; k < 2; ++k) {
      const T t = ((k == 0 ? T(0) : H) - o.z) / d.z;
      if (!(t > t_min && t < t_best)) continue;
      const T x = o.x + t * d.x, y = o.y + t * d.y;
      const T margin = zraka::gamma<T>(4) * (std::abs(o.x) + std::abs(o.y) + std::abs(t * d.x) +
                                             std::abs(t * d.y) + R);
      if (std::hypot(x, y) <= R + margin) {
        t_best = t;
        part = 1 + k;
      }
    }
  }
  if (part < 0) return false;

  // The hit point in the local frame, projected onto the part it hit, and its error bound.
  const T t = t_best;
  V pl = o + t * d;
  V err_local;
  V n_local;
  if (part == 0) {
    const T rho = std::hypot(pl.x, pl.y);
    if (rho > T(0)) { pl.x *= R / rho; pl.y *= R / rho; }
    err_local = zraka::gamma<T>(3) * V(std::abs(pl.x), std::abs(pl.y), std::abs(o.z) + std::abs(t * d.z));
    n_local = V(pl.x / R, pl.y / R, T(0));
  } else {
    pl.z = part == 1 ? T(0) : H;
    err_local = zraka::gamma<T>(3) * V(std::abs(o.x) + std::abs(t * d.x), std::abs(o.y) + std::abs(t * d.y), T(0));
    n_local = V(T(0), T(0), part == 1 ? T(-1) : T(1));
  }
  const V world_offset = frame.to_world(pl);
  rec.t = t;
  rec.p = cyl.base + world_offset;
  // to_world's rounding, the frame's, and adding base: gamma(5) of the magnitudes involved;
  // the local error carried through the (orthonormal) frame by the absolute matrix.
  const auto abs_world = [&](const V& v) {
    return glm::abs(frame.t) * v.x + glm::abs(frame.b) * v.y + glm::abs(frame.n) * v.z;
  };
  rec.p_error = zraka::gamma<T>(5) * (glm::abs(cyl.base) + abs_world(glm::abs(pl))) + abs_world(err_local);
  rec.normal = zraka::normalize_or_zero(frame.to_world(n_local));
  rec.set_face(r.direction);
  const T phi = std::atan2(pl.y, pl.x) + zraka::pi<T>;
  rec.uv = part == 0 ? zraka::vec2_t<T>(phi / (T(2) * zraka::pi<T>), pl.z / H)
                     : zraka::vec2_t<T>(phi / (T(2) * zraka::pi<T>), std::hypot(pl.x, pl.y) / R);
  return true;
}

}  // namespace course

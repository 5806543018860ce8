#pragma once
// Assignment 01: a finite cylinder with caps, about any axis. Fill in intersect() below; see
// book/assignments/01-cylinder/README.md. The struct is given; do not change its members, the
// tests and the renderer use them.
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

// The nearest hit with t in (t_min, t_max). On a hit, fill rec.t, rec.p, rec.p_error (a bound
// on the error of rec.p, for zraka::spawn_ray), rec.normal (unit, outward), rec.uv and
// rec.front_face (rec.set_face(r.direction)), and return true. Leave rec alone on a miss.
template <class T>
bool intersect(const cylinder_t<T>& cyl, const zraka::ray_t<T>& r, T t_min, T t_max,
               zraka::hit_t<T>& rec) {
  // TODO: the side (a quadratic in the cylinder's own frame), then the two caps; keep the
  // nearest t in (t_min, t_max). Hint: zraka::onb_t<T> frame(cyl.axis) gives the frame.
  (void)cyl, (void)r, (void)t_min, (void)t_max, (void)rec;
  return false;
}

}  // namespace course

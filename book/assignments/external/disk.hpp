#pragma once
// A shape zraka does not have: a flat disk of radius r around a centre, facing a unit normal.
// The plane's t = (c - O).n / (D.n); the hit counts if |p - c| <= r.
#include <zraka/hit.hpp>
#include <zraka/onb.hpp>
#include <zraka/ray.hpp>
#include <zraka/spawn.hpp>

namespace mycourse {

template <class T> struct disk_t {
  zraka::vec3_t<T> center{T(0)};
  zraka::vec3_t<T> normal{T(0), T(0), T(1)};  // unit; the side the normal points to is "outside"
  T radius = T(1);
};

template <class T>
bool intersect(const disk_t<T>& d, const zraka::ray_t<T>& r, T t_min, T t_max, zraka::hit_t<T>& rec) {
  const T denom = glm::dot(r.direction, d.normal);
  if (!(std::abs(denom) > T(0)) || !r.valid()) return false;  // parallel, or an invalid ray
  const T t = glm::dot(d.center - r.origin, d.normal) / denom;
  if (!(t > t_min && t < t_max)) return false;
  // Work relative to the centre, then project onto the plane: the in-plane offset q is what
  // the radius test and the hit point use, and it carries only the rounding of q itself.
  const zraka::vec3_t<T> q0 = (r.origin - d.center) + t * r.direction;
  const zraka::vec3_t<T> q = q0 - glm::dot(q0, d.normal) * d.normal;
  if (!(glm::dot(q, q) <= d.radius * d.radius)) return false;
  rec.t = t;
  rec.p = d.center + q;
  rec.p_error = zraka::gamma<T>(7) * (glm::abs(d.center) + glm::abs(q));
  rec.normal = d.normal;
  rec.set_face(r.direction);
  const zraka::onb_t<T> frame(d.normal);
  rec.uv = {T(0.5) + glm::dot(q, frame.t) / (T(2) * d.radius), T(0.5) + glm::dot(q, frame.b) / (T(2) * d.radius)};
  return true;
}

}  // namespace mycourse

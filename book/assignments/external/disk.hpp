#pragma once
// A shape zraka does not have: a flat disk of radius r around a centre, facing a unit normal,
// as a zraka::user_shape_t (user_shape.hpp). It gives its area and a uniform point on it, so a
// glowing material makes it an area light that next-event estimation samples.
// The plane's t = (c - O).n / (D.n); the hit counts if |p - c| <= r.
#include <zraka/core/error.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/geometry/user_shape.hpp>
#include <zraka/sampling/sampling.hpp>

#include <cmath>
#include <string>

namespace mycourse {

template <class T> struct disk_t final : zraka::user_shape_t<T> {
  zraka::vec3_t<T> center{T(0)};
  zraka::vec3_t<T> normal{T(0), T(0), T(1)};  // unit; the side the normal points to is "outside"
  T radius = T(1);

  disk_t(const zraka::vec3_t<T>& c, const zraka::vec3_t<T>& n, T r)
      : center(c), normal(zraka::normalize_or_zero(n)), radius(r) {
    if (!zraka::is_finite(center)) throw zraka::error("disk: the centre must be finite");
    if (normal == zraka::vec3_t<T>(T(0))) throw zraka::error("disk: the normal must not be zero");
    if (!(radius > T(0)) || !std::isfinite(radius)) throw zraka::error("disk: the radius must be positive");
  }

  std::string name() const override { return "disk"; }

  bool intersect(const zraka::ray_t<T>& r, T t_min, T t_max, zraka::hit_t<T>& rec) const override {
    const T denom = glm::dot(r.direction, normal);
    if (!(std::abs(denom) > T(0)) || !r.valid()) return false;  // parallel, or an invalid ray
    const T t = glm::dot(center - r.origin, normal) / denom;
    if (!(t > t_min && t < t_max)) return false;
    // Work relative to the centre, then project onto the plane: the in-plane offset q is what
    // the radius test and the hit point use, and it carries only the rounding of q itself.
    const zraka::vec3_t<T> q0 = (r.origin - center) + t * r.direction;
    const zraka::vec3_t<T> q = q0 - glm::dot(q0, normal) * normal;
    if (!(glm::dot(q, q) <= radius * radius)) return false;
    rec.t = t;
    rec.p = center + q;
    rec.p_error = zraka::gamma<T>(7) * (glm::abs(center) + glm::abs(q));
    rec.normal = normal;
    rec.set_face(r.direction);
    const zraka::onb_t<T> frame(normal);
    rec.uv = {T(0.5) + glm::dot(q, frame.t) / (T(2) * radius), T(0.5) + glm::dot(q, frame.b) / (T(2) * radius)};
    return true;
  }

  // The disk's exact box: along axis i it reaches r sqrt(1 - n_i^2) from the centre.
  zraka::aabb_t<T> bounds() const override {
    const zraka::vec3_t<T> e = radius * glm::sqrt(glm::max(zraka::vec3_t<T>(T(0)), T(1) - normal * normal));
    return {center - e, center + e};
  }

  T area() const override { return zraka::pi<T> * radius * radius; }

  // Uniform in area: the concentric map of the unit square onto the disk (sampling.hpp).
  std::optional<zraka::surface_point_t<T>> sample_area(const zraka::vec2_t<T>& u) const override {
    const zraka::vec2_t<T> d = zraka::sample_disk_concentric(u) * radius;
    const zraka::onb_t<T> frame(normal);
    const zraka::vec3_t<T> q = d.x * frame.t + d.y * frame.b;
    return zraka::surface_point_t<T>{center + q, normal, zraka::gamma<T>(7) * (glm::abs(center) + glm::abs(q))};
  }
};

using disk = disk_t<double>;

}  // namespace mycourse

#pragma once
// Assignment 04, reference solution: a flat ring (an annulus: a disk with a round hole) as a
// zraka::user_shape_t, with area sampling so that it can be an area light.
#include <zraka/core/hit.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/geometry/user_shape.hpp>
#include <zraka/sampling/sampling.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace course {

template <class T> struct ring_t final : zraka::user_shape_t<T> {
  zraka::vec3_t<T> center{T(0)};
  zraka::vec3_t<T> normal{T(0), T(0), T(1)};  // unit; the front side
  T inner = T(0.5), outer = T(1);              // 0 <= inner < outer

  ring_t(const zraka::vec3_t<T>& c, const zraka::vec3_t<T>& n, T a, T b) : center(c), normal(n), inner(a), outer(b) {}

  std::string name() const override { return "ring"; }

  bool intersect(const zraka::ray_t<T>& r, T t_min, T t_max, zraka::hit_t<T>& h) const override {
    const T denom = glm::dot(r.direction, normal);
    if (!(std::abs(denom) > T(0)) || !r.valid()) return false;
    const T t = glm::dot(center - r.origin, normal) / denom;
    if (!(t > t_min && t < t_max)) return false;
    // The in-plane offset from the centre: the radius test and the hit point both use it.
    const zraka::vec3_t<T> q0 = (r.origin - center) + t * r.direction;
    const zraka::vec3_t<T> q = q0 - glm::dot(q0, normal) * normal;
    const T rr = glm::dot(q, q);
    if (!(rr <= outer * outer && rr >= inner * inner)) return false;
    h.t = t;
    h.p = center + q;
    h.p_error = zraka::gamma<T>(7) * (glm::abs(center) + glm::abs(q));
    h.normal = normal;
    const zraka::onb_t<T> frame(normal);
    const T phi = std::atan2(glm::dot(q, frame.b), glm::dot(q, frame.t));
    h.uv = {(std::sqrt(rr) - inner) / (outer - inner), (phi + zraka::pi<T>) / (T(2) * zraka::pi<T>)};
    h.set_face(r.direction);
    return true;
  }

  zraka::aabb_t<T> bounds() const override {
    const zraka::vec3_t<T> e = outer * glm::sqrt(glm::max(zraka::vec3_t<T>(T(0)), T(1) - normal * normal));
    return {center - e, center + e};
  }

  T area() const override { return zraka::pi<T> * (outer * outer - inner * inner); }

  // Uniform in area: r^2 uniform in [inner^2, outer^2], the angle uniform.
  std::optional<zraka::surface_point_t<T>> sample_area(const zraka::vec2_t<T>& u) const override {
    const T r = std::sqrt(inner * inner + u.x * (outer * outer - inner * inner));
    const T phi = T(2) * zraka::pi<T> * u.y;
    const zraka::onb_t<T> frame(normal);
    const zraka::vec3_t<T> q = r * std::cos(phi) * frame.t + r * std::sin(phi) * frame.b;
    return zraka::surface_point_t<T>{center + q, normal, zraka::gamma<T>(7) * (glm::abs(center) + glm::abs(q))};
  }
};

}  // namespace course

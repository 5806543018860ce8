#pragma once
// Assignment 04: a flat ring (an annulus: a disk with a round hole) as a zraka::user_shape_t,
// with area sampling so that it can be an area light. Fill in intersect, bounds, area and
// sample_area; see README.md.
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

  // The nearest hit in (t_min, t_max): fill t, p, p_error, normal, uv; set_face last.
  bool intersect(const zraka::ray_t<T>& r, T t_min, T t_max, zraka::hit_t<T>& h) const override {
    (void)r, (void)t_min, (void)t_max, (void)h;
    return false;  // TODO
  }

  // A box that contains the ring (as tight as you can make it).
  zraka::aabb_t<T> bounds() const override {
    return {};  // TODO
  }

  // The ring's area.
  T area() const override {
    return T(0);  // TODO
  }

  // A point uniform in area from u in [0,1)^2, with its normal and error bound.
  std::optional<zraka::surface_point_t<T>> sample_area(const zraka::vec2_t<T>& u) const override {
    (void)u;
    return std::nullopt;  // TODO
  }
};

}  // namespace course

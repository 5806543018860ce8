#pragma once
// A shape of your own (book 2.3, "Extending zraka"): the extension point that lets an instructor
// or a student add a shape without editing the library. Derive from user_shape_t<T>, give it
// an intersection routine and a bounding box, and add it to a scene with
//     sc.add(std::make_shared<my_disk>(...), material_index);
// It then goes into the scene's object BVH and into every CPU renderer (nearest_hit, occluded,
// Whitted, the path tracer). If it also gives its area and a uniform point on it, a glowing
// material on it makes it an area light that next-event estimation samples (lights.hpp);
// without them it still glows where a ray finds it, but is never sampled (the summary says so).
// The OpenCL kernel cannot run C++ code: it refuses a scene with a user shape, by name.
//
// Conventions are those of the built-in shapes (sphere.hpp, quad.hpp): hits in the open interval
// (t_min, t_max); hit_t::normal is the unit outward geometric normal, p_error bounds the error of
// the hit point per component (spawn.hpp moves new rays off the surface by it), uv are surface
// coordinates; call h.set_face(r.direction) last.
#include <zraka/core/hit.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/aabb.hpp>

#include <optional>
#include <string>

namespace zraka {

// A point on a surface chosen by area sampling.
template <class T> struct surface_point_t {
  vec3_t<T> p{T(0)};
  vec3_t<T> normal{T(0)};   // unit, outward: its side decides front and back emission
  vec3_t<T> p_error{T(0)};  // bound on the error of p, per component
};

template <class T> struct user_shape_t {
  virtual ~user_shape_t() = default;
  // What the shape is called in messages and summaries ("disk").
  virtual std::string name() const = 0;
  virtual bool intersect(const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h) const = 0;
  // A finite box that contains the shape (the object BVH needs it).
  virtual aabb_t<T> bounds() const = 0;
  // Optional, for area lights: the surface area, and a point uniform in area from u in [0,1)^2.
  // An area of 0 means "cannot be sampled".
  virtual T area() const { return T(0); }
  virtual std::optional<surface_point_t<T>> sample_area(const vec2_t<T>& /*u*/) const { return std::nullopt; }
};

using user_shape = user_shape_t<double>;

}  // namespace zraka

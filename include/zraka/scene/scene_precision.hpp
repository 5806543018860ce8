#pragma once
// A scene in another precision: scene_in<float>(sc) is the same scene with every coordinate in
// float, for the float path through the renderer (issue 17; every routine of the path loop is a
// template on the precision T). Materials, textures, the environment and media hold no
// coordinates of T and are shared as they are.
//
// Rounding a coordinate to float can change a shape's nature: a quad whose edges are 1e-30 long
// has a normal of 1e-60, which is zero in float; a sphere of radius 1e-50 has radius 0. Such a
// shape would silently vanish from the image, so it is an error that names it; so is a value
// beyond float's range. A user shape is a C++ object written for one precision (user_shape.hpp):
// it cannot be converted and is refused by its name.
#include <zraka/core/error.hpp>
#include <zraka/scene/scene.hpp>

#include <cmath>
#include <string>

namespace zraka {

namespace detail {
template <class U, class T> vec3_t<U> coordinates_in(const vec3_t<T>& v, const std::string& what) {
  const vec3_t<U> w(v);
  if (is_finite(v) && !is_finite(w))
    throw error(what + ": a coordinate beyond the range of " + (sizeof(U) == 4 ? "float" : "double"));
  return w;
}
template <class U> const char* precision_name() { return sizeof(U) == 4 ? "float" : "double"; }
}  // namespace detail

template <class U, class T> scene_t<U> scene_in(const scene_t<T>& s) {
  using detail::coordinates_in;
  const std::string in = std::string(" in ") + detail::precision_name<U>();
  auto fail = [&](const char* what, std::size_t i, const char* why) {
    throw error(std::string(what) + " " + std::to_string(i) + ": " + why + in);
  };
  scene_t<U> f;
  f.materials = s.materials;
  f.material_names = s.material_names;
  for (std::size_t i = 0; i < s.spheres.size(); ++i) {
    const auto& o = s.spheres[i];
    sphere_t<U> sp{coordinates_in<U>(o.shape.center, "sphere " + std::to_string(i)), U(o.shape.radius)};
    if (!sp.valid()) fail("sphere", i, "its radius is zero or not finite");
    f.spheres.push_back({sp, o.material});
  }
  for (std::size_t i = 0; i < s.quads.size(); ++i) {
    const auto& o = s.quads[i];
    const std::string what = "quad " + std::to_string(i);
    const parallelogram_t<U> q{coordinates_in<U>(o.shape.corner, what), coordinates_in<U>(o.shape.u, what),
                               coordinates_in<U>(o.shape.v, what)};
    if (!q.valid()) fail("quad", i, "its edges are parallel or too short");
    f.quads.push_back({q, o.material});
  }
  for (std::size_t i = 0; i < s.planes.size(); ++i) {
    const auto& o = s.planes[i];
    const std::string what = "plane " + std::to_string(i);
    const plane_t<U> p{coordinates_in<U>(o.shape.point, what), coordinates_in<U>(o.shape.normal, what)};
    if (!p.valid()) fail("plane", i, "its normal is zero");
    f.planes.push_back({p, o.material});
  }
  for (std::size_t i = 0; i < s.triangles.size(); ++i) {
    const auto& o = s.triangles[i];
    const std::string what = "triangle " + std::to_string(i);
    const triangle_t<U> t{coordinates_in<U>(o.shape.a, what), coordinates_in<U>(o.shape.b, what),
                          coordinates_in<U>(o.shape.c, what)};
    if (t.normal() == vec3_t<U>(0)) fail("triangle", i, "it has no area");
    f.triangles.push_back({t, o.material});
  }
  for (std::size_t i = 0; i < s.meshes.size(); ++i) {
    const mesh_t<T>& m = s.meshes[i].shape;
    const std::string what = "mesh " + std::to_string(i);
    mesh_t<U> g;
    g.triangles = m.triangles;
    for (const auto& p : m.positions) g.positions.push_back(coordinates_in<U>(p, what));
    for (const auto& n : m.normals) g.normals.push_back(vec3_t<U>(n));  // unit: always in range
    for (const auto& t : m.texcoords) g.texcoords.push_back(vec2_t<U>(t));
    // A mesh's sliver triangle may lose its area (as in the double mesh, it is then never hit).
    f.add(std::move(g), s.meshes[i].material);
  }
  if (!s.user_shapes.empty())
    throw error("user shape '" + s.user_shapes.front().shape->name() + "' is written in " + detail::precision_name<T>() +
                " (user_shape.hpp) and cannot be converted; render this scene in " + detail::precision_name<T>());
  // The light kinds keep double parameters (lights/light.hpp); a point light's position must
  // still fit in U, where it is sampled.
  for (std::size_t i = 0; i < s.lights.size(); ++i) {
    const light& l = s.lights[i];
    if (const auto* p = l.get<light_kinds::point>()) coordinates_in<U>(p->position, "point light " + std::to_string(i));
  }
  f.lights = s.lights;
  f.background = s.background;
  f.environment = s.environment;
  f.ambient = s.ambient;
  f.camera.position = coordinates_in<U>(s.camera.position, "camera");
  f.camera.look_at = coordinates_in<U>(s.camera.look_at, "camera");
  f.camera.up = vec3_t<U>(s.camera.up);
  f.camera.vfov_degrees = U(s.camera.vfov_degrees);
  f.camera.aspect = U(s.camera.aspect);
  f.camera.aperture = U(s.camera.aperture);
  f.camera.focus_distance = U(s.camera.focus_distance);
  if (f.camera.position == f.camera.look_at) throw error("camera: position and look_at are one point" + in);
  f.settings = s.settings;
  f.media = s.media;
  f.global_medium = s.global_medium;
  if (s.has_object_bvh()) f.build_acceleration();
  return f;
}

}  // namespace zraka

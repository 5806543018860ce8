#pragma once
// The scene as JSON for tools/mitsuba_reference.py, which builds the same scene in Mitsuba 3 to
// render a reference (book 2.3): size, depth, background, camera, materials, spheres, quads,
// triangles (every mesh's too, flat), point lights and homogeneous media (book 6.1). What the
// converter cannot express is refused by name (zraka::error): an infinite plane, a user shape,
// a density grid, an environment light, a custom BSDF, a rough material, a kind it does not know. Numbers are written with 17 digits, so doubles survive the trip.
#include <zraka/compiled.hpp>
#include <zraka/error.hpp>
#include <zraka/material.hpp>
#include <zraka/scene.hpp>

#include <cstddef>
#include <sstream>
#include <string>

namespace zraka {

namespace detail {
// The converter's name of a material kind, or nullptr for one it does not know.
inline const char* mitsuba_kind(material_kind k) {
  if (k == material_kind::lambertian) return "lambertian";
  if (k == material_kind::fuzzy_metal) return "metal";
  if (k == material_kind::dielectric) return "dielectric";
  if (k == material_kind::emitter) return "emitter";
  if (k == material_kind::phong) return "phong";
  return nullptr;
}
}  // namespace detail

// Throws zraka::error for what the converter cannot express (see the top).
ZRAKA_COMPILED_FN std::string mitsuba_scene_json(const scene& sc, int width, int height, int depth);

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN std::string mitsuba_scene_json(const scene& sc, int width, int height, int depth) {
  if (!sc.planes.empty()) throw error("--export: Mitsuba has no infinite plane; use a large quad");
  if (!sc.user_shapes.empty())
    throw error("--export: a user shape ('" + sc.user_shapes[0].shape->name() + "') cannot be exported");
  for (const medium& md : sc.media)
    if (!md.homogeneous()) throw error("--export: medium '" + md.name + "' is a density grid; only homogeneous media are exported");
  if (sc.environment) throw error("--export: the environment light ('" + sc.environment->name() + "') is not exported to Mitsuba yet");
  for (std::size_t i = 0; i < sc.materials.size(); ++i) {
    const material& m = sc.materials[i];
    if (is_custom(m)) throw error("--export: " + sc.material_label(int(i)) + " is a custom BSDF ('" + m.bsdf->name() + "'), which cannot be exported");
    if (is_microfacet(m))
      throw error("--export: " + sc.material_label(int(i)) + " is a " + kind_name(m.kind) + ", which cannot be exported yet (tools/mitsuba_reference.py has no rough materials)");
    if (m.albedo.type == texture::kind::image || m.albedo.type == texture::kind::noise)
      throw error("--export: " + sc.material_label(int(i)) + " has " + describe(m.albedo) + ", which is not exported yet");
    if (!detail::mitsuba_kind(m.kind))
      throw error("--export: " + sc.material_label(int(i)) + " is of a kind the converter does not know");
  }
  std::ostringstream o;
  o.precision(17);
  auto v3 = [&](const auto& v) { o << '[' << double(v.x) << ", " << double(v.y) << ", " << double(v.z) << ']'; };
  o << "{\n  \"width\": " << width << ", \"height\": " << height << ", \"max_depth\": " << depth
    << ",\n  \"background\": ";
  v3(sc.background);
  o << ",\n  \"camera\": {\"position\": ";
  v3(sc.camera.position);
  o << ", \"look_at\": ";
  v3(sc.camera.look_at);
  o << ", \"up\": ";
  v3(sc.camera.up);
  o << ", \"vfov\": " << sc.camera.vfov_degrees << "},\n  \"materials\": [";
  for (std::size_t i = 0; i < sc.materials.size(); ++i) {
    const material& m = sc.materials[i];
    o << (i ? ",\n    " : "\n    ") << "{\"type\": \"" << detail::mitsuba_kind(m.kind) << "\", \"albedo\": ";
    v3(m.albedo.a);
    o << ", \"checker\": " << (m.albedo.type == texture::kind::checker ? "true" : "false")
      << ", \"fuzz\": " << m.fuzz << ", \"ior\": " << m.ior << ", \"radiance\": ";
    v3(m.radiance);
    o << ", \"two_sided\": " << (m.two_sided ? "true" : "false") << ", \"interior\": " << m.interior << "}";
  }
  o << "],\n  \"global_medium\": " << sc.global_medium << ",\n  \"media\": [";  // book 6.1
  for (std::size_t i = 0; i < sc.media.size(); ++i) {
    const medium& md = sc.media[i];
    o << (i ? ",\n    " : "\n    ") << "{\"name\": \"" << md.name << "\", \"sigma_a\": ";
    v3(md.sigma_a);
    o << ", \"sigma_s\": ";
    v3(md.sigma_s);
    o << ", \"g\": " << md.g << "}";
  }
  o << "],\n  \"spheres\": [";
  for (std::size_t i = 0; i < sc.spheres.size(); ++i) {
    o << (i ? ",\n    " : "\n    ") << "{\"center\": ";
    v3(sc.spheres[i].shape.center);
    o << ", \"radius\": " << sc.spheres[i].shape.radius << ", \"material\": " << sc.spheres[i].material << "}";
  }
  o << "],\n  \"quads\": [";
  for (std::size_t i = 0; i < sc.quads.size(); ++i) {
    const auto& q = sc.quads[i].shape;
    o << (i ? ",\n    " : "\n    ") << "{\"corner\": ";
    v3(q.corner);
    o << ", \"u\": ";
    v3(q.u);
    o << ", \"v\": ";
    v3(q.v);
    o << ", \"material\": " << sc.quads[i].material << "}";
  }
  o << "],\n  \"triangles\": [";  // loose triangles and every mesh's triangles, flat-shaded
  bool first = true;
  auto tri = [&](const auto& a, const auto& b, const auto& c, int mat) {
    o << (first ? "\n    " : ",\n    ") << "{\"a\": ";
    v3(a), o << ", \"b\": ", v3(b), o << ", \"c\": ", v3(c);
    o << ", \"material\": " << mat << "}";
    first = false;
  };
  for (const auto& t : sc.triangles) tri(t.shape.a, t.shape.b, t.shape.c, t.material);
  for (const auto& m : sc.meshes)
    for (std::size_t i = 0; i < m.shape.triangle_count(); ++i) {
      const auto t = m.shape.triangle(i);
      tri(t.a, t.b, t.c, m.material);
    }
  o << "],\n  \"point_lights\": [";
  for (std::size_t i = 0; i < sc.point_lights.size(); ++i) {
    o << (i ? ",\n    " : "\n    ") << "{\"position\": ";
    v3(sc.point_lights[i].position);
    o << ", \"intensity\": ";
    v3(sc.point_lights[i].intensity);
    o << "}";
  }
  o << "]\n}\n";
  return o.str();
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

#pragma once
// Asking a scene about rays (book 2.2, 4.1, 5.2): the nearest hit along a ray and whether a
// shadow segment is blocked. Both test every object, unless build_acceleration() made an object
// BVH (walked four-wide: wide_bvh.hpp); planes are infinite and are always tested. Renderers
// never know which of the two happened.
#include <zraka/accel/wide_bvh.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/scene/scene.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

namespace zraka {

template <class T> struct scene_hit_t {
  hit_t<T> h;
  int material = -1;
  object_ref object{shape_kind::sphere, -1};
  std::uint32_t triangle = 0;      // meshes: the triangle hit
  vec3_t<T> shading_normal{T(0)};  // unit, on h.normal's side; meshes interpolate vertex normals
  // The shading normal turned to the side the ray came from, as lighting wants it.
  vec3_t<T> facing_shading_normal() const { return h.front_face ? shading_normal : -shading_normal; }
};
using scene_hit = scene_hit_t<double>;

// [listing nearest-hit]
// The nearest hit along r with t in (0, t_max): each hit found shrinks the interval, so the
// result is the minimum over all objects whatever their order (or the BVH's).
template <class T>
bool nearest_hit(const scene_t<T>& sc, const ray_t<T>& r, scene_hit_t<T>& out, T t_max = infinity<T>) {
  bool found = false;
  auto visit = [&](object_ref o) {
    if (!intersect_object(sc, o, r, T(0), t_max, out.h, out.triangle)) return false;
    found = true;
    t_max = out.h.t;
    out.object = o;
    return true;
  };
  if (sc.has_object_bvh()) {
    for (int i = 0; i < static_cast<int>(sc.planes.size()); ++i) visit({shape_kind::plane, i});
    wide_intersect(sc.accel.wide, r, T(0), t_max, [&](std::uint32_t i, T& tm) {
      t_max = tm;
      const bool hit = visit(sc.accel.objects[i]);
      tm = t_max;
      return hit;
    });
  } else {
    for_each_object(sc, visit);
  }
  if (!found) return false;
  out.material = sc.material_index(out.object);
  out.shading_normal = out.h.normal;
  if (out.object.kind == shape_kind::mesh) {
    const mesh_t<T>& m = sc.meshes[std::size_t(out.object.index)].shape;
    if (m.normals.size() == m.positions.size()) {
      const vec3_t<T> n = m.shading_normal(out.triangle, out.h.uv.x, out.h.uv.y);
      out.shading_normal = glm::dot(n, out.h.normal) < T(0) ? -n : n;  // on the geometric side
    }
    out.h.uv = m.texcoord(out.triangle, out.h.uv.x, out.h.uv.y);  // barycentrics: used above, now texture space
  }
  return true;
}
// [end]

// Is anything in the way along a shadow segment (spawn.hpp)?
template <class T> bool occluded(const scene_t<T>& sc, const segment_t<T>& s) {
  if (sc.has_object_bvh()) {
    for (int i = 0; i < static_cast<int>(sc.planes.size()); ++i)
      if (object_blocks(sc, {shape_kind::plane, i}, s.ray, s.t_max)) return true;
    return wide_occluded(sc.accel.wide, s.ray, T(0), s.t_max, [&](std::uint32_t i) {
      return object_blocks(sc, sc.accel.objects[i], s.ray, s.t_max);
    });
  }
  bool blocked = false;
  for_each_object(sc, [&](object_ref o) { blocked = blocked || object_blocks(sc, o, s.ray, s.t_max); });
  return blocked;
}

// What the scene holds and what was built for it, in one line, e.g.
// "built: 3 spheres, 1 mesh (16384 triangles, BVH 0.02 s), 1 point light; no object BVH (4 objects)".
template <class T> std::string describe_built(const scene_t<T>& sc) {
  std::string out = "built:";
  bool first = true;
  auto item = [&](std::size_t n, const char* one, const char* many, const std::string& extra = "") {
    if (n == 0) return;
    out += (first ? " " : ", ") + std::to_string(n) + " " + (n == 1 ? one : many) + extra;
    first = false;
  };
  item(sc.spheres.size(), "sphere", "spheres");
  item(sc.quads.size(), "quad", "quads");
  item(sc.planes.size(), "plane", "planes");
  item(sc.triangles.size(), "triangle", "triangles");
  std::size_t tris = 0;
  double secs = 0;
  for (const auto& m : sc.meshes) tris += m.shape.triangle_count(), secs += m.build_seconds;
  char buf[96];
  std::snprintf(buf, sizeof buf, " (%zu triangles, BVH %.3f s)", tris, secs);
  item(sc.meshes.size(), "mesh", "meshes", buf);
  item(sc.user_shapes.size(), "user shape", "user shapes");
  const auto points = std::size_t(std::count_if(sc.lights.begin(), sc.lights.end(), [](const light& l) {
    return l.is<light_kinds::point>();
  }));
  item(points, "point light", "point lights");
  item(sc.lights.size() - points, "course's light", "course's lights");  // lights/custom_light.hpp
  if (first) out += " nothing";
  if (sc.has_object_bvh()) {
    std::snprintf(buf, sizeof buf, "; object BVH over %zu objects (%.3f s)", sc.accel.objects.size(),
                  sc.accel.seconds);
    out += buf;
  } else {
    out += "; no object BVH (" + std::to_string(sc.bounded_count()) + " bounded objects)";
  }
  return out;
}

// Compiled once at double (compiled.hpp).
ZRAKA_INSTANCE(bool nearest_hit(const scene_t<double>&, const ray_t<double>&, scene_hit_t<double>&, double))
ZRAKA_INSTANCE(bool occluded(const scene_t<double>&, const segment_t<double>&))
ZRAKA_INSTANCE(std::string describe_built(const scene_t<double>&))

}  // namespace zraka

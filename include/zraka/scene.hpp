#pragma once
// A scene described in code (book 2.2, 2.3, 4.1): materials, objects that name their material by
// index, point lights, the area lights (every sphere or quad whose material emits), a background
// colour, the camera and the render settings (the thesis's "hyper-parameters", Def 4.1.1). The
// scene file loader (scene_file.hpp) fills the same struct.
//
// Objects: spheres, quads (a box is six of them), infinite planes, single triangles, and meshes
// (each with its own triangle BVH, built when the mesh is added). Geometry queries go through two
// functions only, nearest_hit() and occluded(). They test every object, unless
// build_acceleration() found enough bounded objects to make an object BVH pay (bvh.hpp); planes
// are infinite and are always tested. Renderers never know which of the two happened.
#include <zraka/bvh.hpp>
#include <zraka/camera.hpp>
#include <zraka/material.hpp>
#include <zraka/mesh.hpp>
#include <zraka/plane.hpp>
#include <zraka/quad.hpp>
#include <zraka/sampling.hpp>
#include <zraka/spawn.hpp>
#include <zraka/sphere.hpp>
#include <zraka/stopwatch.hpp>
#include <zraka/triangle.hpp>
#include <zraka/triangle_bvh.hpp>

#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace zraka {

// Def 4.1.1's hyper-parameters.
struct render_settings {
  int width = 320, height = 240;
  int spp = 16;          // samples (primary rays) per pixel
  int max_depth = 8;     // bounces before a path stops (Whitted: depth of the ray tree)
  std::uint64_t seed = 1;
};

enum class shape_kind { sphere, quad, plane, triangle, mesh };
struct object_ref {
  shape_kind kind;
  int index;  // into the scene's vector of that kind
};

// A point light: radiant intensity I, so the irradiance at distance d, facing it, is I / d^2.
template <class T> struct point_light_t {
  vec3_t<T> position{T(0)};
  rgb intensity{20.0f};
};

// A mesh object: the triangles (in T, for exact hit points and shading normals) and their BVH
// (in float, triangle_bvh.hpp), built once when the mesh is added.
template <class T> struct mesh_object_t {
  mesh_t<T> shape;
  triangle_bvh bvh;
  int material = 0;
  double build_seconds = 0;
};

template <class T> struct scene_t {
  struct sphere_object {
    sphere_t<T> shape;
    int material;
  };
  struct quad_object {
    parallelogram_t<T> shape;
    int material;
  };
  struct plane_object {
    plane_t<T> shape;
    int material;
  };
  struct triangle_object {
    triangle_t<T> shape;
    int material;
  };
  // The object BVH over the bounded objects, when build_acceleration() decided to make one.
  struct acceleration {
    bvh_t<T> tree;
    std::vector<object_ref> objects;  // the BVH's primitive i is objects[i]
    double seconds = 0;
  };

  std::vector<material> materials;
  std::vector<sphere_object> spheres;
  std::vector<quad_object> quads;
  std::vector<plane_object> planes;
  std::vector<triangle_object> triangles;
  std::vector<mesh_object_t<T>> meshes;
  std::vector<point_light_t<T>> point_lights;
  std::vector<object_ref> lights;  // area lights, kept up to date by add()
  rgb background{0};               // radiance of rays that leave the scene
  rgb ambient{0};                  // Whitted only: Phong's ambient light I_a
  camera_t<T> camera;
  render_settings settings;
  acceleration accel;              // empty: every object is tested

  int add_material(const material& m) {
    materials.push_back(m);
    return static_cast<int>(materials.size()) - 1;
  }
  object_ref add(const sphere_t<T>& s, int mat) {
    check_material(mat);
    spheres.push_back({s, mat});
    return note_light({shape_kind::sphere, static_cast<int>(spheres.size()) - 1}, mat);
  }
  object_ref add(const parallelogram_t<T>& q, int mat) {
    check_material(mat);
    quads.push_back({q, mat});
    return note_light({shape_kind::quad, static_cast<int>(quads.size()) - 1}, mat);
  }
  // Planes, triangles and meshes may use an emitter material: they glow where seen, but are not
  // sampled as lights (only spheres and quads have samplers).
  object_ref add(const plane_t<T>& p, int mat) {
    check_material(mat);
    planes.push_back({p, mat});
    return {shape_kind::plane, static_cast<int>(planes.size()) - 1};
  }
  object_ref add(const triangle_t<T>& t, int mat) {
    check_material(mat);
    triangles.push_back({t, mat});
    return {shape_kind::triangle, static_cast<int>(triangles.size()) - 1};
  }
  object_ref add(mesh_t<T> m, int mat) {
    check_material(mat);
    if (!m.normals.empty() && m.normals.size() != m.positions.size())
      throw error("mesh: " + std::to_string(m.normals.size()) + " normals for " +
                  std::to_string(m.positions.size()) + " vertices");
    stopwatch clock;
    mesh_object_t<T> o;
    o.bvh = triangle_bvh(m);
    o.build_seconds = clock.seconds();
    o.shape = std::move(m);
    o.material = mat;
    meshes.push_back(std::move(o));
    return {shape_kind::mesh, static_cast<int>(meshes.size()) - 1};
  }
  void add(const point_light_t<T>& l) { point_lights.push_back(l); }

  int material_index(object_ref o) const {
    switch (o.kind) {
      case shape_kind::sphere: return spheres[o.index].material;
      case shape_kind::quad: return quads[o.index].material;
      case shape_kind::plane: return planes[o.index].material;
      case shape_kind::triangle: return triangles[o.index].material;
      case shape_kind::mesh: return meshes[o.index].material;
    }
    return 0;
  }
  const material& material_of(object_ref o) const { return materials[material_index(o)]; }

  // Everything but the planes, which have no bounding box.
  std::size_t bounded_count() const {
    return spheres.size() + quads.size() + triangles.size() + meshes.size();
  }
  // Builds the object BVH if there are more than `threshold` bounded objects, or drops it.
  // Call it again after adding objects; until then nearest_hit() falls back to testing all.
  // Returns whether a BVH was built.
  bool build_acceleration(std::size_t threshold = 4);
  bool has_object_bvh() const { return !accel.tree.empty() && accel.objects.size() == bounded_count(); }

  // The camera with the image's aspect ratio, ready to generate rays.
  typename camera_t<T>::prepared prepared_camera() const {
    camera_t<T> c = camera;
    c.aspect = T(settings.width) / T(settings.height);
    return c.prepare();
  }

 private:
  void check_material(int mat) const {
    if (mat < 0 || mat >= static_cast<int>(materials.size()))
      throw error("material index " + std::to_string(mat) + " does not exist");
  }
  object_ref note_light(object_ref o, int mat) {
    if (materials[mat].kind == material_kind::emitter) lights.push_back(o);
    return o;
  }
};

using scene = scene_t<double>;

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

namespace detail {

// A mesh hit found by the float BVH, rebuilt in T from the barycentrics: the point is
// interpolated from the vertices, so it lies on the triangle up to T's rounding. The BVH tests
// in float, though, so a ray spawned from here must clear float's rounding of the vertices and
// of its own origin, or the float test would find this triangle again ("acne"): p_error is
// widened to gamma<float>(64) of the vertex magnitudes (test_scene_file: spawned rays never
// re-hit a mesh).
template <class T>
bool intersect_mesh(const mesh_object_t<T>& mo, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h,
                    std::uint32_t& triangle) {
  const ray_t<float> rf(vec3_t<float>(r.origin), vec3_t<float>(r.direction));
  triangle_bvh_hit th;
  if (!mo.bvh.intersect(rf, float(t_min), float(t_max), th)) return false;
  const T t(th.t);
  if (!(t > t_min && t < t_max)) return false;  // float rounded t_min or t_max across
  const triangle_t<T> tri = mo.shape.triangle(th.triangle);
  const T u(th.u), v(th.v), w = T(1) - u - v;
  fill_triangle_hit(tri, r, t, u, v, h);
  const vec3_t<T> magnitude = glm::abs(w * tri.a) + glm::abs(u * tri.b) + glm::abs(v * tri.c);
  h.p_error = glm::max(h.p_error, T(gamma<float>(64)) * magnitude);
  triangle = th.triangle;
  return true;
}

template <class T>
bool intersect_object(const scene_t<T>& sc, object_ref o, const ray_t<T>& r, T t_min, T t_max,
                      hit_t<T>& h, std::uint32_t& triangle) {
  switch (o.kind) {
    case shape_kind::sphere: return intersect(sc.spheres[o.index].shape, r, t_min, t_max, h);
    case shape_kind::quad: return intersect(sc.quads[o.index].shape, r, t_min, t_max, h);
    case shape_kind::plane: return intersect(sc.planes[o.index].shape, r, t_min, t_max, h);
    case shape_kind::triangle: return intersect(sc.triangles[o.index].shape, r, t_min, t_max, h);
    case shape_kind::mesh: return intersect_mesh(sc.meshes[o.index], r, t_min, t_max, h, triangle);
  }
  return false;
}

template <class T> aabb_t<T> object_bounds(const scene_t<T>& sc, object_ref o) {
  aabb_t<T> b;
  T pad_gamma = gamma<T>(4);  // the intersection routines' own rounding, generously
  switch (o.kind) {
    case shape_kind::sphere: {
      const auto& s = sc.spheres[o.index].shape;
      b.grow(s.center - vec3_t<T>(s.radius));
      b.grow(s.center + vec3_t<T>(s.radius));
      break;
    }
    case shape_kind::quad: {
      const auto& q = sc.quads[o.index].shape;
      for (const auto& p : {q.corner, q.corner + q.u, q.corner + q.v, q.corner + q.u + q.v}) b.grow(p);
      break;
    }
    case shape_kind::triangle: {
      const auto& t = sc.triangles[o.index].shape;
      for (const auto& p : {t.a, t.b, t.c}) b.grow(p);
      break;
    }
    case shape_kind::mesh:
      b = sc.meshes[o.index].shape.bounds();
      pad_gamma = T(gamma<float>(4));  // the mesh is tested in float
      break;
    case shape_kind::plane:
      break;
  }
  if (b.empty()) return b;
  const vec3_t<T> pad = pad_gamma * (glm::abs(b.lo) + glm::abs(b.hi));
  return {b.lo - pad, b.hi + pad};
}

}  // namespace detail

// One object's own intersection test, the building block for brute force and for a BVH.
template <class T>
bool intersect_object(const scene_t<T>& sc, object_ref o, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h) {
  std::uint32_t ignored = 0;
  return detail::intersect_object(sc, o, r, t_min, t_max, h, ignored);
}

template <class T> bool scene_t<T>::build_acceleration(std::size_t threshold) {
  accel = {};
  if (bounded_count() <= threshold) return false;
  stopwatch clock;
  std::vector<aabb_t<T>> boxes;
  auto push = [&](shape_kind k, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) {
      accel.objects.push_back({k, static_cast<int>(i)});
      boxes.push_back(detail::object_bounds(*this, accel.objects.back()));
    }
  };
  push(shape_kind::sphere, spheres.size());
  push(shape_kind::quad, quads.size());
  push(shape_kind::triangle, triangles.size());
  push(shape_kind::mesh, meshes.size());
  accel.tree = build_bvh(boxes);
  accel.seconds = clock.seconds();
  return true;
}

// [listing nearest-hit]
// The nearest hit along r with t in (0, t_max): each hit found shrinks the interval, so the
// result is the minimum over all objects whatever their order (or the BVH's).
template <class T>
bool nearest_hit(const scene_t<T>& sc, const ray_t<T>& r, scene_hit_t<T>& out, T t_max = infinity<T>) {
  bool found = false;
  auto visit = [&](object_ref o) {
    if (!detail::intersect_object(sc, o, r, T(0), t_max, out.h, out.triangle)) return false;
    found = true;
    t_max = out.h.t;
    out.object = o;
    return true;
  };
  for (int i = 0; i < static_cast<int>(sc.planes.size()); ++i) visit({shape_kind::plane, i});
  if (sc.has_object_bvh()) {
    bvh_intersect(sc.accel.tree, r, T(0), t_max, [&](std::uint32_t i, T& tm) {
      t_max = tm;
      const bool hit = visit(sc.accel.objects[i]);
      tm = t_max;
      return hit;
    });
  } else {
    for (int i = 0; i < static_cast<int>(sc.spheres.size()); ++i) visit({shape_kind::sphere, i});
    for (int i = 0; i < static_cast<int>(sc.quads.size()); ++i) visit({shape_kind::quad, i});
    for (int i = 0; i < static_cast<int>(sc.triangles.size()); ++i) visit({shape_kind::triangle, i});
    for (int i = 0; i < static_cast<int>(sc.meshes.size()); ++i) visit({shape_kind::mesh, i});
  }
  if (!found) return false;
  out.material = sc.material_index(out.object);
  out.shading_normal = out.h.normal;
  if (out.object.kind == shape_kind::mesh) {
    const mesh_t<T>& m = sc.meshes[out.object.index].shape;
    if (m.normals.size() == m.positions.size()) {
      const vec3_t<T> n = m.shading_normal(out.triangle, out.h.uv.x, out.h.uv.y);
      out.shading_normal = glm::dot(n, out.h.normal) < T(0) ? -n : n;  // on the geometric side
    }
  }
  return true;
}
// [end]

// Is anything in the way along a shadow segment (spawn.hpp)?
template <class T> bool occluded(const scene_t<T>& sc, const segment_t<T>& s) {
  for (const auto& o : sc.planes)
    if (occludes(o.shape, s.ray, T(0), s.t_max)) return true;
  auto blocks = [&](object_ref o) {
    if (o.kind == shape_kind::mesh) {
      const ray_t<float> rf(vec3_t<float>(s.ray.origin), vec3_t<float>(s.ray.direction));
      return sc.meshes[o.index].bvh.occluded(rf, 0.0f, float(s.t_max));
    }
    hit_t<T> ignored;
    return intersect_object(sc, o, s.ray, T(0), s.t_max, ignored);
  };
  if (sc.has_object_bvh())
    return bvh_occluded(sc.accel.tree, s.ray, T(0), s.t_max,
                        [&](std::uint32_t i) { return blocks(sc.accel.objects[i]); });
  for (const auto& o : sc.spheres)
    if (occludes(o.shape, s.ray, T(0), s.t_max)) return true;
  for (const auto& o : sc.quads)
    if (occludes(o.shape, s.ray, T(0), s.t_max)) return true;
  for (const auto& o : sc.triangles)
    if (occludes(o.shape, s.ray, T(0), s.t_max)) return true;
  for (int i = 0; i < static_cast<int>(sc.meshes.size()); ++i)
    if (blocks({shape_kind::mesh, i})) return true;
  return false;
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
  item(sc.point_lights.size(), "point light", "point lights");
  item(sc.lights.size(), "area light", "area lights");
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

// ---------------------------------------------------------------- lights (next-event estimation)
template <class T> struct light_sample_t {
  vec3_t<T> point;   // on the light
  vec3_t<T> wi;      // unit, from the shading point towards `point`
  T pdf;             // per steradian at the shading point, including the choice of this light
  rgb radiance;      // emitted towards the shading point (0 from a quad light's back)
  object_ref light;
};

// The density (per steradian) with which one light's sampler produces direction wi from x;
// zero if wi misses it. Quads: uniform in area, converted to solid angle. Spheres: uniform in
// the cone of directions that see the sphere (sampling.hpp).
template <class T>
T light_direction_pdf(const scene_t<T>& sc, object_ref l, const vec3_t<T>& x, const vec3_t<T>& wi) {
  if (l.kind == shape_kind::sphere) {
    const auto& s = sc.spheres[l.index].shape;
    return cone_t<T>(x, s.center, s.radius).pdf(wi);
  }
  const auto& q = sc.quads[l.index].shape;
  hit_t<T> h;
  if (!intersect(q, ray_t<T>(x, wi), T(0), infinity<T>, h)) return T(0);
  return area_to_solid_angle_pdf(T(1) / q.area(), h.t * h.t, glm::dot(h.normal, wi));
}

// [listing sample-light]
// Picks one light uniformly and a point on it, seen from the shading point x. The caller tests
// visibility with occluded(sc, spawn_segment(hit, sample.point)).
// u_light picks the light, u the point: both uniform in [0,1) (stratified if the caller likes).
template <class T>
std::optional<light_sample_t<T>> sample_light(const scene_t<T>& sc, const vec3_t<T>& x, T u_light,
                                              const vec2_t<T>& u) {
  if (sc.lights.empty()) return std::nullopt;
  const int n = static_cast<int>(sc.lights.size());
  const object_ref l = sc.lights[std::clamp(static_cast<int>(u_light * T(n)), 0, n - 1)];
  const rgb Le = sc.material_of(l).radiance;
  light_sample_t<T> s{};
  s.light = l;
  if (l.kind == shape_kind::quad) {
    const auto& q = sc.quads[l.index].shape;
    s.point = sample_parallelogram(u, q.corner, q.u, q.v);
    const vec3_t<T> to = s.point - x;
    const T d2 = length2(to);
    s.wi = normalize_or_zero(to);
    const T cos_l = -glm::dot(q.normal(), s.wi);  // > 0: x sees the light's front
    s.pdf = area_to_solid_angle_pdf(T(1) / q.area(), d2, cos_l) / T(n);
    s.radiance = cos_l > T(0) ? Le : rgb(0);
  } else {
    const auto& sp = sc.spheres[l.index].shape;
    const cone_t<T> cone(x, sp.center, sp.radius);
    s.wi = cone.sample(u);
    hit_t<T> h;  // the point where that direction meets the sphere
    if (!intersect(sp, ray_t<T>(x, s.wi), T(0), infinity<T>, h)) return std::nullopt;
    s.point = h.p;
    s.pdf = cone.pdf(s.wi) / T(n);
    s.radiance = h.front_face ? Le : rgb(0);
  }
  if (!(s.pdf > T(0)) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}
// [end]

template <class T>
std::optional<light_sample_t<T>> sample_light(const scene_t<T>& sc, const vec3_t<T>& x, rng& g) {
  const T u_light = T(g.uniform());
  return sample_light(sc, x, u_light, vec2_t<T>(g.uniform2()));
}

// The density with which sample_light() produces wi from x, summed over the lights (for MIS).
template <class T> T light_pdf(const scene_t<T>& sc, const vec3_t<T>& x, const vec3_t<T>& wi) {
  if (sc.lights.empty()) return T(0);
  T sum = 0;
  for (object_ref l : sc.lights) sum += light_direction_pdf(sc, l, x, wi);
  return sum / T(sc.lights.size());
}

}  // namespace zraka

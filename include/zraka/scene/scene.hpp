#pragma once
// A scene described in code (book 2.2, 2.3, 4.1): materials, objects that name their material by
// index, lights that are not shapes (lights/light.hpp: point lights, a course's own), a background
// colour, the camera and the render settings (the thesis's "hyper-parameters", Def 4.1.1).
// The scene file loader (scene_file.hpp) fills the same struct. This header holds the data;
// scene_query.hpp asks it for hits, lights.hpp for its lights.
//
// Objects: spheres, quads (a box is six of them), infinite planes, single triangles, meshes
// (each with its own triangle BVH, built when the mesh is added) and user shapes
// (user_shape.hpp: any shape a program defines). visit_object() is the one place that knows the
// list of kinds; everything else (intersection, bounds, light sampling) asks it.
// build_acceleration() makes an object BVH over the bounded objects when there are enough of
// them to pay: bvh.hpp's binary tree, collapsed to wide_bvh.hpp's four-wide nodes, which
// nearest_hit() and occluded() walk; planes are infinite and are always tested.
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/accel/wide_bvh.hpp>
#include <zraka/cameras/camera.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/mesh.hpp>
#include <zraka/geometry/plane.hpp>
#include <zraka/geometry/quad.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/geometry/triangle.hpp>
#include <zraka/geometry/user_shape.hpp>
#include <zraka/lights/environment.hpp>
#include <zraka/lights/light.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/media/medium.hpp>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace zraka {

// Def 4.1.1's hyper-parameters.
struct render_settings {
  int width = 320, height = 240;
  int spp = 16;          // samples (primary rays) per pixel
  int max_depth = 8;     // bounces before a path stops (Whitted: depth of the ray tree)
  std::uint64_t seed = 1;
  std::string integrator;  // a scene file's settings.integrator, by name (empty: the program's own)
};

enum class shape_kind { sphere, quad, plane, triangle, mesh, user };
struct object_ref {
  shape_kind kind;
  int index;  // into the scene's vector of that kind
  bool operator==(const object_ref&) const = default;
};

// An object: a shape and the index of its material.
template <class S> struct object_t {
  S shape;
  int material = 0;
};

// A mesh object: the triangles (in T, for exact hit points and shading normals) and their BVH
// (in float, triangle_bvh.hpp), built once when the mesh is added.
template <class T> struct mesh_object_t {
  mesh_t<T> shape;
  triangle_bvh bvh;
  int material = 0;
  double build_seconds = 0;
};

template <class T> using user_shape_ptr = std::shared_ptr<const user_shape_t<T>>;

template <class T> struct scene_t {
  // The object BVH over the bounded objects, when build_acceleration() decided to make one.
  struct acceleration {
    bvh_t<T> tree;                    // the binary tree (bvh.hpp), kept for its readable walk
    wide_bvh wide;                    // the same tree four-wide: what queries walk
    std::vector<object_ref> objects;  // the BVH's primitive i is objects[i]
    std::vector<quad_plane_t<T>> quad_planes;  // quad i's plane (quad.hpp), computed once
    double seconds = 0;
  };

  std::vector<material> materials;
  std::vector<std::string> material_names;  // by index, from the scene file; may be short or ""
  std::vector<object_t<sphere_t<T>>> spheres;
  std::vector<object_t<parallelogram_t<T>>> quads;
  std::vector<object_t<plane_t<T>>> planes;
  std::vector<object_t<triangle_t<T>>> triangles;
  std::vector<mesh_object_t<T>> meshes;
  std::vector<object_t<user_shape_ptr<T>>> user_shapes;
  std::vector<std::string> user_shape_labels;  // by index, from the scene file: "object 'ring'", "objects[2]"
  // The lights that are not shapes (lights/light.hpp: point lights, a course's own kinds), in the
  // order they were added; glowing objects are lights too (scene/lights.hpp).
  std::vector<light> lights;
  rgb background{0};               // radiance of rays that leave the scene (hit only)
  // The environment light (environment.hpp): when set, rays that leave the scene see it instead
  // of the background, and the lights sample it (lights.hpp).
  std::shared_ptr<const environment_map> environment;
  rgb ambient{0};                  // Whitted only: Phong's ambient light I_a
  camera_t<T> camera;
  render_settings settings;
  acceleration accel;              // empty: every object is tested
  // Participating media (book 6.1): a material's `interior` names one by index; global_medium
  // fills everything outside those shapes (fog: the camera starts in it), -1 for clear air.
  std::vector<medium> media;
  int global_medium = -1;

  // "fog, milk": for the renderers that cannot trace media and refuse the scene by name.
  std::string media_names() const {
    std::string s;
    for (const medium& m : media) s += (s.empty() ? "" : ", ") + m.name;
    return s;
  }

  // "material 'gold'" as the scene file names it, else "material 3": for refusals and errors.
  std::string material_label(int i) const {
    if (i >= 0 && std::size_t(i) < material_names.size() && !material_names[std::size_t(i)].empty())
      return "material '" + material_names[std::size_t(i)] + "'";
    return "material " + std::to_string(i);
  }

  // User shape i as the scene file names it ("object 'ring'", or its place "objects[2]"), else
  // "user shape 2": for refusals.
  std::string user_shape_label(std::size_t i) const {
    if (i < user_shape_labels.size() && !user_shape_labels[i].empty()) return user_shape_labels[i];
    return "user shape " + std::to_string(i);
  }

  // The special members and add_material are defined below the class, so that with
  // zraka::compiled they are compiled once (compiled.hpp), not in every program that has a scene.
  scene_t() = default;
  scene_t(const scene_t&);
  scene_t(scene_t&&) noexcept;
  scene_t& operator=(const scene_t&);
  scene_t& operator=(scene_t&&) noexcept;
  ~scene_t();

  int add_material(const material& m);
  object_ref add(const sphere_t<T>& s, int mat) { return push(spheres, s, mat, shape_kind::sphere); }
  object_ref add(const parallelogram_t<T>& q, int mat) { return push(quads, q, mat, shape_kind::quad); }
  // An infinite plane may glow, but it cannot be sampled as a light (it has no finite area to
  // pick a point on): its light is counted only where a ray finds it (lights.hpp says so).
  object_ref add(const plane_t<T>& p, int mat) { return push(planes, p, mat, shape_kind::plane); }
  object_ref add(const triangle_t<T>& t, int mat) { return push(triangles, t, mat, shape_kind::triangle); }
  object_ref add(mesh_t<T> m, int mat);  // builds the mesh's own BVH
  object_ref add(user_shape_ptr<T> s, int mat) {
    if (!s) throw error("user shape: null");
    const aabb_t<T> b = s->bounds();
    if (b.empty() || !is_finite(b.lo) || !is_finite(b.hi))
      throw error("user shape '" + s->name() + "': its bounds must be a finite, non-empty box");
    return push(user_shapes, std::move(s), mat, shape_kind::user);
  }
  void add(light l) { lights.push_back(std::move(l)); }  // a point light: add(point_light_t<T>{p, I})
  int add_medium(const medium& m) {
    m.check();
    media.push_back(m);
    return static_cast<int>(media.size()) - 1;
  }

  int material_index(object_ref o) const;
  const material& material_of(object_ref o) const { return materials[std::size_t(material_index(o))]; }

  // Everything but the planes, which have no bounding box.
  std::size_t bounded_count() const {
    return spheres.size() + quads.size() + triangles.size() + meshes.size() + user_shapes.size();
  }
  // Builds the object BVH if there are more than `threshold` bounded objects, or drops it.
  // Call it again after adding objects; until then nearest_hit() falls back to testing all.
  // Returns whether a BVH was built.
  bool build_acceleration(std::size_t threshold = 4);
  bool has_object_bvh() const { return !accel.wide.empty() && accel.objects.size() == bounded_count(); }

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
  template <class V, class S> object_ref push(V& v, S s, int mat, shape_kind k) {
    check_material(mat);
    v.push_back({std::move(s), mat});
    return {k, static_cast<int>(v.size()) - 1};
  }
};

template <class T> scene_t<T>::scene_t(const scene_t&) = default;
template <class T> scene_t<T>::scene_t(scene_t&&) noexcept = default;
template <class T> scene_t<T>& scene_t<T>::operator=(const scene_t&) = default;
template <class T> scene_t<T>& scene_t<T>::operator=(scene_t&&) noexcept = default;
template <class T> scene_t<T>::~scene_t() = default;

template <class T> int scene_t<T>::add_material(const material& m) {
  materials.push_back(m);
  return static_cast<int>(materials.size()) - 1;
}

template <class T> object_ref scene_t<T>::add(mesh_t<T> m, int mat) {
  check_material(mat);
  if (!m.texcoords.empty() && m.texcoords.size() != m.positions.size())
    throw error("mesh: " + std::to_string(m.texcoords.size()) + " texture coordinates for " +
                std::to_string(m.positions.size()) + " positions");
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

using scene = scene_t<double>;

// [listing visit-object]
// The one place that lists the shape kinds: calls f with the object o refers to (an object_t
// of a sphere, quad, plane, triangle or user shape, or a mesh_object_t). A new kind is one more
// line here and an overload of intersect/bounds for its object.
template <class T, class F> decltype(auto) visit_object(const scene_t<T>& sc, object_ref o, F&& f) {
  const auto i = std::size_t(o.index);
  switch (o.kind) {
    case shape_kind::sphere: return f(sc.spheres[i]);
    case shape_kind::quad: return f(sc.quads[i]);
    case shape_kind::plane: return f(sc.planes[i]);
    case shape_kind::triangle: return f(sc.triangles[i]);
    case shape_kind::mesh: return f(sc.meshes[i]);
    case shape_kind::user: break;
  }
  return f(sc.user_shapes[i]);
}
// Calls f(object_ref) for every object of the scene, planes first.
template <class T, class F> void for_each_object(const scene_t<T>& sc, F&& f) {
  auto all = [&](shape_kind k, std::size_t n) {
    for (std::size_t i = 0; i < n; ++i) f(object_ref{k, int(i)});
  };
  all(shape_kind::plane, sc.planes.size());
  all(shape_kind::sphere, sc.spheres.size());
  all(shape_kind::quad, sc.quads.size());
  all(shape_kind::triangle, sc.triangles.size());
  all(shape_kind::mesh, sc.meshes.size());
  all(shape_kind::user, sc.user_shapes.size());
}
// [end]

template <class T> int scene_t<T>::material_index(object_ref o) const {
  return visit_object(*this, o, [](const auto& obj) { return obj.material; });
}

// ---------------------------------------------------------------- each kind's intersection and box
// A user shape is called through its interface.
template <class T>
bool intersect(const user_shape_ptr<T>& s, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h) {
  return s->intersect(r, t_min, t_max, h);
}

namespace detail {

// One object's nearest hit in (t_min, t_max); meshes also say which triangle.
template <class S, class T>
bool intersect_one(const object_t<S>& o, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h,
                   std::uint32_t&) {
  return intersect(o.shape, r, t_min, t_max, h);
}

// A mesh hit found by the float BVH, rebuilt in T from the barycentrics: the point is
// interpolated from the vertices, so it lies on the triangle up to T's rounding. The BVH tests
// in float, though, so a ray spawned from here must clear float's rounding of the vertices and
// of its own origin, or the float test would find this triangle again ("acne"): p_error is
// widened to gamma<float>(64) of the vertex magnitudes (test_scene_file: spawned rays never
// re-hit a mesh).
template <class T>
bool intersect_one(const mesh_object_t<T>& mo, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h,
                   std::uint32_t& triangle) {
  const ray_t<float> rf(vec3_t<float>(r.origin), vec3_t<float>(r.direction));
  triangle_bvh_hit th;
  if (!mo.bvh.intersect(rf, float(t_min), float(t_max), th)) return false;
  const T t(th.t);
  if (!(t > t_min && t < t_max)) return false;  // float rounded t_min or t_max across
  const triangle_t<T> tri = mo.shape.triangle(th.triangle);
  const T u(th.u), v(th.v), w = T(1) - u - v;
  fill_triangle_hit(tri, r, t, u, v, h);
  const vec3_t<T> magnitude = abs3(w * tri.a) + abs3(u * tri.b) + abs3(v * tri.c);
  h.p_error = glm::max(h.p_error, T(gamma<float>(64)) * magnitude);
  triangle = th.triangle;
  return true;
}

// Does the object block the segment (0, t_max)? Meshes skip rebuilding the hit.
template <class S, class T> bool blocks_one(const object_t<S>& o, const ray_t<T>& r, T t_max) {
  if constexpr (requires { occludes(o.shape, r, T(0), t_max); }) {
    return occludes(o.shape, r, T(0), t_max);  // the shape's own test, which builds no hit
  } else {
    hit_t<T> ignored;
    return intersect(o.shape, r, T(0), t_max, ignored);
  }
}
template <class T> bool blocks_one(const mesh_object_t<T>& mo, const ray_t<T>& r, T t_max) {
  const ray_t<float> rf(vec3_t<float>(r.origin), vec3_t<float>(r.direction));
  return mo.bvh.occluded(rf, 0.0f, float(t_max));
}

template <class T> aabb_t<T> shape_bounds(const sphere_t<T>& s) {
  return {s.center - vec3_t<T>(s.radius), s.center + vec3_t<T>(s.radius)};
}
template <class T> aabb_t<T> shape_bounds(const parallelogram_t<T>& q) {
  aabb_t<T> b;
  for (const auto& p : {q.corner, q.corner + q.u, q.corner + q.v, q.corner + q.u + q.v}) b.grow(p);
  return b;
}
template <class T> aabb_t<T> shape_bounds(const triangle_t<T>& t) {
  aabb_t<T> b;
  for (const auto& p : {t.a, t.b, t.c}) b.grow(p);
  return b;
}
template <class T> aabb_t<T> shape_bounds(const plane_t<T>&) { return {}; }  // unbounded
template <class T> aabb_t<T> shape_bounds(const user_shape_ptr<T>& s) { return s->bounds(); }

// The box padded by the intersection routines' own rounding, generously.
template <class T> aabb_t<T> padded(const aabb_t<T>& b, T pad_gamma) {
  if (b.empty()) return b;
  const vec3_t<T> pad = pad_gamma * (abs3(b.lo) + abs3(b.hi));
  return {b.lo - pad, b.hi + pad};
}
template <class S, class T> aabb_t<T> bounds_one(const object_t<S>& o, T) {
  return padded(shape_bounds(o.shape), gamma<T>(4));
}
template <class T> aabb_t<T> bounds_one(const mesh_object_t<T>& mo, T) {
  return padded(mo.shape.bounds(), T(gamma<float>(4)));  // the mesh is tested in float
}

}  // namespace detail

// One object's own intersection test, the building block for brute force and for a BVH.
// A quad's plane comes from the object BVH when it was built with it.
template <class T>
bool intersect_object(const scene_t<T>& sc, object_ref o, const ray_t<T>& r, T t_min, T t_max,
                      hit_t<T>& h, std::uint32_t& triangle) {
  const auto i = std::size_t(o.index);
  if (o.kind == shape_kind::quad && i < sc.accel.quad_planes.size())
    return intersect(sc.quads[i].shape, sc.accel.quad_planes[i], r, t_min, t_max, h);
  return visit_object(sc, o, [&](const auto& obj) { return detail::intersect_one(obj, r, t_min, t_max, h, triangle); });
}
template <class T>
bool intersect_object(const scene_t<T>& sc, object_ref o, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h) {
  std::uint32_t ignored = 0;
  return intersect_object(sc, o, r, t_min, t_max, h, ignored);
}
template <class T> bool object_blocks(const scene_t<T>& sc, object_ref o, const ray_t<T>& r, T t_max) {
  const auto i = std::size_t(o.index);
  if (o.kind == shape_kind::quad && i < sc.accel.quad_planes.size())
    return occludes(sc.quads[i].shape, sc.accel.quad_planes[i], r, T(0), t_max);
  return visit_object(sc, o, [&](const auto& obj) { return detail::blocks_one(obj, r, t_max); });
}
// The object's box, padded for rounding; empty for a plane.
template <class T> aabb_t<T> object_bounds(const scene_t<T>& sc, object_ref o) {
  return visit_object(sc, o, [](const auto& obj) { return detail::bounds_one(obj, T(0)); });
}

template <class T> bool scene_t<T>::build_acceleration(std::size_t threshold) {
  accel = {};
  if (bounded_count() <= threshold) return false;
  stopwatch clock;
  std::vector<aabb_t<T>> boxes;
  for_each_object(*this, [&](object_ref o) {
    if (o.kind == shape_kind::plane) return;
    accel.objects.push_back(o);
    boxes.push_back(object_bounds(*this, o));
  });
  accel.tree = build_bvh(boxes);
  accel.wide = make_wide_bvh(accel.tree);
  for (const auto& q : quads) accel.quad_planes.emplace_back(q.shape);
  accel.seconds = clock.seconds();
  return true;
}

ZRAKA_INSTANCE(struct scene_t<double>)  // compiled.hpp

}  // namespace zraka

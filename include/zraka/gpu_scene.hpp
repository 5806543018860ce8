#pragma once
// A scene packed into flat arrays for a GPU kernel (book 4.3, the real-time chapter): what moves
// from the CPU to kernels/pathtrace.cl. A kernel has no pointers, no std::vector, no virtual
// calls and no recursion, so the scene becomes plain arrays of fixed-size records that name each
// other by index (an object's material, a light's object, a BVH node's children).
//
// Layout rules shared with the kernel (which declares the same structs in OpenCL C):
// * every 3-vector is a gpu_float4 (16 bytes, 16-aligned), never a float3: OpenCL's float3 is
//   16 bytes too but C++ has no such type, and a 12-byte host vec3 would shift every field after
//   it. Sizes and offsets are static_assert'ed here and checked again in the kernel;
// * integers are 32 bits (cl_int/cl_uint), padded to a multiple of 16 bytes;
// * geometry is float: what GPUs do fast. The CPU tracer is double, so the two images agree in
//   distribution, not bit for bit (tests/test_realtime.cpp states the bound).
// Triangles (meshes and lone triangles) go into one triangle BVH (triangle_bvh.hpp), whose
// 4-wide nodes are copied as they are: they were laid out as flat arrays for SIMD already.
// Spheres, quads and planes are tested one by one (the course's scenes have a few dozen).
// What the kernel does differently is listed in gpu_scene::notes: a phong material (the Whitted
// tracer's) becomes lambertian with its kd; point lights are ignored, as by path.hpp; mesh
// vertex normals too (the kernel shades triangles flat).
//
// features() says what a scene uses and build_options() turns that into -D switches, so the
// kernel compiled for a scene of diffuse spheres has no triangle, BVH or glass code at all.
#include <zraka/error.hpp>
#include <zraka/lights.hpp>
#include <zraka/path.hpp>
#include <zraka/scene.hpp>
#include <zraka/triangle_bvh.hpp>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace zraka {

// [listing gpu-structs]
struct alignas(16) gpu_float4 {
  float x = 0, y = 0, z = 0, w = 0;
};
struct gpu_sphere {
  gpu_float4 center_radius;  // w: radius
  std::int32_t material, pad[3];
};
struct gpu_quad {
  gpu_float4 corner, u, v;
  gpu_float4 normal_area;  // unit normal of u x v; w: area
  std::int32_t material, pad[3];
};
struct gpu_plane {
  gpu_float4 point, normal;  // unit normal
  std::int32_t material, pad[3];
};
struct gpu_triangle {        // packed_triangle (the watertight test's data), in the BVH's leaf order
  gpu_float4 a, b, c;        // the vertices
  std::uint32_t id;          // index in the input, the tie-breaker of triangle_bvh
  std::int32_t material, pad[2];
};
struct gpu_node4 {           // triangle_bvh_node4, byte for byte
  float box[6][4];
  std::uint32_t child[4], count[4];
};
enum gpu_material_kind : std::int32_t { gpu_lambertian = 0, gpu_metal = 1, gpu_dielectric = 2, gpu_emitter = 3 };
struct gpu_material {
  gpu_float4 albedo_a, albedo_b;  // solid: a; checker: a and b
  gpu_float4 radiance;            // emitted from the front face (both faces if two_sided)
  std::int32_t kind, checker, two_sided, pad;
  float fuzz, ior, cell, pad2;
};
struct gpu_light {           // an emitting sphere (kind 0) or quad (kind 1)
  std::int32_t kind, index;
};
struct gpu_camera {          // camera_t::prepared in float
  gpu_float4 origin, u, v, corner, horizontal, vertical;
  float lens_radius, pad[3];
};
// [end]

static_assert(sizeof(gpu_float4) == 16 && alignof(gpu_float4) == 16);
static_assert(sizeof(gpu_sphere) == 32 && offsetof(gpu_sphere, material) == 16);
static_assert(sizeof(gpu_quad) == 80 && offsetof(gpu_quad, normal_area) == 48 &&
              offsetof(gpu_quad, material) == 64);
static_assert(sizeof(gpu_plane) == 48 && offsetof(gpu_plane, material) == 32);
static_assert(sizeof(gpu_triangle) == 64 && offsetof(gpu_triangle, id) == 48 &&
              offsetof(gpu_triangle, material) == 52);
static_assert(sizeof(gpu_node4) == sizeof(triangle_bvh_node4) && sizeof(gpu_node4) == 128 &&
              offsetof(gpu_node4, child) == 96 && offsetof(gpu_node4, count) == 112);
static_assert(sizeof(gpu_material) == 80 && offsetof(gpu_material, radiance) == 32 &&
              offsetof(gpu_material, kind) == 48 && offsetof(gpu_material, fuzz) == 64);
static_assert(sizeof(gpu_light) == 8);
static_assert(sizeof(gpu_camera) == 112 && offsetof(gpu_camera, lens_radius) == 96);

// What a scene uses: each flag is one -D switch of the kernel.
struct gpu_features {
  bool spheres = false, quads = false, planes = false, triangles = false;
  bool metal = false, dielectric = false, checker = false, emitters = false;
  bool thin_lens = false;
  bool next_event = true;  // path.hpp's default
  int max_depth = 8;
  bool weak_seed = false;  // the thesis's per-pixel seed, for the book's before/after figure
};

struct gpu_scene {
  std::vector<gpu_sphere> spheres;
  std::vector<gpu_quad> quads;
  std::vector<gpu_plane> planes;
  std::vector<gpu_triangle> triangles;
  std::vector<gpu_node4> nodes;
  std::vector<gpu_material> materials;
  std::vector<gpu_light> lights;
  gpu_camera camera;
  gpu_float4 background;
  gpu_features features;
  std::vector<std::string> notes;  // what the kernel does differently for this scene
};

template <class T> gpu_float4 to_gpu(const vec3_t<T>& v, double w = 0) {
  return {float(v.x), float(v.y), float(v.z), float(w)};
}
inline gpu_float4 to_gpu(const rgb& c, float w = 0) { return {c.x, c.y, c.z, w}; }

namespace detail {
template <class P> gpu_camera camera_to_gpu(const P& c) {
  gpu_camera g;
  g.origin = to_gpu(c.origin);
  g.u = to_gpu(c.u);
  g.v = to_gpu(c.v);
  g.corner = to_gpu(c.corner);
  g.horizontal = to_gpu(c.horizontal);
  g.vertical = to_gpu(c.vertical);
  g.lens_radius = float(c.lens_radius);
  g.pad[0] = g.pad[1] = g.pad[2] = 0;
  return g;
}
}  // namespace detail
inline gpu_camera to_gpu(const camera_t<double>::prepared& c) { return detail::camera_to_gpu(c); }
inline gpu_camera to_gpu(const camera_t<float>::prepared& c) { return detail::camera_to_gpu(c); }

inline gpu_material to_gpu(const material& m) {
  gpu_material g{};
  switch (m.kind) {
    case material_kind::lambertian: g.kind = gpu_lambertian; break;
    case material_kind::fuzzy_metal: g.kind = gpu_metal; break;
    case material_kind::dielectric: g.kind = gpu_dielectric; break;
    case material_kind::emitter: g.kind = gpu_emitter; break;
    case material_kind::phong:  // pack_scene() notes it: the Whitted tracer's material
      g.kind = gpu_lambertian;
      g.albedo_a = g.albedo_b = to_gpu(m.kd);
      break;
  }
  if (m.kind != material_kind::phong) {
    g.albedo_a = to_gpu(m.albedo.a);
    g.albedo_b = to_gpu(m.albedo.b);
    g.checker = m.albedo.type == texture::kind::checker ? 1 : 0;
  }
  g.cell = float(m.albedo.cell);
  g.radiance = to_gpu(m.radiance);
  g.two_sided = m.two_sided ? 1 : 0;
  g.fuzz = float(m.fuzz);
  g.ior = float(m.ior);
  return g;
}

// [listing gpu-pack]
// The scene as arrays, the camera prepared for a width x height image, and the features used.
template <class T>
gpu_scene pack_scene(const scene_t<T>& sc, int width, int height, int max_depth, bool next_event = true) {
  if (width < 1 || height < 1) throw error("image size must be positive");
  gpu_scene g;
  auto& f = g.features;
  // C++ code cannot run in the kernel: refuse it by name, before anything is built.
  if (!sc.user_shapes.empty())
    throw error("realtime: the scene has a user shape ('" + sc.user_shapes[0].shape->name() +
                "'), which the OpenCL kernel cannot intersect; render it with pathtrace");
  for_each_object(sc, [&](object_ref o) {
    const material& m = sc.material_of(o);
    if (is_custom(m))
      throw error("realtime: material " + std::to_string(sc.material_index(o)) + " is a custom BSDF ('" +
                  m.bsdf->name() + "'), which the OpenCL kernel cannot run; render it with pathtrace");
  });
  for (const material& m : sc.materials) {
    g.materials.push_back(to_gpu(m));
    if (m.kind == material_kind::phong)
      g.notes.push_back("material " + std::to_string(g.materials.size() - 1) +
                        " is phong: the kernel renders it as lambertian with its kd");
  }
  auto note_material = [&](int mi) {
    const material& m = sc.materials[std::size_t(mi)];
    f.metal |= m.kind == material_kind::fuzzy_metal;
    f.dielectric |= m.kind == material_kind::dielectric;
    f.checker |= m.albedo.type == texture::kind::checker && m.kind != material_kind::dielectric &&
                 m.kind != material_kind::emitter;
    f.emitters |= emits(m);
  };
  for (const auto& s : sc.spheres) {
    g.spheres.push_back({to_gpu(s.shape.center, s.shape.radius), s.material, {0, 0, 0}});
    note_material(s.material);
  }
  for (const auto& q : sc.quads) {
    g.quads.push_back({to_gpu(q.shape.corner), to_gpu(q.shape.u), to_gpu(q.shape.v),
                       to_gpu(q.shape.normal(), q.shape.area()), q.material, {0, 0, 0}});
    note_material(q.material);
  }
  for (const auto& p : sc.planes) {
    g.planes.push_back({to_gpu(p.shape.point), to_gpu(p.shape.normal), p.material, {0, 0, 0}});
    note_material(p.material);
  }
  // Every triangle, lone or in a mesh, goes into one BVH; tri_material maps input index -> material.
  std::vector<triangle_t<float>> tris;
  std::vector<std::int32_t> tri_material;
  for (const auto& t : sc.triangles) {
    tris.push_back({vec3_t<float>(t.shape.a), vec3_t<float>(t.shape.b), vec3_t<float>(t.shape.c)});
    tri_material.push_back(t.material);
    note_material(t.material);
  }
  for (const auto& mo : sc.meshes) {
    for (std::size_t i = 0; i < mo.shape.triangle_count(); ++i) {
      const auto t = mo.shape.triangle(i);
      tris.push_back({vec3_t<float>(t.a), vec3_t<float>(t.b), vec3_t<float>(t.c)});
      tri_material.push_back(mo.material);
    }
    note_material(mo.material);
  }
  if (!tris.empty()) {
    const triangle_bvh bvh(tris);
    for (const packed_triangle& p : bvh.triangles())
      g.triangles.push_back({to_gpu(p.a), to_gpu(p.b), to_gpu(p.c), p.id,
                             tri_material[p.id], {0, 0}});
    for (const triangle_bvh_node4& n : bvh.nodes()) {
      gpu_node4 o;
      static_assert(sizeof o == sizeof n);
      std::memcpy(&o, &n, sizeof o);
      g.nodes.push_back(o);
    }
  }
  const light_set_t<T> light_list(sc, light_selection::uniform);
  for (const auto& l : light_list.lights())
    if (l.point < 0 && (l.object.kind == shape_kind::sphere || l.object.kind == shape_kind::quad))
      g.lights.push_back({l.object.kind == shape_kind::sphere ? 0 : 1, l.object.index});
  if (!sc.point_lights.empty())
    g.notes.push_back(std::to_string(sc.point_lights.size()) +
                      " point light(s) ignored, as path.hpp does (they have no area to hit)");
  for (const auto& mo : sc.meshes)
    if (!mo.shape.normals.empty()) {
      g.notes.push_back("mesh vertex normals ignored: the kernel shades triangles flat");
      break;
    }
  if (g.lights.empty() && !f.emitters && sc.background == rgb(0))
    g.notes.push_back("no area light, no glowing surface and a black background: the image is "
                      "black (point lights need the Whitted tracer)");

  camera_t<T> c = sc.camera;
  c.aspect = T(width) / T(height);
  g.camera = to_gpu(c.prepare());
  g.background = to_gpu(sc.background);
  f.spheres = !g.spheres.empty();
  f.quads = !g.quads.empty();
  f.planes = !g.planes.empty();
  f.triangles = !g.nodes.empty();
  f.thin_lens = sc.camera.aperture > 0;
  f.next_event = next_event;
  f.max_depth = max_depth;
  return g;
}
// [end]

// [listing gpu-options]
// The -D switches for a scene's features; all_features compiles every code path (the
// benchmark's comparison, and what one kernel for every scene would be).
inline std::string build_options(const gpu_features& f, bool all_features = false) {
  std::string o = "-cl-std=CL1.2";
  auto flag = [&](bool on, const char* name) {
    if (on || all_features) o += std::string(" -D") + name;
  };
  flag(f.spheres, "HAS_SPHERES");
  flag(f.quads, "HAS_QUADS");
  flag(f.planes, "HAS_PLANES");
  flag(f.triangles, "HAS_TRIANGLES");  // the triangle BVH comes with them
  flag(f.metal, "HAS_METAL");
  flag(f.dielectric, "HAS_DIELECTRIC");
  flag(f.checker, "HAS_CHECKER");
  flag(f.emitters, "HAS_EMITTERS");
  flag(f.thin_lens, "HAS_THIN_LENS");
  if (f.next_event) o += " -DNEE";  // an algorithm choice, not a feature: never forced on
  if (f.weak_seed) o += " -DWEAK_SEED";
  o += " -DMAX_DEPTH=" + std::to_string(f.max_depth);
  return o;
}
// [end]

// [listing reference-sample]
// The CPU twin of one kernel sample: the same pixel jitter and lens draws from the same stream
// rng(seed, pixel, sample), then path.hpp's path tracer in double (NEE as its default).
template <class T>
rgb reference_sample(const scene_t<T>& sc, const light_set_t<T>& lights,
                     const typename camera_t<T>::prepared& cam, int x, int y, int width, int height, rng& g,
                     const path_options& opt, std::uint64_t& rays) {
  const T sx = (T(x) + T(g.uniform())) / T(width);
  const T sy = (T(y) + T(g.uniform())) / T(height);
  T lu = 0, lv = 0;
  if (cam.lens_radius > T(0)) {
    lu = T(g.uniform());
    lv = T(g.uniform());
  }
  return path_radiance(sc, lights, cam.generate(sx, sy, lu, lv), g, opt, rays);
}
// [end]

}  // namespace zraka

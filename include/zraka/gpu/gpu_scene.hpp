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
// Triangles (meshes and lone triangles) go into one triangle BVH (triangle_bvh.hpp) with four
// children a node (triangle_bvh4: the kernel tests a node's boxes as float4), whose nodes are
// copied as they are: they were laid out as flat arrays for SIMD already.
// Spheres and planes are tested one by one, quads four at a time (gpu_quad4): the course's
// scenes have a few dozen.
// The lights are lights.hpp's light_set_t, packed as it is: one record per light (its kind,
// object, material, selection CDF and probability, area), the triangles of triangle and mesh
// lights with their area CDF in a side table, and in every sphere, quad and triangle the index
// of its light (or -1), which a BSDF-sampled ray that hits a light needs for MIS.
// The appearance of chapter 5: the rough materials (microfacet.hpp) with their Fresnel presets,
// image and noise textures (a texture table, the images' texels in one array) and the
// environment light, whose map and sampling tables are packed from environment.hpp's own.
// What the kernel cannot run is refused here, by name, before anything is built: a user shape
// (C++ intersection code), a custom BSDF (C++ scattering code), a light kind without a pack()
// (lights/light.hpp: a course's light), participating media.
//
// The features a scene uses become -D switches (build_options()), so the kernel compiled for a
// scene of diffuse spheres has no triangle, BVH, glass or Phong code at all.
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/core/error.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/lights/environment.hpp>
#include <zraka/lights/light.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/render_it_with.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/textures/noise.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace zraka {

// [listing gpu-structs]
struct alignas(16) gpu_float4 {
  float x = 0, y = 0, z = 0, w = 0;
};
// light: the object's index in the light table, or -1 (not a sampled light)
struct gpu_sphere {
  gpu_float4 center_radius;  // w: radius
  std::int32_t material, light, pad[2];
};
struct gpu_quad {            // what a hit record and a light sample need
  gpu_float4 corner, u, v;
  gpu_float4 normal_area;  // unit normal of u x v; w: area
  std::int32_t material, light, pad[2];
};
// Four quads lane by lane (a structure of arrays): the kernel tests them in one step of float4
// arithmetic, each lane quad.hpp's test on gpu_quad's numbers and w, quad_plane_t::w (n / |n|^2
// for the plane coordinates). Lanes past the last quad are 0: t = 0/0, never hit.
struct gpu_quad4 {
  gpu_float4 nx, ny, nz, qx, qy, qz, ux, uy, uz, vx, vy, vz, wx, wy, wz;
};
struct gpu_plane {
  gpu_float4 point, normal;  // unit normal
  std::int32_t material, pad[3];
};
struct gpu_triangle {        // packed_triangle (the watertight test's data), in the BVH's leaf order
  gpu_float4 a, b, c;        // the vertices
  std::uint32_t id;          // index in the input, the tie-breaker of triangle_bvh
  std::int32_t material, light, pad;
};
struct gpu_node4 {           // triangle_bvh_node4, byte for byte
  float box[6][4];
  std::uint32_t child[4], count[4];
};
enum gpu_material_kind : std::int32_t {
  gpu_lambertian = 0, gpu_metal = 1, gpu_dielectric = 2, gpu_emitter = 3, gpu_phong = 4,
  gpu_rough_conductor = 5, gpu_rough_dielectric = 6
};
struct gpu_material {
  gpu_float4 albedo_a, albedo_b;  // solid: a; checker: a and b; phong: kd and ks
  gpu_float4 radiance;            // emitted from the front face (both faces if two_sided)
  std::int32_t kind, checker, two_sided, schlick;  // checker: 1 world, 2 uv; schlick: F0 in eta
  float fuzz, ior, cell, shininess;
  gpu_float4 eta, k;              // rough_conductor: the complex index per channel (or F0)
  std::int32_t albedo_texture, roughness_texture, pad[2];  // index in textures, or -1
  float roughness, pad2[3];       // rough_*: the GGX alpha (when roughness_texture is -1)
};
// texture.hpp's texture, for an image or noise albedo and any roughness map (a material's
// solid or checker albedo stays in the material itself).
enum gpu_texture_kind : std::int32_t {
  gpu_tex_solid = 0, gpu_tex_checker = 1, gpu_tex_image = 2, gpu_tex_noise = 3, gpu_tex_checker_uv = 4
};
struct gpu_texture {
  gpu_float4 a, b;                  // solid, checker, noise colours
  std::int32_t kind, width, height, first;  // image: its texels from texels[first], row 0 at the top
  std::int32_t repeat, octaves, marble, pad;
  float cell, frequency, pad2[2];
};
// environment.hpp's environment_map: a constant sky, or a lat-long map whose texels are in
// texels[first] and whose distribution_2d is in env_tables (see pack_environment).
struct gpu_environment {
  gpu_float4 radiance;              // a constant sky's
  std::int32_t is_constant, width, height, first;
  std::int32_t light, present, pad[2];  // light: its index in the light table, or -1 (black: not sampled)
  float cos_rotation, sin_rotation, marginal_total, pad2;
};
enum gpu_light_kind : std::int32_t {
  gpu_light_sphere = 0, gpu_light_quad = 1, gpu_light_triangles = 2, gpu_light_point = 3,
  gpu_light_environment = 4
};
struct gpu_light {                  // one light of light_set_t, in its order
  gpu_float4 position, intensity;   // point lights
  std::int32_t kind, object, material, first;  // object: sphere or quad; first: in light_triangles
  std::uint32_t count;              // triangle lights: 1; meshes: their triangles
  float cdf, pdf, area;             // selection CDF up to this light, its probability, area
};
struct gpu_light_triangle {         // a triangle of a triangle or mesh light
  gpu_float4 a, b, c;               // a.w, b.w: the light's area CDF before and after it
};
struct gpu_camera {          // camera_t::prepared in float
  gpu_float4 origin, u, v, corner, horizontal, vertical;
  float lens_radius, pad[3];
};
// [end]

static_assert(sizeof(gpu_float4) == 16 && alignof(gpu_float4) == 16);
static_assert(sizeof(gpu_sphere) == 32 && offsetof(gpu_sphere, material) == 16 && offsetof(gpu_sphere, light) == 20);
static_assert(sizeof(gpu_quad) == 80 && offsetof(gpu_quad, normal_area) == 48 && offsetof(gpu_quad, material) == 64);
static_assert(sizeof(gpu_quad4) == 240 && offsetof(gpu_quad4, wz) == 224);
static_assert(sizeof(gpu_plane) == 48 && offsetof(gpu_plane, material) == 32);
static_assert(sizeof(gpu_triangle) == 64 && offsetof(gpu_triangle, id) == 48 &&
              offsetof(gpu_triangle, material) == 52 && offsetof(gpu_triangle, light) == 56);
static_assert(sizeof(gpu_node4) == sizeof(triangle_bvh_node4) && sizeof(gpu_node4) == 128 &&
              offsetof(gpu_node4, child) == 96 && offsetof(gpu_node4, count) == 112);
static_assert(sizeof(gpu_material) == 144 && offsetof(gpu_material, radiance) == 32 &&
              offsetof(gpu_material, kind) == 48 && offsetof(gpu_material, fuzz) == 64 &&
              offsetof(gpu_material, shininess) == 76 && offsetof(gpu_material, eta) == 80 &&
              offsetof(gpu_material, albedo_texture) == 112 && offsetof(gpu_material, roughness) == 128);
static_assert(sizeof(gpu_texture) == 80 && offsetof(gpu_texture, kind) == 32 && offsetof(gpu_texture, cell) == 64);
static_assert(sizeof(gpu_environment) == 64 && offsetof(gpu_environment, light) == 32 &&
              offsetof(gpu_environment, cos_rotation) == 48);
static_assert(sizeof(gpu_light) == 64 && offsetof(gpu_light, kind) == 32 && offsetof(gpu_light, cdf) == 52);
static_assert(sizeof(gpu_light_triangle) == 48);
static_assert(gpu_light_point == light_kinds::point::kernel_kind);
static_assert(sizeof(gpu_camera) == 112 && offsetof(gpu_camera, lens_radius) == 96);

// What a scene uses: each flag is one -D switch of the kernel.
struct gpu_features {
  bool spheres = false, quads = false, planes = false, triangles = false;
  bool metal = false, dielectric = false, phong = false, checker = false, emitters = false;
  bool rough_conductor = false, rough_dielectric = false;  // microfacet.hpp
  bool textures = false, image_textures = false, noise_textures = false;  // texture records
  bool uv_checker = false;  // a checker in surface coordinates (texture.hpp's uv_space)
  bool environment = false;  // rays that leave see it; sampled when it is in the light table
  bool sphere_lights = false, quad_lights = false, triangle_lights = false, point_lights = false;
  bool thin_lens = false;
  integrator method = integrator::mis;  // path.hpp's default
  int max_depth = 8, rr_depth = 3;
  bool weak_seed = false;  // the thesis's per-pixel seed, for the book's before/after figure
};

struct gpu_scene {
  std::vector<gpu_sphere> spheres;
  std::vector<gpu_quad> quads;
  std::vector<gpu_quad4> quad_groups;  // the quads, four by four, for the intersection test
  std::vector<gpu_plane> planes;
  std::vector<gpu_triangle> triangles;
  std::vector<gpu_node4> nodes;
  std::vector<gpu_material> materials;
  std::vector<gpu_light> lights;                    // light_set_t's lights, in its order
  std::vector<gpu_light_triangle> light_triangles;  // of the triangle and mesh lights
  std::vector<gpu_texture> textures;
  std::vector<gpu_float4> texels;                   // the images' and the environment's, linear RGB
  std::vector<gpu_float4> triangle_uvs;             // image textures on triangles: 2 per triangle
  gpu_environment environment{};
  std::vector<float> env_tables;                    // the environment's distribution_2d
  std::vector<std::int32_t> noise_permutation;      // noise.hpp's, when a noise texture is used
  gpu_camera camera;
  gpu_float4 background;
  gpu_features features;
  std::string light_summary;  // light_set_t::describe(): what is sampled, what is hit only
};

template <class T> gpu_float4 to_gpu(const vec3_t<T>& v, double w = 0) {
  return {float(v.x), float(v.y), float(v.z), float(w)};
}
inline gpu_float4 to_gpu(const rgb& c, float w = 0) { return {c.x, c.y, c.z, w}; }
// A quad's n / |n|^2 as the CPU's float path has it (scene_in<float>, then quad_plane_t): from
// the edges rounded to float, so that the kernel's plane coordinates are that path's bits.
template <class T> vec3_t<float> float_quad_w(const parallelogram_t<T>& q) {
  return quad_plane_t<float>(parallelogram_t<float>{vec3_t<float>(q.corner), vec3_t<float>(q.u), vec3_t<float>(q.v)}).w;
}

// The quads four by four, lane i of group k quad 4k + i (gpu_quad4); w[i]: quad i's float_quad_w.
inline std::vector<gpu_quad4> quad_groups(const std::vector<gpu_quad>& quads, const std::vector<gpu_float4>& w) {
  auto lane = [](gpu_float4& v, std::size_t k) -> float& { return k == 0 ? v.x : k == 1 ? v.y : k == 2 ? v.z : v.w; };
  std::vector<gpu_quad4> groups((quads.size() + 3) / 4);
  for (std::size_t i = 0; i < quads.size(); ++i) {
    gpu_quad4& g = groups[i / 4];
    const gpu_quad& q = quads[i];
    const std::size_t k = i % 4;
    lane(g.nx, k) = q.normal_area.x, lane(g.ny, k) = q.normal_area.y, lane(g.nz, k) = q.normal_area.z;
    lane(g.qx, k) = q.corner.x, lane(g.qy, k) = q.corner.y, lane(g.qz, k) = q.corner.z;
    lane(g.ux, k) = q.u.x, lane(g.uy, k) = q.u.y, lane(g.uz, k) = q.u.z;
    lane(g.vx, k) = q.v.x, lane(g.vy, k) = q.v.y, lane(g.vz, k) = q.v.z;
    lane(g.wx, k) = w[i].x, lane(g.wy, k) = w[i].y, lane(g.wz, k) = w[i].z;
  }
  return groups;
}

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
inline bool finite(const gpu_float4& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z) && std::isfinite(v.w);
}
}  // namespace detail
inline gpu_camera to_gpu(const camera_t<double>::prepared& c) { return detail::camera_to_gpu(c); }
inline gpu_camera to_gpu(const camera_t<float>::prepared& c) { return detail::camera_to_gpu(c); }

// A texture record, its image's texels appended to g.texels (linear RGB: the scene file decoded
// sRGB when it read the image, texture_file.hpp); returns its index in g.textures.
inline std::int32_t pack_texture(gpu_scene& g, const texture& t) {
  gpu_texture o{};
  o.a = to_gpu(t.a);
  o.b = to_gpu(t.b);
  o.cell = float(t.cell);
  o.frequency = float(t.frequency);
  o.octaves = t.octaves;
  o.marble = t.marble ? 1 : 0;
  o.repeat = t.repeat ? 1 : 0;
  switch (t.type) {
    case texture::kind::solid: o.kind = gpu_tex_solid; break;
    case texture::kind::checker: o.kind = t.uv_space ? gpu_tex_checker_uv : gpu_tex_checker; break;
    case texture::kind::noise: o.kind = gpu_tex_noise; break;
    case texture::kind::image: {
      if (!t.map || t.map->width < 1 || t.map->height < 1) throw error("realtime: " + describe(t) + " is empty");
      o.kind = gpu_tex_image;
      o.width = t.map->width;
      o.height = t.map->height;
      o.first = std::int32_t(g.texels.size());
      for (const rgb& c : t.map->pixels) g.texels.push_back(to_gpu(c));
      break;
    }
  }
  g.textures.push_back(o);
  return std::int32_t(g.textures.size() - 1);
}

// What a material kind's pack() (materials/) fills: the record the kernel reads, and a texture
// record in the scene's table for a texture it names (none when one material is packed alone).
struct gpu_material_packer {
  gpu_material& record;
  gpu_scene* scene = nullptr;
  static gpu_float4 colour(const rgb& c) { return to_gpu(c); }
  std::int32_t texture(const zraka::texture& t) { return scene ? pack_texture(*scene, t) : -1; }
  // An albedo: a solid colour or a checker in the record itself, an image or noise as a record.
  void albedo(const zraka::texture& t) {
    record.albedo_a = to_gpu(t.a);
    record.albedo_b = to_gpu(t.b);
    record.checker = t.type != zraka::texture::kind::checker ? 0 : t.uv_space ? 2 : 1;
    record.cell = float(t.cell);
    if (t.type == zraka::texture::kind::image || t.type == zraka::texture::kind::noise) record.albedo_texture = texture(t);
  }
};
// Does the kernel render kind K? (It has a pack() and a KIND_ in kernels/pathtrace.cl.)
template <class K> constexpr bool gpu_renders = requires(const K& k, gpu_material_packer& p) { k.pack(p); };
static_assert(material_kinds::lambertian::gpu_kind == gpu_lambertian && material_kinds::fuzzy_metal::gpu_kind == gpu_metal &&
              material_kinds::dielectric::gpu_kind == gpu_dielectric && material_kinds::emitter::gpu_kind == gpu_emitter &&
              material_kinds::phong::gpu_kind == gpu_phong && material_kinds::rough_conductor::gpu_kind == gpu_rough_conductor &&
              material_kinds::rough_dielectric::gpu_kind == gpu_rough_dielectric, "the kinds' KIND_ numbers");

// The record of a material, packed by its kind; its textures go into g's table (g null: -1).
// What a kind does not set keeps a default material's values: the kernel reads a field only
// for the kinds that have it.
inline gpu_material pack_material(const material& m, gpu_scene* g) {
  gpu_material r{};
  r.albedo_texture = r.roughness_texture = -1;
  gpu_material_packer p{r, nullptr};
  p.albedo(material_kinds::lambertian{}.albedo);
  material_kinds::rough_conductor{}.pack(p);
  r.ior = float(material_kinds::dielectric{}.ior);
  p.scene = g;
  std::visit([&](const auto& k) {
    if constexpr (gpu_renders<std::decay_t<decltype(k)>>) {
      r.kind = k.gpu_kind;
      k.pack(p);
    }
  }, m.kind);
  r.radiance = to_gpu(m.radiance);
  r.two_sided = m.two_sided ? 1 : 0;
  return r;
}
// The material's numbers alone (no texture records).
inline gpu_material to_gpu(const material& m) { return pack_material(m, nullptr); }

// [listing gpu-environment]
// The environment: a constant sky's colour, or the map's texels and its distribution_2d's
// tables as they are, in float: the marginal's bins [H] and CDF [H + 1], each row's total [H],
// then every row's bins [H][W] and CDF [H][W + 1]. light: its index in the light table.
inline void pack_environment(gpu_scene& g, const environment_map& e, int light) {
  gpu_environment& o = g.environment;
  o.present = 1;
  o.light = light;
  o.is_constant = e.is_constant() ? 1 : 0;
  o.radiance = to_gpu(e.constant_radiance());
  o.cos_rotation = float(e.cos_rotation());
  o.sin_rotation = float(e.sin_rotation());
  if (e.is_constant()) return;
  const image& map = e.map();
  o.width = map.width;
  o.height = map.height;
  o.first = std::int32_t(g.texels.size());
  for (const rgb& c : map.pixels) g.texels.push_back(to_gpu(c));
  const distribution_2d& d = e.distribution();
  auto put = [&](const std::vector<double>& v) {
    for (double x : v) g.env_tables.push_back(float(x));
  };
  put(d.marginal().bins());
  put(d.marginal().cdf());
  o.marginal_total = float(d.marginal().total());
  for (std::size_t v = 0; v < d.height(); ++v) g.env_tables.push_back(float(d.row(v).total()));
  for (std::size_t v = 0; v < d.height(); ++v) put(d.row(v).bins());
  for (std::size_t v = 0; v < d.height(); ++v) put(d.row(v).cdf());
}
// [end]

// [listing gpu-pack]
// The scene as arrays, the camera prepared for a width x height image, the lights of
// path.hpp's tracer for these options, and the features used. Throws for what the kernel
// cannot render, naming it, and for the options path.hpp refuses (naive with point lights).
template <class T>
gpu_scene pack_scene(const scene_t<T>& sc, int width, int height, const path_options& opt) {
  if (width < 1 || height < 1) throw error("image size must be positive");
  gpu_scene g;
  auto& f = g.features;
  // C++ code cannot run in the kernel: refuse it by name, before anything is built.
  if (!sc.user_shapes.empty())
    throw error("realtime: " + sc.user_shape_label(0) + " is a user shape ('" + sc.user_shapes[0].shape->name() +
                "'), which the OpenCL kernel cannot run; " + render_it_with(sc));
  if (!sc.media.empty())  // book 6.1: the kernel has no free-flight sampling yet
    throw error("realtime: the scene has participating media ('" + sc.media[0].name +
                "'), which the OpenCL kernel does not render; " + render_it_with(sc));
  for (std::size_t i = 0; i < sc.lights.size(); ++i) {
    kernel_light k;
    if (!pack_light(sc.lights[i], k))
      throw error("realtime: light " + std::to_string(i) + " is of type '" + light_type(sc.lights[i]) +
                  "', a course's light, which the OpenCL kernel cannot run; " + render_it_with(sc));
  }
  for_each_object(sc, [&](object_ref o) {
    const material& m = sc.material_of(o);
    if (is_custom(m))
      throw error("realtime: " + sc.material_label(sc.material_index(o)) + " is a custom BSDF ('" +
                  m.get<material_kinds::custom>()->bsdf->name() + "'), which the OpenCL kernel cannot run; " + render_it_with(sc));
    if (!std::visit([](const auto& k) { return gpu_renders<std::decay_t<decltype(k)>>; }, m.kind))
      throw error("realtime: " + sc.material_label(sc.material_index(o)) + " is a " + kind_name(m.kind) +
                  ", which the OpenCL kernel does not render; " + render_it_with(sc));
  });
  const path_tracer_t<T> tracer(sc, opt);  // the CPU's own checks, and its lights
  const light_set_t<T>& lights = tracer.lights;
  g.light_summary = lights.describe();
  for (const material& m : sc.materials) g.materials.push_back(pack_material(m, &g));
  // What the kernel must compile for the materials the objects use: read off their records.
  auto note_texture = [&](std::int32_t i) {
    const std::int32_t k = g.textures[std::size_t(i)].kind;
    f.textures = true;
    f.checker |= k == gpu_tex_checker || k == gpu_tex_checker_uv;
    f.uv_checker |= k == gpu_tex_checker_uv;
    f.image_textures |= k == gpu_tex_image;
    f.noise_textures |= k == gpu_tex_noise;
  };
  auto note_material = [&](int mi) {
    const material& m = sc.materials[std::size_t(mi)];
    const gpu_material& r = g.materials[std::size_t(mi)];
    f.metal |= r.kind == gpu_metal;
    f.dielectric |= r.kind == gpu_dielectric;
    f.phong |= r.kind == gpu_phong;
    f.rough_conductor |= r.kind == gpu_rough_conductor;
    f.rough_dielectric |= r.kind == gpu_rough_dielectric;
    f.checker |= r.checker != 0;
    f.uv_checker |= r.checker == 2;
    if (r.albedo_texture >= 0) note_texture(r.albedo_texture);
    if (r.roughness_texture >= 0) note_texture(r.roughness_texture);
    f.emitters |= emits(m);
  };
  auto light_of = [&](shape_kind k, std::size_t i) { return std::int32_t(lights.index_of({k, int(i)})); };
  for (std::size_t i = 0; i < sc.spheres.size(); ++i) {
    const auto& s = sc.spheres[i];
    g.spheres.push_back({to_gpu(s.shape.center, s.shape.radius), s.material, light_of(shape_kind::sphere, i), {0, 0}});
    note_material(s.material);
  }
  std::vector<gpu_float4> quad_w;  // for quad_groups, once they are checked
  for (std::size_t i = 0; i < sc.quads.size(); ++i) {
    const auto& q = sc.quads[i];
    g.quads.push_back({to_gpu(q.shape.corner), to_gpu(q.shape.u), to_gpu(q.shape.v),
                       to_gpu(q.shape.normal(), q.shape.area()), q.material, light_of(shape_kind::quad, i), {0, 0}});
    quad_w.push_back(to_gpu(float_quad_w(q.shape)));
    note_material(q.material);
  }
  for (const auto& p : sc.planes) {
    g.planes.push_back({to_gpu(p.shape.point), to_gpu(p.shape.normal), p.material, {0, 0, 0}});
    note_material(p.material);
  }
  // Every triangle, lone or in a mesh, goes into one BVH; tri_material and tri_light map the
  // input index to the material and the light (the mesh's, for its triangles).
  // tri_uv: the vertices' texture coordinates (a lone triangle's and an untextured mesh's are
  // (0, 0), (1, 0), (0, 1), so that interpolating them gives the barycentrics, as on the CPU).
  std::vector<triangle_t<float>> tris;
  std::vector<std::int32_t> tri_material, tri_light;
  std::vector<std::array<gpu_float4, 2>> tri_uv;
  const std::array<gpu_float4, 2> barycentric = {gpu_float4{0, 0, 1, 0}, gpu_float4{0, 1, 0, 0}};
  for (std::size_t i = 0; i < sc.triangles.size(); ++i) {
    const auto& t = sc.triangles[i];
    tris.push_back({vec3_t<float>(t.shape.a), vec3_t<float>(t.shape.b), vec3_t<float>(t.shape.c)});
    tri_material.push_back(t.material);
    tri_light.push_back(light_of(shape_kind::triangle, i));
    tri_uv.push_back(barycentric);
    note_material(t.material);
  }
  for (std::size_t m = 0; m < sc.meshes.size(); ++m) {
    const auto& mo = sc.meshes[m];
    for (std::size_t i = 0; i < mo.shape.triangle_count(); ++i) {
      const auto t = mo.shape.triangle(i);
      tris.push_back({vec3_t<float>(t.a), vec3_t<float>(t.b), vec3_t<float>(t.c)});
      tri_material.push_back(mo.material);
      tri_light.push_back(light_of(shape_kind::mesh, m));
      const auto t0 = mo.shape.texcoord(i, T(0), T(0)), t1 = mo.shape.texcoord(i, T(1), T(0)),
                 t2 = mo.shape.texcoord(i, T(0), T(1));
      tri_uv.push_back({gpu_float4{float(t0.x), float(t0.y), float(t1.x), float(t1.y)},
                        gpu_float4{float(t2.x), float(t2.y), 0, 0}});
    }
    note_material(mo.material);
  }
  if (!tris.empty()) {
    const triangle_bvh4 bvh(tris);
    // The BVH's positions, the empty lanes of its blocks of four included (a leaf's child
    // indexes them; the kernel reads only a leaf's count, never an empty lane, which gets zeros
    // rather than the CPU's NaN vertices).
    for (std::size_t k = 0; k < bvh.positions(); ++k) {
      const packed_triangle p = bvh.triangle(k);
      const bool empty = p.id == UINT32_MAX;
      if (empty) {
        const gpu_float4 zero{0, 0, 0, 0};
        g.triangles.push_back({zero, zero, zero, p.id, 0, -1, 0});
      } else {
        g.triangles.push_back({to_gpu(p.a), to_gpu(p.b), to_gpu(p.c), p.id, tri_material[p.id], tri_light[p.id], 0});
      }
      if (f.image_textures || f.uv_checker) {
        if (empty) g.triangle_uvs.insert(g.triangle_uvs.end(), 2, gpu_float4{0, 0, 0, 0});
        else g.triangle_uvs.insert(g.triangle_uvs.end(), tri_uv[p.id].begin(), tri_uv[p.id].end());
      }
    }
    for (const triangle_bvh_node4& n : bvh.nodes()) {
      gpu_node4 o;
      static_assert(sizeof o == sizeof n);
      std::memcpy(&o, &n, sizeof o);
      g.nodes.push_back(o);
    }
  }
  // The light table: light_set_t's lights, selection probabilities and mesh area CDFs as they are.
  double cdf = 0;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const auto& l = lights.lights()[i];
    gpu_light o{};
    const double p = double(lights.selection_pdf(int(i)));
    o.cdf = float(cdf += p);
    o.pdf = float(p);
    o.area = float(l.area);
    if (l.environment) {
      o.kind = gpu_light_environment;
      o.object = o.material = -1;
      g.lights.push_back(o);
      continue;
    }
    if (l.point >= 0) {  // a light kind's own numbers (lights/kernel_light.hpp)
      kernel_light k;
      pack_light(sc.lights[std::size_t(l.point)], k);
      o.kind = k.kind;
      o.object = l.point;
      o.position = {k.position[0], k.position[1], k.position[2], 0.0f};
      o.intensity = {k.intensity[0], k.intensity[1], k.intensity[2], 0.0f};
      f.point_lights |= k.kind == gpu_light_point;
      g.lights.push_back(o);
      continue;
    }
    o.object = l.object.index;
    o.material = sc.material_index(l.object);
    const auto k = std::size_t(l.object.index);
    switch (l.object.kind) {
      case shape_kind::sphere: o.kind = gpu_light_sphere; f.sphere_lights = true; break;
      case shape_kind::quad: o.kind = gpu_light_quad; f.quad_lights = true; break;
      case shape_kind::triangle: {
        const auto& t = sc.triangles[k].shape;
        o.kind = gpu_light_triangles;
        o.first = std::int32_t(g.light_triangles.size());
        o.count = 1;
        g.light_triangles.push_back({to_gpu(t.a, 0.0), to_gpu(t.b, double(l.area)), to_gpu(t.c)});
        f.triangle_lights = true;
        break;
      }
      case shape_kind::mesh: {
        const auto& mesh = sc.meshes[k].shape;
        const std::vector<double>& c = lights.triangle_cdf();
        o.kind = gpu_light_triangles;
        o.first = std::int32_t(g.light_triangles.size());
        o.count = l.count;
        for (std::uint32_t j = 0; j < l.count; ++j) {
          const auto t = mesh.triangle(j);
          g.light_triangles.push_back({to_gpu(t.a, c[l.first + j]), to_gpu(t.b, c[l.first + j + 1]), to_gpu(t.c)});
        }
        f.triangle_lights = true;
        break;
      }
      case shape_kind::plane:
      case shape_kind::user: throw error("realtime: internal: a plane or user shape in the light table");
    }
    g.lights.push_back(o);
  }
  // Float is the kernel's precision: a number beyond its range is refused, not rendered as inf.
  auto need_finite = [](const gpu_float4& v, const std::string& what) {
    if (!detail::finite(v)) throw error("realtime: " + what + " does not fit in float, the kernel's precision");
  };
  for (std::size_t i = 0; i < g.spheres.size(); ++i) need_finite(g.spheres[i].center_radius, "sphere " + std::to_string(i));
  for (std::size_t i = 0; i < g.quads.size(); ++i)
    for (const auto& v : {g.quads[i].corner, g.quads[i].u, g.quads[i].v, g.quads[i].normal_area, quad_w[i]})
      need_finite(v, "quad " + std::to_string(i));  // w: NaN where u x v underflows in float (edges ~1e-20)
  g.quad_groups = quad_groups(g.quads, quad_w);
  for (std::size_t i = 0; i < g.planes.size(); ++i) need_finite(g.planes[i].point, "plane " + std::to_string(i));
  for (const auto& t : g.triangles)
    for (const auto& v : {t.a, t.b, t.c}) need_finite(v, "triangle " + std::to_string(t.id));
  for (std::size_t i = 0; i < g.materials.size(); ++i)
    need_finite(g.materials[i].radiance, "the radiance of material " + std::to_string(i));
  for (const auto& l : g.lights) need_finite(l.intensity, "a point light's intensity");
  for (const auto& t : g.textures)
    for (const auto& v : {t.a, t.b}) need_finite(v, "a texture's colour");
  for (const auto& v : g.texels) need_finite(v, "a texel of a texture or of the environment");

  if (sc.environment) {
    pack_environment(g, *sc.environment, lights.environment_index());
    need_finite(g.environment.radiance, "the environment's colour");
    f.environment = true;
  }
  if (f.noise_textures)
    for (std::uint8_t p : detail::noise_permutation()) g.noise_permutation.push_back(p);

  camera_t<T> c = sc.camera;
  c.aspect = T(width) / T(height);
  g.camera = to_gpu(c.prepare());
  g.background = to_gpu(sc.background);
  f.spheres = !g.spheres.empty();
  f.quads = !g.quads.empty();
  f.planes = !g.planes.empty();
  f.triangles = !g.nodes.empty();
  f.thin_lens = sc.camera.aperture > 0;
  f.method = opt.method;
  f.max_depth = opt.max_depth;
  f.rr_depth = opt.rr_depth;
  return g;
}
// [end]

// The scenes the kernel's eight-lane loop covers (PATH_LANES, book 4.3): spheres and quads, Lambert
// (solid or a checker in world space), glass, emitters, quad and sphere lights, with any method and
// camera. Anything else (a plane, a mesh, another material or light, a texture, an environment)
// takes the loop of one path per work item.
inline bool lanes_cover(const gpu_features& f) {
  return !(f.planes || f.triangles || f.metal || f.phong || f.rough_conductor || f.rough_dielectric || f.textures ||
           f.image_textures || f.noise_textures || f.uv_checker || f.environment || f.triangle_lights ||
           f.point_lights || f.weak_seed);
}
// How many pixels a work item of the lanes loop renders: the kernel's float8.
constexpr int gpu_path_lanes = 8;
// Pixels per work item of the kernel built for f: gpu_path_lanes with the eight-lane loop, else
// 1 (the all-features kernel is always the one-path loop). build_options and the launch both ask.
inline int gpu_pixels_per_item(const gpu_features& f, bool all_features) {
  return !all_features && lanes_cover(f) ? gpu_path_lanes : 1;
}

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
  flag(f.phong, "HAS_PHONG");
  flag(f.checker, "HAS_CHECKER");
  flag(f.emitters, "HAS_EMITTERS");
  flag(f.rough_conductor, "HAS_ROUGH_CONDUCTOR");
  flag(f.rough_dielectric, "HAS_ROUGH_DIELECTRIC");
  flag(f.textures, "HAS_TEXTURES");  // records for the two below and for roughness maps
  flag(f.image_textures, "HAS_IMAGE_TEXTURES");
  flag(f.noise_textures, "HAS_NOISE_TEXTURES");
  flag(f.uv_checker, "HAS_UV_CHECKER");
  flag(f.environment, "HAS_ENVIRONMENT");
  flag(f.sphere_lights, "HAS_SPHERE_LIGHTS");
  flag(f.quad_lights, "HAS_QUAD_LIGHTS");
  flag(f.triangle_lights, "HAS_TRIANGLE_LIGHTS");
  flag(f.point_lights, "HAS_POINT_LIGHTS");
  flag(f.thin_lens, "HAS_THIN_LENS");
  // The algorithm is a choice, not a feature: never forced.
  o += f.method == integrator::naive ? " -DMETHOD_NAIVE" : f.method == integrator::nee ? " -DMETHOD_NEE" : " -DMETHOD_MIS";
  if (f.weak_seed) o += " -DWEAK_SEED";
  o += " -DMAX_DEPTH=" + std::to_string(f.max_depth) + " -DRR_DEPTH=" + std::to_string(f.rr_depth);
  if (const int n = gpu_pixels_per_item(f, all_features); n > 1) o += " -DPATH_LANES=" + std::to_string(n);
  return o;
}
// [end]

// [listing reference-sample]
// The CPU twin of one kernel sample: the same pixel jitter and lens draws from the same stream
// rng(seed, pixel, sample), then path.hpp's path tracer in double.
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

ZRAKA_INSTANCE(gpu_scene pack_scene(const scene_t<double>&, int, int, const path_options&))  // compiled.hpp

}  // namespace zraka

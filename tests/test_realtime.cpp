// links: OpenCL yaml-cpp
// The real-time path tracer (realtime.hpp, kernels/pathtrace.cl) against the REFERENCE: a long
// mis render of the CPU path tracer (path.hpp through render.hpp), on a scene set covering
// every emitter kind (triangle, mesh, one- and two-sided quads, spheres, point lights, the
// environment map and a constant sky), every material (Lambert with checker, image and noise
// textures, Phong, metal, glass, rough conductors and dielectrics) and the naive, nee and mis
// kernels; and the new functions (environment sampling, image lookups, microfacets) on extreme
// inputs against the C++ they mirror, through small probe kernels.
// Without an OpenCL platform every case says so and passes (nothing to test on this machine).
#include <zraka/core/resources.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/gpu/realtime.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/lights/environment.hpp>
#include <zraka/scene/cornell.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

using namespace zraka;

namespace {

std::optional<cl::context> device() {
  try {
    return cl::context(cl::pick_device(0));
  } catch (const cl::no_platform& e) {
    MESSAGE("skipped, no OpenCL platform: " << e.what());
    return std::nullopt;
  }
}

path_options method(integrator m, int depth = 5) {
  path_options o;
  o.method = m;
  o.max_depth = depth;
  return o;
}

// ---------------------------------------------------------------- the scenes
// Issue 11's scene (scenes/triangle-light.yaml): floor, back wall, an emissive triangle, a point light.
scene triangle_light_scene() { return load_scene_file(resource_path("scenes/triangle-light.yaml")).sc; }

// A two-sided quad light over a floor, seen from above: the camera sees its front (top) face,
// the floor gets only the light of its back face.
scene two_sided_scene() {
  scene sc;
  const int floor = sc.add_material(material::lambertian(rgb(0.8f)));
  const int lamp = sc.add_material(material::emitter(rgb(3.0f, 2.5f, 2.0f), true));
  sc.add(quad{{-3, 0, -3}, {0, 0, 6}, {6, 0, 0}}, floor);      // normal up
  sc.add(quad{{-0.5, 1, -0.5}, {0, 0, 1}, {1, 0, 0}}, lamp);  // normal up: the floor sees its back
  sc.camera.position = {0, 2.2, 2.5};
  sc.camera.look_at = {0, 0.3, 0};
  return sc;
}

// A glowing octahedron (a mesh of eight triangles of two sizes) over a floor, with a ball.
scene mesh_light_scene() {
  scene sc;
  const int floor = sc.add_material(material::lambertian(texture::checker(rgb(0.8f), rgb(0.3f), 0.5)));
  const int ball = sc.add_material(material::lambertian(rgb(0.7f, 0.4f, 0.2f)));
  const int lamp = sc.add_material(material::emitter(rgb(3.0f, 2.5f, 2.0f)));
  sc.add(quad{{-3, 0, -3}, {0, 0, 6}, {6, 0, 0}}, floor);
  sc.add(sphere{{-0.6, 0.35, 0.2}, 0.35}, ball);
  mesh m;
  const vec3 c(0.3, 1.4, -0.2);
  m.positions = {c + vec3(0.6, 0, 0), c - vec3(0.6, 0, 0), c + vec3(0, 0.3, 0),
                 c - vec3(0, 0.3, 0), c + vec3(0, 0, 0.3), c - vec3(0, 0, 0.3)};
  for (std::uint32_t x : {0u, 1u})
    for (std::uint32_t y : {2u, 3u})
      for (std::uint32_t z : {4u, 5u}) {  // one face per octant, wound to face outwards
        const vec3 a = m.positions[x], b = m.positions[y], d = m.positions[z];
        const bool out = glm::dot(glm::cross(b - a, d - a), (a + b + d) / 3.0 - c) > 0;
        m.triangles.push_back(out ? std::array<std::uint32_t, 3>{x, y, z} : std::array<std::uint32_t, 3>{x, z, y});
      }
  sc.add(m, lamp);
  sc.camera.position = {0, 1.2, 3};
  sc.camera.look_at = {0, 0.6, 0};
  return sc;
}

// A 6 x 6 floor at y = 0 (normal up), a square lamp of side `side` facing down at height y, a
// sky colour and the camera: the stage of the scenes below.
scene stage(const material& floor, double side, double y, rgb lamp, rgb sky, vec3 eye, vec3 at) {
  scene sc;
  sc.add(quad{{-3, 0, -3}, {0, 0, 6}, {6, 0, 0}}, sc.add_material(floor));
  sc.add(quad{{-side / 2, y, -side / 2}, {side, 0, 0}, {0, 0, side}}, sc.add_material(material::emitter(lamp)));
  sc.background = sky;
  sc.camera.position = eye;
  sc.camera.look_at = at;
  return sc;
}

// Phong (the normalised lobe, book 1.9) on a ball and the floor, under a quad light and a dim sky.
scene phong_scene() {
  scene sc = stage(material::phong(rgb(0.5f), rgb(0.3f), 8), 1, 2, rgb(4.0f), rgb(0.05f, 0.07f, 0.1f), {0, 1.3, 3},
                   {0, 0.5, 0});
  sc.add(sphere{{0, 0.6, 0}, 0.6}, sc.add_material(material::phong(rgb(0.4f, 0.2f, 0.1f), rgb(0.5f), 40)));
  return sc;
}

// Chapter 5's appearance. Rough metals (a preset's complex index, an RGB F0 with Schlick, a
// roughness map) on a checker floor under a quad light and a dim sky.
scene rough_conductor_scene() {
  scene sc = stage(material::lambertian(texture::checker(rgb(0.7f), rgb(0.3f), 0.5)), 1.2, 2, rgb(5.0f),
                   rgb(0.1f, 0.12f, 0.15f), {0, 1.2, 3}, {0, 0.4, 0});
  const int gold = sc.add_material(material::rough_conductor(0.25, *find_metal("gold")));
  const int f0 = sc.add_material(material::rough_conductor(0.05, conductor_fresnel::from_f0(rgb(0.9f, 0.6f, 0.4f))));
  material mapped = material::rough_conductor(0.3, *find_metal("copper"));
  mapped.get<material_kinds::rough_conductor>()->roughness.map = texture::checker(rgb(0.02f), rgb(0.6f), 0.2);
  const int copper = sc.add_material(mapped);
  sc.add(sphere{{-0.9, 0.4, 0}, 0.4}, gold);
  sc.add(sphere{{0, 0.4, -0.3}, 0.4}, f0);
  sc.add(sphere{{0.9, 0.4, 0}, 0.4}, copper);
  return sc;
}

// Rough glass (Walter 2007): a ball and a slab in front of a checker wall, lit by a quad light.
scene rough_dielectric_scene() {
  scene sc = stage(material::lambertian(rgb(0.7f)), 1, 2.2, rgb(6.0f), rgb(0.05f), {0, 1.1, 3}, {0, 0.5, 0});
  const int wall =
      sc.add_material(material::lambertian(texture::checker(rgb(0.8f, 0.3f, 0.2f), rgb(0.2f, 0.3f, 0.8f), 0.3)));
  const int frosted = sc.add_material(material::rough_dielectric(0.15, 1.5));
  const int milky = sc.add_material(material::rough_dielectric(0.5, 1.33));
  sc.add(quad{{-3, 0, -1.5}, {6, 0, 0}, {0, 3, 0}}, wall);
  sc.add(sphere{{-0.5, 0.5, 0}, 0.5}, frosted);
  sc.add(quad{{0.3, 0, 0.3}, {0.8, 0, 0}, {0, 0.9, 0}}, milky);  // a thin pane, one interface
  return sc;
}

// An image (procedural, 6 x 4, repeated and clamped) on a floor, a ball and a mesh with texture
// coordinates; marble noise on a ball; under a quad light.
scene textured_scene() {
  auto img = std::make_shared<image>(6, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 6; ++x)
      img->at(x, y) = rgb(0.15f + 0.13f * float(x), 0.1f + 0.2f * float(y), (x + y) % 2 ? 0.8f : 0.1f);
  scene sc = stage(material::lambertian(texture::image_map(img, true, "grid")), 1, 2.2, rgb(5.0f), rgb(0),
                   {0, 1.3, 3}, {0, 0.5, 0});
  const int ball = sc.add_material(material::lambertian(texture::image_map(img, false, "grid")));
  const int marble = sc.add_material(
      material::lambertian(texture::noise(rgb(0.9f, 0.85f, 0.8f), rgb(0.1f, 0.15f, 0.3f), 2.5, 5, true)));
  sc.add(sphere{{-0.7, 0.45, 0}, 0.45}, ball);
  sc.add(sphere{{0.7, 0.45, 0}, 0.45}, marble);
  mesh m;  // a square behind, its texture coordinates beyond [0, 1] (the clamp shows)
  m.positions = {{-1, 0.2, -1}, {1, 0.2, -1}, {1, 1.6, -1}, {-1, 1.6, -1}};
  m.texcoords = {{-0.5, -0.5}, {1.5, -0.5}, {1.5, 1.5}, {-0.5, 1.5}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  sc.add(m, ball);
  return sc;
}

// Checkers in (u, v) (Mitsuba's checkerboard): the floor's 6 m quad in cells of 1/4 of its uv
// (1.5 m, several pixels each), and a rough copper ball whose roughness map is one.
scene uv_checker_scene() {
  scene sc = stage(material::lambertian(texture::checker_uv(rgb(0.9f, 0.3f, 0.1f), rgb(0.1f, 0.3f, 0.8f), 0.25)), 1, 2.2,
                   rgb(5.0f), rgb(0.05f), {0.4, 1.6, 3}, {0, 0.3, 0});
  material rough = material::rough_conductor(0.3, *find_metal("copper"));
  rough.get<material_kinds::rough_conductor>()->roughness.map = texture::checker_uv(rgb(0.05f), rgb(0.6f), 0.25);
  sc.add(sphere{{0, 0.5, 0}, 0.5}, sc.add_material(rough));
  return sc;
}

// A lat-long sky (16 x 8, rotated) with a small bright sun, the only light, over a plane with a
// diffuse ball, a mirror and a rough gold ball; or a constant sky.
scene sky_scene(bool constant) {
  scene sc;
  const int floor = sc.add_material(material::lambertian(texture::checker(rgb(0.75f), rgb(0.3f), 0.75)));
  sc.add(plane::from_point_normal(vec3(0), vec3(0, 1, 0)), floor);
  sc.add(sphere{{-1.0, 0.5, 0}, 0.5}, sc.add_material(material::lambertian(rgb(0.7f, 0.35f, 0.2f))));
  sc.add(sphere{{0, 0.5, -0.4}, 0.5}, sc.add_material(material::mirror(rgb(0.9f))));
  sc.add(sphere{{1.0, 0.5, 0}, 0.5}, sc.add_material(material::rough_conductor(0.2, *find_metal("gold"))));
  if (constant) {
    sc.environment = std::make_shared<environment_map>(environment_map::constant(rgb(0.6f, 0.7f, 0.9f)));
  } else {
    image sky(16, 8);
    for (int y = 0; y < 8; ++y)
      for (int x = 0; x < 16; ++x)
        sky.at(x, y) = y < 4 ? rgb(0.3f + 0.05f * float(y), 0.4f + 0.05f * float(y), 0.8f) : rgb(0.1f, 0.08f, 0.05f);
    sky.at(5, 2) = rgb(60, 55, 45);  // the sun
    sc.environment = std::make_shared<environment_map>(environment_map::from_image(sky, "sky", 1.0f, 40));
  }
  sc.camera.position = {0, 1.4, 3.5};
  sc.camera.look_at = {0, 0.4, 0};
  return sc;
}

// ---------------------------------------------------------------- images with standard errors
// A mean image and each pixel's sample variance of one sample (unbiased, per channel).
struct estimate {
  image mean, variance;
  int spp = 0;
};

// The reference: the CPU path tracer's mis, in double, with its own seed (independent of the kernel).
estimate cpu_reference(const scene& sc, int w, int h, int spp, const path_options& po, std::uint64_t seed) {
  camera c = sc.camera;
  c.aspect = double(w) / h;
  const auto cam = c.prepare();
  estimate e{image(w, h), image(w, h), spp};
  std::vector<vec3> sum2(std::size_t(w) * std::size_t(h), vec3(0));  // each pixel is one thread's alone
  render_options opt;
  opt.progress = false;
  const path_tracer tracer(sc, po);
  render(e.mean, spp, seed, [&](sample_context& s) {
    const rgb v = reference_sample(sc, tracer.lights, cam, s.x, s.y, w, h, s.random, po, s.rays);
    if (is_finite(v)) sum2[std::size_t(s.y) * std::size_t(w) + std::size_t(s.x)] += vec3(v) * vec3(v);
    return v;
  }, opt);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const vec3 m(e.mean.at(x, y));
      e.variance.at(x, y) = rgb(glm::max(vec3(0), (sum2[std::size_t(y) * std::size_t(w) + std::size_t(x)] -
                                                    double(spp) * m * m) / double(spp - 1)));
    }
  return e;
}

estimate kernel_render(const cl::context& ctx, const scene& sc, int w, int h, int spp, const path_options& po,
                       std::uint64_t seed, std::string* options = nullptr) {
  gpu_renderer r(ctx, pack_scene(sc, w, h, po), w, h, seed);
  if (options) *options = r.options();
  r.launch(std::uint32_t(spp));
  return {r.read_image(), r.read_variance(), spp};
}

// [listing agreement]
// The kernel's image K and the reference R are means of n_K and n_R independent samples, so
// pixel p's difference d_p = K_p - R_p has mean 0 (if the kernel is right) and variance
// se_p^2 = s_K,p^2 / n_K + s_R,p^2 / n_R, from each side's own sample variance. Two bounds:
//   channel mean  |mean_p d_p| <= 5 sqrt(sum_p se_p^2) / P    (5 standard errors)
//   per pixel     mean_p min(z_p^2, 25) <= 1.5,  z_p = d_p / se_p   (the expectation is < 1)
// Each z_p^2 is capped at 25 (5 standard errors): a pixel that a naive kernel's 1024 samples
// never saw lit has s_K = 0 and an unbounded z with nothing wrong, while an image that is off
// everywhere (10 % darker) moves many pixels and fails the mean either way.
// se_p also counts float rounding (2^-14 of the value) so a noiseless pixel has a bound.
struct agreement {
  vec3 mean_diff{0}, mean_se{0};  // GLM leaves vectors uninitialised by default
  double mean_z2 = 0;             // capped, per pixel and channel
  double worst_z = 0;             // the largest |z_p|, for the report
};

agreement compare(const estimate& k, const estimate& r, float scale = 1.0f) {
  agreement a;
  const double P = double(k.mean.width) * k.mean.height;
  vec3 se_sum(0);
  for (int y = 0; y < k.mean.height; ++y)
    for (int x = 0; x < k.mean.width; ++x) {
      const vec3 K = vec3(k.mean.at(x, y)) * double(scale), R(r.mean.at(x, y));
      const vec3 rounding = 0x1p-14 * glm::max(glm::abs(K), glm::abs(R)) + 1e-7;
      const vec3 se2 = vec3(k.variance.at(x, y)) * double(scale * scale) / double(k.spp) +
                       vec3(r.variance.at(x, y)) / double(r.spp) + rounding * rounding;
      const vec3 d = K - R;
      a.mean_diff += d / P;
      se_sum += se2;
      for (int c = 0; c < 3; ++c) {
        const double z = d[c] / std::sqrt(se2[c]);
        a.mean_z2 += std::min(z * z, 25.0) / (3 * P);
        a.worst_z = std::max(a.worst_z, std::abs(z));
      }
    }
  a.mean_se = glm::sqrt(se_sum) / P;
  return a;
}

bool within(const agreement& a) {
  for (int c = 0; c < 3; ++c)
    if (!(std::abs(a.mean_diff[c]) <= 5 * a.mean_se[c])) return false;
  return a.mean_z2 <= 1.5;
}
// [end]

void report(const char* scene_name, const char* what, const agreement& a) {
  std::printf("%-14s %-22s mean diff %+.5f %+.5f %+.5f = %+5.2f %+5.2f %+5.2f se; pixels: mean z^2 "
              "%.2f, worst |z| %.1f\n",
              scene_name, what, a.mean_diff.x, a.mean_diff.y, a.mean_diff.z, a.mean_diff.x / a.mean_se.x,
              a.mean_diff.y / a.mean_se.y, a.mean_diff.z / a.mean_se.z, a.mean_z2, a.worst_z);
}

// The kernel with each method against one long mis render of the CPU path tracer.
constexpr int W = 16, H = 12, kernel_spp = 1024, reference_spp = 4096;

void check_scene(const char* name, const scene& sc, std::vector<integrator> methods) {
  auto ctx = device();
  if (!ctx) return;
  const estimate ref = cpu_reference(sc, W, H, reference_spp, method(integrator::mis), 1000);
  for (integrator m : methods) {
    std::string options;
    const estimate k = kernel_render(*ctx, sc, W, H, kernel_spp, method(m), 7, &options);
    CAPTURE(options);
    const agreement a = compare(k, ref);
    report(name, (std::string("kernel ") + zraka::name(m) + " vs CPU mis").c_str(), a);
    CHECK(within(a));
    if (m == methods.back()) {  // the test can fail: the kernel's image made 10 % darker does
      const agreement darker = compare(k, ref, 0.9f);
      report(name, "  the same, 10 % darker", darker);
      CHECK_FALSE(within(darker));
    }
  }
}

// Paired: the kernel draws path.hpp's numbers in path.hpp's order, so most samples follow the
// same path as reference_sample's with the same (seed, pixel, sample) and differ only by float
// rounding. Were the streams out of step (a draw added or moved), the difference would be that
// of independent samples: the RMS difference must stay under 20 % of that.
void check_paired(const char* name, const scene& sc, integrator m, int w = 16, int h = 12,
                  std::string* options = nullptr) {
  auto ctx = device();
  if (!ctx) return;
  const int spp = 16;
  const std::uint64_t seed = 11;
  const estimate k = kernel_render(*ctx, sc, w, h, spp, method(m), seed, options);
  const estimate c = cpu_reference(sc, w, h, spp, method(m), seed);
  double d2 = 0, independent = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const vec3 d = vec3(k.mean.at(x, y)) - vec3(c.mean.at(x, y));
      d2 += glm::dot(d, d);
      independent += 2.0 * glm::dot(vec3(c.variance.at(x, y)), vec3(1)) / spp;
    }
  std::printf("%-14s paired with reference_sample (%s, %d spp): RMS difference %.5f, independent %.5f\n", name,
              zraka::name(m), spp, std::sqrt(d2 / (3 * w * h)), std::sqrt(independent / (3 * w * h)));
  CHECK(d2 < 0.04 * independent);
}

}  // namespace

TEST_CASE("the kernel sees the structs gpu_scene.hpp packs: same sizes and offsets") {
  auto ctx = device();
  if (!ctx) return;
  const auto prog = cl::build_program_files(*ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
                                            "-cl-std=CL1.2 -DHAS_SPHERES -DMETHOD_MIS");
  const auto k = cl::make_kernel(prog, "layout");
  const auto out = ctx->make_buffer(CL_MEM_WRITE_ONLY, 38 * sizeof(cl_uint));
  cl::set_args(k, out);
  cl::run_1d(*ctx, k, 1);
  std::vector<cl_uint> v(38);
  ctx->read(out, 38 * sizeof(cl_uint), v.data());
  const std::vector<cl_uint> host = {
      sizeof(gpu_sphere), offsetof(gpu_sphere, material), sizeof(gpu_sphere), offsetof(gpu_sphere, light),
      sizeof(gpu_quad), offsetof(gpu_quad, material), sizeof(gpu_plane), offsetof(gpu_plane, material),
      sizeof(gpu_triangle), offsetof(gpu_triangle, material), sizeof(gpu_triangle), offsetof(gpu_triangle, light),
      sizeof(gpu_node4), offsetof(gpu_node4, count), sizeof(gpu_material), offsetof(gpu_material, fuzz),
      sizeof(gpu_material), offsetof(gpu_material, shininess), sizeof(gpu_light), offsetof(gpu_light, kind),
      sizeof(gpu_light), offsetof(gpu_light, cdf), sizeof(gpu_light_triangle), offsetof(gpu_light_triangle, c),
      sizeof(gpu_material), offsetof(gpu_material, eta), sizeof(gpu_material), offsetof(gpu_material, albedo_texture),
      sizeof(gpu_material), offsetof(gpu_material, roughness), sizeof(gpu_texture), offsetof(gpu_texture, kind),
      sizeof(gpu_texture), offsetof(gpu_texture, cell), sizeof(gpu_environment),
      offsetof(gpu_environment, cos_rotation), sizeof(gpu_quad4), offsetof(gpu_quad4, wz)};
  for (std::size_t i = 0; i < 38; ++i) CHECK(v[i] == host[i]);
}

// Issue 11's scene: naive cannot find the point light, and says so, on the CPU and here.
TEST_CASE("against the CPU's mis: an emissive triangle and a point light (nee, mis; naive refused)") {
  const scene sc = triangle_light_scene();
  CHECK_THROWS_WITH_AS(pack_scene(sc, W, H, method(integrator::naive)), doctest::Contains("point light"), error);
  check_scene("triangle+point", sc, {integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: a two-sided quad over a floor, both faces seen (naive, nee, mis)") {
  check_scene("two-sided quad", two_sided_scene(), {integrator::naive, integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: a mesh light, a checker floor (naive, nee, mis)") {
  check_scene("mesh light", mesh_light_scene(), {integrator::naive, integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: Phong under a quad light and a sky (naive, nee, mis)") {
  check_scene("phong", phong_scene(), {integrator::naive, integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: the Cornell box with glass (naive, nee, mis)") {
  check_scene("cornell glass", cornell_box<double>(cornell_variant::glass),
              {integrator::naive, integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: diffuse spheres, a spherical light, a sky (naive, nee, mis)") {
  check_scene("spheres", spheres_scene(), {integrator::naive, integrator::nee, integrator::mis});
}

// A closed form (book 2.3's furnace): the camera inside a sphere of albedo a that glows with Le
// on its inside sees L = Le (1 - a^(D+1)) / (1 - a) after at most D bounces, in every pixel;
// the sphere is a light sampled from its own inside (every direction of the cone).
TEST_CASE("the furnace: inside a glowing sphere, Le (1 - a^(D+1)) / (1 - a) (naive, nee, mis)") {
  auto ctx = device();
  if (!ctx) return;
  scene sc;
  material m = material::lambertian(rgb(0.5f));
  m.radiance = rgb(1.0f);
  m.two_sided = true;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(m));
  sc.camera.position = {0.2, -0.1, 0.3};
  sc.camera.look_at = {0, 0, -1};
  const int depth = 5, w = 8, h = 8, spp = 256;
  const double expected = (1 - std::pow(0.5, depth + 1)) / (1 - 0.5);
  for (integrator mth : {integrator::naive, integrator::nee, integrator::mis}) {
    const estimate k = kernel_render(*ctx, sc, w, h, spp, method(mth, depth), 3);
    double mean = 0, var = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        mean += double(k.mean.at(x, y).x) / (w * h);
        var += double(k.variance.at(x, y).x) / spp / (w * h) / (w * h);
      }
    const double se = std::sqrt(var);
    std::printf("furnace        kernel %-5s mean %.5f, expected %.5f: %+.2f se (se %.5f)\n", zraka::name(mth), mean,
                expected, (mean - expected) / se, se);
    CHECK(std::abs(mean - expected) <= 5 * se + 1e-4 * expected);
    CHECK(se > 0);
  }
}

TEST_CASE("the kernel draws path.hpp's random numbers in path.hpp's order (paired samples)") {
  check_paired("triangle+point", triangle_light_scene(), integrator::mis);
  check_paired("phong", phong_scene(), integrator::mis);
}

TEST_CASE("against the CPU's mis: a triangle mesh in the Cornell box (nee, mis)") {
  // The kernel's watertight leaf test (hit_bvh, test_triangle) against the CPU's mesh BVH: a
  // tilted octahedron of 8 triangles, flat shaded (no vertex normals), on the glass variant.
  scene sc = cornell_box<double>(cornell_variant::glass);
  mesh m;
  const vec3 c(-0.45, 0.55, 0.35);
  const double r = 0.35;
  const vec3 ax = glm::normalize(vec3(1, 0.3, 0.2)), ay = glm::normalize(glm::cross(vec3(0, 0, 1), ax));
  const vec3 az = glm::cross(ax, ay);
  for (const vec3& d : {ax, -ax, ay, -ay, az, -az}) m.positions.push_back(c + r * d);
  // vertices 0/1: +-x, 2/3: +-y, 4/5: +-z; counter-clockwise from outside
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  sc.add(m, sc.add_material(material::lambertian(rgb(0.2f, 0.7f, 0.3f))));
  camera cam_settings = sc.camera;
  cam_settings.aspect = 1;
  const auto cam = cam_settings.prepare();
  int seen = 0;  // pixels whose camera ray meets the mesh first: it is in the picture
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      scene_hit h;
      if (nearest_hit(sc, cam.generate((x + 0.5) / 64, (y + 0.5) / 64), h))
        seen += h.object.kind == shape_kind::mesh ? 1 : 0;
    }
  MESSAGE("the mesh covers " << seen << " of 4096 pixels");
  CHECK(seen > 100);
  check_scene("cornell glass + octahedron mesh", sc, {integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: rough conductors, a preset, an F0 and a roughness map (nee, mis)") {
  check_scene("rough metal", rough_conductor_scene(), {integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: rough dielectrics, a ball and a pane (nee, mis)") {
  check_scene("rough glass", rough_dielectric_scene(), {integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: image textures (repeat, clamp, a mesh's uvs) and marble (nee, mis)") {
  check_scene("textures", textured_scene(), {integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: checkers in uv, an albedo and a roughness map (nee, mis)") {
  check_scene("uv checker", uv_checker_scene(), {integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: an environment map, the only light (naive, nee, mis)") {
  check_scene("sky map", sky_scene(false), {integrator::naive, integrator::nee, integrator::mis});
}

TEST_CASE("against the CPU's mis: a constant environment (mis)") {
  check_scene("constant sky", sky_scene(true), {integrator::mis});
}

TEST_CASE("the new features draw path.hpp's numbers in path.hpp's order (paired samples)") {
  check_paired("rough metal", rough_conductor_scene(), integrator::mis);
  check_paired("rough glass", rough_dielectric_scene(), integrator::mis);
  check_paired("textures", textured_scene(), integrator::mis);
  check_paired("sky map", sky_scene(false), integrator::mis);
}

// ---------------------------------------------------------------- the new functions at the extremes
// The kernel's environment sampling and image lookups (built with -DPROBES) against
// environment.hpp's and texture.hpp's on the same numbers: float against double, so within
// float rounding, at the places where a float copy could go wrong.
TEST_CASE("the kernel's environment: samples, densities and radiance as environment.hpp's, at the extremes") {
  auto ctx = device();
  if (!ctx) return;
  image sky(8, 4);  // a row and a column of zeros (empty bins), one bright texel, the rest graded
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) sky.at(x, y) = y == 3 || x == 5 ? rgb(0) : rgb(0.2f * float(x + 1), 0.5f, float(y + 1));
  sky.at(2, 1) = rgb(50, 40, 30);
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::lambertian(rgb(0.5f))));
  sc.environment = std::make_shared<environment_map>(environment_map::from_image(sky, "sky", 1.0f, 30));
  const environment_map& e = *sc.environment;
  const gpu_scene g = pack_scene(sc, 4, 4, method(integrator::mis));
  std::vector<cl_float4> in;
  std::vector<vec2> us = {{0, 0}, {0x1.fffffep-1, 0x1.fffffep-1}, {0, 0x1.fffffep-1}, {0.5, 0.5}, {0.999, 0.001}};
  rng r(5, 0, 0);
  while (us.size() < 64) us.push_back(vec2(float(r.uniform()), float(r.uniform())));
  std::vector<vec3> ds = {{0, 1, 0}, {0, -1, 0}, {1, 0, 0}, {0, 0, -1}, {1e-30, 1, 0}};
  while (ds.size() < us.size()) ds.push_back(glm::normalize(vec3(r.uniform() - 0.5, r.uniform() - 0.5, r.uniform() - 0.5)));
  for (const vec2& u : us) in.push_back({{float(u.x), float(u.y), 0, 0}});
  for (const vec3& d : ds) in.push_back({{float(d.x), float(d.y), float(d.z), 0}});
  const int n = int(us.size());
  const auto prog = cl::build_program_files(*ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
                                            "-cl-std=CL1.2 -DHAS_ENVIRONMENT -DMETHOD_MIS -DPROBES");
  const auto k = cl::make_kernel(prog, "probe_environment");
  const auto env = ctx->make_buffer(CL_MEM_READ_ONLY, sizeof(gpu_environment), &g.environment);
  const auto tables = ctx->make_buffer(CL_MEM_READ_ONLY, g.env_tables.size() * sizeof(float), g.env_tables.data());
  const auto texels = ctx->make_buffer(CL_MEM_READ_ONLY, g.texels.size() * sizeof(gpu_float4), g.texels.data());
  const auto inb = ctx->make_buffer(CL_MEM_READ_ONLY, in.size() * sizeof(cl_float4), in.data());
  const auto out = ctx->make_buffer(CL_MEM_WRITE_ONLY, 3 * in.size() * sizeof(cl_float4));
  cl::set_args(k, env, tables, texels, inb, out, cl_int(n));
  cl::run_1d(*ctx, k, std::size_t(n));
  std::vector<cl_float4> o(3 * std::size_t(n));
  ctx->read(out, o.size() * sizeof(cl_float4), o.data());
  for (int i = 0; i < n; ++i) {
    const cl_float4 s = o[3 * std::size_t(i)], self = o[3 * std::size_t(i) + 1], l = o[3 * std::size_t(i) + 2];
    double pdf = 0;
    const vec3 w = e.sample(vec2(double(in[std::size_t(i)].s[0]), double(in[std::size_t(i)].s[1])), pdf);
    CAPTURE(i);
    CHECK(std::abs(s.s[0] - w.x) < 1e-4);  // the same direction for the same numbers
    CHECK(std::abs(s.s[1] - w.y) < 1e-4);
    CHECK(std::abs(s.s[2] - w.z) < 1e-4);
    // Its density is the CPU's density of the direction the kernel made (next to a pole, where
    // 1 - v has no digits left in float, that direction is not quite the CPU's), and the
    // kernel's own env_pdf of it: what makes MIS and NEE consistent.
    // u.x = 0 is the seam phi = 0 = 2 pi, where the direction's density is read from the last
    // column instead of the first, by the CPU's pdf() as well: a set of measure zero.
    const vec3 wk(s.s[0], s.s[1], s.s[2]);
    CHECK(std::isfinite(s.s[3]));
    if (in[std::size_t(i)].s[0] != 0.0f) {
      CHECK(s.s[3] == doctest::Approx(e.pdf(glm::normalize(wk))).epsilon(1e-4));
      CHECK(self.s[0] == doctest::Approx(s.s[3]).epsilon(1e-4));
    }
    if (i > 4) CHECK(s.s[3] == doctest::Approx(pdf).epsilon(1e-4));  // away from the extremes: the CPU's too
    const vec3 d = ds[std::size_t(i)];
    const double p = e.pdf(d);
    const rgb L = e.radiance(d);
    CHECK(l.s[3] == doctest::Approx(p).epsilon(1e-4));  // 0 at the poles, exactly
    if (p == 0) CHECK(l.s[3] == 0.0f);
    for (int c = 0; c < 3; ++c) CHECK(l.s[c] == doctest::Approx(L[c]).epsilon(1e-4));
  }
}

TEST_CASE("the kernel's microfacets: f, pdf and samples as microfacet.hpp's, grazing and at alpha 1e-4 to 1") {
  auto ctx = device();
  if (!ctx) return;
  const material gold = material::rough_conductor(0.5, *find_metal("gold"));
  const gpu_material gm = to_gpu(gold);
  struct case_t {
    vec3 wo, wi;
    double alpha, u_lobe, ux, uy, eta;
    int kind;  // 0 conductor, 1 glass
  };
  std::vector<case_t> cases;
  rng r(13, 0, 0);
  auto unit = [&] {
    return glm::normalize(vec3(r.uniform() - 0.5, r.uniform() - 0.5, r.uniform() - 0.5) + vec3(0, 0, 1e-3));
  };
  const vec3 grazing = glm::normalize(vec3(1, 0.2, 1e-6));
  const vec3 edge[] = {{0, 0, 1}, grazing, {1, 0, 0}, {0.6, 0, -0.8}};  // normal, grazing, on the horizon, below
  for (double alpha : {1e-4, 1e-3, 0.05, 0.5, 1.0})
    for (int kind : {0, 1})
      for (double eta : {1.5, 1 / 1.5}) {
        for (const vec3& wo : edge) cases.push_back({wo, unit(), alpha, r.uniform(), r.uniform(), r.uniform(), eta, kind});
        for (int k = 0; k < 12; ++k) {
          vec3 wo = unit();
          wo.z = std::abs(wo.z);
          cases.push_back({wo, unit(), alpha, r.uniform(), r.uniform(), r.uniform(), eta, kind});
        }
      }
  std::vector<cl_float4> in;
  for (const case_t& c : cases) {
    in.push_back({{float(c.wo.x), float(c.wo.y), float(c.wo.z), float(c.alpha)}});
    in.push_back({{float(c.wi.x), float(c.wi.y), float(c.wi.z), float(c.u_lobe)}});
    in.push_back({{float(c.ux), float(c.uy), float(c.eta), float(c.kind)}});
  }
  const int n = int(cases.size());
  const auto prog = cl::build_program_files(
      *ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
      "-cl-std=CL1.2 -DHAS_ROUGH_CONDUCTOR -DHAS_ROUGH_DIELECTRIC -DMETHOD_MIS -DPROBES");
  const auto k = cl::make_kernel(prog, "probe_microfacet");
  const auto mb = ctx->make_buffer(CL_MEM_READ_ONLY, sizeof gm, &gm);
  const auto inb = ctx->make_buffer(CL_MEM_READ_ONLY, in.size() * sizeof(cl_float4), in.data());
  const auto out = ctx->make_buffer(CL_MEM_WRITE_ONLY, 4 * cases.size() * sizeof(cl_float4));
  cl::set_args(k, mb, inb, out, cl_int(n));
  cl::run_1d(*ctx, k, std::size_t(n));
  std::vector<cl_float4> o(4 * cases.size());
  ctx->read(out, o.size() * sizeof(cl_float4), o.data());
  int compared = 0, sampled = 0;
  for (int i = 0; i < n; ++i) {
    const case_t& c = cases[std::size_t(i)];
    // The CPU side on the float inputs the kernel saw.
    auto f32 = [](const vec3& v) { return vec3(float(v.x), float(v.y), float(v.z)); };
    const vec3 wo = f32(c.wo), wi = f32(c.wi);
    const ggx_t<double> d(double(float(c.alpha)));
    const double eta = double(float(c.eta));
    rgb f;
    double pdf;
    std::optional<microfacet_sample_t<double>> sm;
    const vec2 u(double(float(c.ux)), double(float(c.uy)));
    if (c.kind == 0) {
      const rough_conductor_t<double> m{d, gold.get<material_kinds::rough_conductor>()->conductor};
      f = m.f(wo, wi);
      pdf = m.pdf(wo, wi);
      sm = m.sample(wo, u);
    } else {
      const rough_dielectric_t<double> m{d, eta};
      f = rgb(float(m.f(wo, wi)));
      pdf = m.pdf(wo, wi);
      sm = m.sample(wo, u, double(float(c.u_lobe)));
    }
    const cl_float4 kf = o[4 * std::size_t(i)], ks = o[4 * std::size_t(i) + 1], kw = o[4 * std::size_t(i) + 2];
    CAPTURE(i);
    CAPTURE(c.alpha);
    CAPTURE(c.kind);
    for (const cl_float4& v : {kf, ks, kw})
      for (int j = 0; j < 4; ++j) CHECK(std::isfinite(v.s[j]));  // never NaN or inf, grazing or sharp
    CHECK(kf.s[3] >= 0.0f);
    if (!(wo.z > 0)) {  // on the horizon or below: nothing, on both sides
      CHECK(kf.s[0] == 0.0f);
      CHECK(kf.s[3] == 0.0f);
      CHECK(kw.s[3] == 0.0f);
      CHECK_FALSE(sm);
      continue;
    }
    // Float against double: the sharpest lobes move by the float rounding of a direction over
    // alpha, so compare where the lobe is resolved (alpha >= 1e-3) and not on a knife's edge.
    if (c.alpha >= 1e-3 && wo.z > 1e-3) {
      ++compared;
      for (int j = 0; j < 3; ++j) CHECK(kf.s[j] == doctest::Approx(f[j]).epsilon(2e-3).scale(1e-6));
      CHECK(kf.s[3] == doctest::Approx(pdf).epsilon(2e-3).scale(1e-6));
      if (sm && kw.s[3] == 1.0f && std::abs(double(c.u_lobe) - 0.5) < 0.45) {
        ++sampled;
        CHECK(std::abs(ks.s[0] - sm->wi.x) < 1e-3);
        CHECK(std::abs(ks.s[2] - sm->wi.z) < 1e-3);
        CHECK(ks.s[3] == doctest::Approx(sm->pdf).epsilon(2e-3));
        CHECK(kw.s[1] == doctest::Approx(sm->weight.y).epsilon(2e-3));
      }
    }
    if (kw.s[3] == 1.0f) CHECK(ks.s[3] > 0.0f);  // a sample has a density
  }
  MESSAGE(compared << " cases compared with microfacet.hpp, " << sampled << " samples");
  CHECK(compared > 150);
  CHECK(sampled > 60);
}

// The kernel tests quads four at a time (quad4_roots); each lane must be quad.hpp's quad_root on
// the packed numbers, bit for bit: the kernel does not fuse products there (FP_CONTRACT OFF),
// and this build does not either (no -mfma). Seven quads (the second group has an empty lane),
// a tiny and a huge one among them; rays from anywhere, rays aimed at and just beside each
// quad, rays leaving a quad's surface (which must not see it again) and rays grazing its plane.
namespace {
// Rays for a probe kernel: ray i is in[2i] (origin) and in[2i + 1] (direction, w: t_max).
std::vector<cl_float4> probe_rays(const std::vector<std::pair<vec3f, glm::vec4>>& rays) {
  std::vector<cl_float4> in;
  for (const auto& [o, d] : rays) {
    in.push_back({{o.x, o.y, o.z, 0}});
    in.push_back({{d.x, d.y, d.z, d.w}});
  }
  return in;
}
}  // namespace

TEST_CASE("the kernel's quads four at a time: each lane is quad.hpp's test (nearest and any hit)") {
  auto ctx = device();
  if (!ctx) return;
  scene sc;
  int shade = 0;  // a material of its own for each quad: the lanes' probe reports the material
  auto m = [&] { return sc.add_material(material::lambertian(rgb(0.1f * float(++shade)))); };
  sc.add(quad{{-2, -2, -3}, {4, 0, 0}, {0, 4, 0}}, m());                      // back wall
  sc.add(quad{{-2, -2, -3}, {0, 0, 5}, {4, 0, 0}}, m());                      // floor
  sc.add(quad{{-2, -2, -3}, {0, 4, 0}, {0, 0, 5}}, m());                      // left wall
  sc.add(quad{{-0.5, 0.3, -1}, {1, 0.2, 0.1}, {-0.1, 0.3, 0.8}}, m());        // slanted
  sc.add(quad{{0.25, 0.25, -1.5}, {1e-6, 0, 0}, {0, 1e-6, 0}}, m());         // tiny (float: w = N/|n|)
  sc.add(quad{{-1e10, 1.5, -1e10}, {2e10, 0, 0}, {0, 0, 2e10}}, m());        // huge ceiling
  sc.add(quad{{1, -1, -2}, {0, 1.5, 0}, {0.2, 0, 1}}, m());
  const gpu_scene g = pack_scene(sc, 4, 4, method(integrator::mis));
  REQUIRE(g.quads.size() == 7);
  REQUIRE(g.quad_groups.size() == 2);
  // The CPU's test on the kernel's numbers: the packed corner, edges, unit normal and w.
  std::vector<quadf> qs;
  std::vector<quad_plane_t<float>> pls;
  for (std::size_t j = 0; j < g.quads.size(); ++j) {
    const gpu_quad& q = g.quads[j];
    auto v3 = [](const gpu_float4& v) { return vec3f(v.x, v.y, v.z); };
    qs.push_back(quadf{v3(q.corner), v3(q.u), v3(q.v)});
    pls.push_back(quad_plane_t<float>(qs.back()));
    pls.back().N = v3(q.normal_area);
    pls.back().w = float_quad_w(sc.quads[j].shape);  // what pack_scene puts in the lanes
  }
  rng r(21, 0, 0);
  auto uniform = [&](double lo, double hi) { return float(lo + (hi - lo) * r.uniform()); };
  auto direction = [&] { return glm::normalize(vec3f(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1))); };
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<std::pair<vec3f, glm::vec4>> rays;  // origin; direction and t_max
  for (int i = 0; i < 400; ++i) rays.push_back({vec3f(uniform(-1.9, 1.9), uniform(-1.9, 1.4), uniform(-2.9, 1)), glm::vec4(direction(), inf)});
  for (std::size_t j = 0; j < qs.size(); ++j)
    for (int i = 0; i < 60; ++i) {
      const bool huge = j == 5;
      const vec3f o(uniform(-1.5, 1.5), huge ? uniform(-1.5, 1.0) : uniform(-1.5, 1.4), uniform(-1, 1));
      const float a = huge ? uniform(0.49, 0.51) : uniform(-0.2, 1.2), b = huge ? uniform(0.49, 0.51) : uniform(-0.2, 1.2);
      const vec3f target = qs[j].point(a, b);
      const float t_max = i % 3 == 0 ? glm::length(target - o) * uniform(0.5, 1.5) : inf;
      rays.push_back({o, glm::vec4(glm::normalize(target - o), t_max)});
      if (j != 5) {
        const vec3f on = qs[j].point(uniform(0.1, 0.9), uniform(0.1, 0.9));  // leaving the surface
        rays.push_back({on, glm::vec4(direction(), inf)});
        rays.push_back({on + 1e-3f * pls[j].N, glm::vec4(glm::normalize(qs[j].u + uniform(-1e-7, 1e-7) * pls[j].N), inf)});
      }
    }
  const std::vector<cl_float4> in = probe_rays(rays);
  const int n = int(rays.size());
  const auto prog = cl::build_program_files(*ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
                                            "-cl-std=CL1.2 -DHAS_QUADS -DMETHOD_MIS -DPROBES");
  const auto k = cl::make_kernel(prog, "probe_quads");
  const auto quads = ctx->make_buffer(CL_MEM_READ_ONLY, g.quads.size() * sizeof(gpu_quad), g.quads.data());
  const auto groups = ctx->make_buffer(CL_MEM_READ_ONLY, g.quad_groups.size() * sizeof(gpu_quad4), g.quad_groups.data());
  const auto inb = ctx->make_buffer(CL_MEM_READ_ONLY, in.size() * sizeof(cl_float4), in.data());
  const auto out = ctx->make_buffer(CL_MEM_WRITE_ONLY, in.size() * sizeof(cl_float4));
  cl::set_args(k, quads, groups, cl_int(g.quads.size()), inb, out, cl_int(n));
  cl::run_1d(*ctx, k, std::size_t(n));
  std::vector<cl_float4> o(in.size());
  ctx->read(out, o.size() * sizeof(cl_float4), o.data());
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const auto& [origin, d] = rays[std::size_t(i)];
    rayf ray;  // the kernel's direction as it is, not normalised again
    ray.origin = origin;
    ray.direction = vec3f(d);
    int want = -1;
    quad_root_t<float> best{};
    for (std::size_t j = 0; j < qs.size(); ++j)
      if (auto root = quad_root(qs[j], pls[j], ray, 0.0f, want < 0 ? d.w : best.t)) {
        want = int(j);
        best = *root;
      }
    const cl_float4 got = o[2 * std::size_t(i)];
    const int index = int(got.s[3]);
    const bool blocked = o[2 * std::size_t(i) + 1].s[0] == 1.0f;
    CAPTURE(i);
    CHECK(index < int(qs.size()));
    CHECK(index == want);
    CHECK(blocked == (want >= 0));
    if (want < 0 || index != want) continue;
    ++hits;
    CHECK(got.s[0] == best.t);
    CHECK(got.s[1] == best.a);
    CHECK(got.s[2] == best.b);
  }
  std::printf("quads four at a time: %d rays, %d hits, each checked bit for bit against quad_root\n", n, hits);
  CHECK(hits > n / 3);

  // The eight-lane loop's tests (PATH_LANES) on the same rays, eight at a time (the last work
  // item has lanes without a ray): quad_root's nearest quad and t, bit for bit, and its any hit.
  const auto lanes_prog = cl::build_program_files(*ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
                                                  "-cl-std=CL1.2 -DHAS_QUADS -DMETHOD_MIS -DPATH_LANES=8 -DPROBES");
  const auto lk = cl::make_kernel(lanes_prog, "probe_lanes");
  const auto no_spheres = ctx->make_buffer(CL_MEM_READ_ONLY, sizeof(gpu_sphere));
  const auto lanes_out = ctx->make_buffer(CL_MEM_WRITE_ONLY, 3 * std::size_t(n) * sizeof(cl_float4));
  cl::set_args(lk, no_spheres, cl_int(0), quads, groups, cl_int(g.quads.size()), inb, lanes_out, cl_int(n));
  cl::run_1d(*ctx, lk, std::size_t((n + 7) / 8));
  std::vector<cl_float4> lo(3 * std::size_t(n));
  ctx->read(lanes_out, lo.size() * sizeof(cl_float4), lo.data());
  int lane_hits = 0;
  for (int i = 0; i < n; ++i) {
    const auto& [origin, d] = rays[std::size_t(i)];
    rayf ray;
    ray.origin = origin;
    ray.direction = vec3f(d);
    int want = -1, nearest = -1;  // with the ray's t_max, and without one
    quad_root_t<float> best{};
    for (std::size_t j = 0; j < qs.size(); ++j) {
      if (quad_root(qs[j], pls[j], ray, 0.0f, d.w)) want = int(j);
      if (auto root = quad_root(qs[j], pls[j], ray, 0.0f, nearest < 0 ? inf : best.t)) {
        nearest = int(j);
        best = *root;
      }
    }
    const cl_float4 got = lo[3 * std::size_t(i)];
    CAPTURE(i);
    CHECK(int(got.s[1]) == (nearest < 0 ? -1 : g.quads[std::size_t(nearest)].material));
    CHECK((lo[3 * std::size_t(i) + 2].s[0] == 1.0f) == (want >= 0));
    if (nearest < 0) continue;
    ++lane_hits;
    CHECK(got.s[0] == best.t);
    CHECK((got.s[2] == 1.0f) == (glm::dot(ray.direction, pls[std::size_t(nearest)].N) < 0));
  }
  std::printf("the same rays in eight lanes: %d hits, each quad_root's nearest quad and t bit for bit\n", lane_hits);
  CHECK(lane_hits > n / 3);
}

// The lanes loop's sphere test (sphere8_root, and the record nearest_hit8 makes) against
// sphere.hpp in float on the kernel's numbers, at the extremes: a 1e-6 sphere, a 1e10 sphere whose
// surface passes near the rays' origins, a sphere 1e6 away, two that overlap, rays aimed at each,
// tangent to each (the line 1e-6 inside and outside the radius), leaving a surface outwards and
// inwards, and starting inside. The products are not fused on either side: t and the point bit
// for bit.
TEST_CASE("the eight-lane loop's spheres: sphere.hpp's root and point bit for bit, at the extremes") {
  auto ctx = device();
  if (!ctx) return;
  scene sc;
  int shade = 0;
  auto m = [&] { return sc.add_material(material::lambertian(rgb(0.1f * float(++shade)))); };
  sc.add(sphere{{0, 0, -3}, 1}, m());
  sc.add(sphere{{0.8, 0, -3}, 0.5}, m());                // overlaps the first
  sc.add(sphere{{0.3, 0.2, -1}, 1e-6}, m());             // tiny
  sc.add(sphere{{0, -1e10 - 2, 0}, 1e10}, m());          // huge: a floor 2 below the origins
  sc.add(sphere{{0.5, 0.5, -1e6}, 1}, m());              // far
  const gpu_scene g = pack_scene(sc, 4, 4, method(integrator::mis));
  REQUIRE(g.spheres.size() == 5);
  std::vector<sphere_t<float>> ss;
  for (const gpu_sphere& s : g.spheres)
    ss.push_back({vec3f(s.center_radius.x, s.center_radius.y, s.center_radius.z), s.center_radius.w});
  rng r(23, 0, 0);
  auto uniform = [&](double lo, double hi) { return float(lo + (hi - lo) * r.uniform()); };
  auto direction = [&] { return glm::normalize(vec3f(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1))); };
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<std::pair<vec3f, glm::vec4>> rays;
  for (int i = 0; i < 300; ++i) rays.push_back({vec3f(uniform(-2, 2), uniform(-1.9, 2), uniform(-4, 1)), glm::vec4(direction(), inf)});
  for (std::size_t j = 0; j < ss.size(); ++j) {
    const vec3f c = ss[j].center;
    const float R = ss[j].radius;
    for (int i = 0; i < 60; ++i) {
      const vec3f o(uniform(-1, 1), uniform(-1, 1), uniform(-0.5, 0.5));
      const vec3f w = direction();  // a point on the sphere, towards the origin's side
      const vec3f to_o = glm::normalize(o - c);
      const vec3f n = glm::normalize(to_o + 0.9f * w);
      const float t_max = i % 3 == 0 ? uniform(0.5, 3.0) : inf;
      if (j != 3) rays.push_back({o, glm::vec4(glm::normalize((c + R * n) - o), t_max)});
      // tangent: the line passes at R (1 +- 1e-6) from the centre
      const vec3f side = glm::normalize(glm::cross(to_o, w));
      const float k = i % 2 ? 1 + 1e-6f : 1 - 1e-6f;
      if (j != 3) rays.push_back({o, glm::vec4(glm::normalize((c + k * R * side) - o), inf)});
      if (j == 3) rays.push_back({o, glm::vec4(glm::normalize(vec3f(uniform(-1, 1), uniform(-1, -0.01), uniform(-1, 1))), inf)});
      if (j <= 1) {
        const vec3f on = c + R * w;  // on the surface, leaving outwards and going in
        rays.push_back({on, glm::vec4(glm::normalize(w + 0.5f * direction()), inf)});
        rays.push_back({on, glm::vec4(-w, inf)});
        rays.push_back({c + 0.3f * R * direction(), glm::vec4(direction(), inf)});  // from inside
      }
    }
  }
  const std::vector<cl_float4> in = probe_rays(rays);
  const int n = int(rays.size());
  const auto prog = cl::build_program_files(*ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
                                            "-cl-std=CL1.2 -DHAS_SPHERES -DMETHOD_MIS -DPATH_LANES=8 -DPROBES");
  const auto k = cl::make_kernel(prog, "probe_lanes");
  const auto spheres = ctx->make_buffer(CL_MEM_READ_ONLY, g.spheres.size() * sizeof(gpu_sphere), g.spheres.data());
  const auto no_quads = ctx->make_buffer(CL_MEM_READ_ONLY, sizeof(gpu_quad4));
  const auto inb = ctx->make_buffer(CL_MEM_READ_ONLY, in.size() * sizeof(cl_float4), in.data());
  const auto out = ctx->make_buffer(CL_MEM_WRITE_ONLY, 3 * std::size_t(n) * sizeof(cl_float4));
  cl::set_args(k, spheres, cl_int(g.spheres.size()), no_quads, no_quads, cl_int(0), inb, out, cl_int(n));
  cl::run_1d(*ctx, k, std::size_t((n + 7) / 8));
  std::vector<cl_float4> o(3 * std::size_t(n));
  ctx->read(out, o.size() * sizeof(cl_float4), o.data());
  int hits = 0, tiny = 0, grazing = 0;
  for (int i = 0; i < n; ++i) {
    const auto& [origin, d] = rays[std::size_t(i)];
    rayf ray;  // the kernel's direction as it is
    ray.origin = origin;
    ray.direction = vec3f(d);
    int nearest = -1, want = -1;
    float best = inf;
    for (std::size_t j = 0; j < ss.size(); ++j) {
      if (sphere_root(ss[j], ray, 0.0f, d.w)) want = int(j);
      if (auto root = sphere_root(ss[j], ray, 0.0f, best)) {
        nearest = int(j);
        best = root->t;
      }
    }
    const cl_float4 got = o[3 * std::size_t(i)], p = o[3 * std::size_t(i) + 1];
    CAPTURE(i);
    CHECK(int(got.s[1]) == (nearest < 0 ? -1 : g.spheres[std::size_t(nearest)].material));
    CHECK((o[3 * std::size_t(i) + 2].s[0] == 1.0f) == (want >= 0));
    if (nearest < 0) continue;
    ++hits;
    tiny += nearest == 2;
    hit_t<float> rec;
    REQUIRE(intersect(ss[std::size_t(nearest)], ray, 0.0f, std::nextafter(best, inf), rec));
    CHECK(got.s[0] == best);
    CHECK(p.s[0] == rec.p.x);
    CHECK(p.s[1] == rec.p.y);
    CHECK(p.s[2] == rec.p.z);
    CHECK((got.s[2] == 1.0f) == rec.front_face);
    const vec3f f = ray.origin - ss[std::size_t(nearest)].center;  // a tangent ray that touched
    grazing += std::abs(glm::length(f - glm::dot(f, ray.direction) * ray.direction) - ss[std::size_t(nearest)].radius) <
               1e-5f * ss[std::size_t(nearest)].radius;
  }
  std::printf("spheres in eight lanes: %d rays, %d hits (%d on the 1e-6 sphere, %d tangent), each sphere_root's t and "
              "the record's point bit for bit\n", n, hits, tiny, grazing);
  CHECK(hits > n / 3);
  CHECK(tiny > 10);
  CHECK(grazing > 10);
}

TEST_CASE("the kernel's image lookups: texture.hpp's bilinear, repeat and clamp, NaN and huge (u, v)") {
  auto ctx = device();
  if (!ctx) return;
  auto img = std::make_shared<image>(5, 3);
  rng r(9, 0, 0);
  for (rgb& p : img->pixels) p = rgb(float(r.uniform()), float(r.uniform()), float(r.uniform()));
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  std::vector<cl_float2> uv = {{{nan, 0.5f}}, {{0.5f, inf}}, {{-inf, -inf}}, {{1e30f, -1e30f}}, {{-1e-9f, 1e-9f}},
                               {{0x1.fffffep-1f, 0.0f}}, {{0.5f, 0.5f}}, {{2.7f, -3.2f}}, {{0.1f, 0.9f}}, {{-0.3f, 1.6f}}};
  while (uv.size() < 64) uv.push_back({{float(4 * r.uniform() - 2), float(4 * r.uniform() - 2)}});
  const int n = int(uv.size());
  const auto prog = cl::build_program_files(*ctx, {"kernels/rng.cl", "kernels/pathtrace.cl"},
                                            "-cl-std=CL1.2 -DHAS_TEXTURES -DHAS_IMAGE_TEXTURES -DMETHOD_MIS -DPROBES");
  const auto k = cl::make_kernel(prog, "probe_image");
  for (bool repeat : {true, false}) {
    scene sc;
    sc.add(sphere{{0, 0, -3}, 1}, sc.add_material(material::lambertian(texture::image_map(img, repeat))));
    const gpu_scene g = pack_scene(sc, 4, 4, method(integrator::mis));
    REQUIRE(g.textures.size() == 1);
    const auto t = ctx->make_buffer(CL_MEM_READ_ONLY, sizeof(gpu_texture), g.textures.data());
    const auto texels = ctx->make_buffer(CL_MEM_READ_ONLY, g.texels.size() * sizeof(gpu_float4), g.texels.data());
    const auto uvb = ctx->make_buffer(CL_MEM_READ_ONLY, uv.size() * sizeof(cl_float2), uv.data());
    const auto out = ctx->make_buffer(CL_MEM_WRITE_ONLY, uv.size() * sizeof(cl_float4));
    cl::set_args(k, t, texels, uvb, out, cl_int(n));
    cl::run_1d(*ctx, k, std::size_t(n));
    std::vector<cl_float4> o(uv.size());
    ctx->read(out, o.size() * sizeof(cl_float4), o.data());
    for (int i = 0; i < n; ++i) {
      const rgb want = lookup_bilinear(*img, double(uv[std::size_t(i)].s[0]), double(uv[std::size_t(i)].s[1]), repeat);
      CAPTURE(i);
      CAPTURE(repeat);
      for (int c = 0; c < 3; ++c) CHECK(std::abs(o[std::size_t(i)].s[c] - want[c]) < 1e-5);
    }
  }
}

// The loop of eight paths per work item (PATH_LANES) is built for the scenes it covers: each
// lane must draw path.hpp's numbers in path.hpp's order as the one-path loop does, for every
// method, with an aperture, and in a row whose width is not a multiple of 8 (the last work item
// has lanes without a pixel).
TEST_CASE("the eight-lane loop: path.hpp's samples in path.hpp's order (paired; naive, nee, mis; 13 x 5)") {
  scene glass = cornell_box<double>(cornell_variant::glass);
  scene lens = glass;
  lens.camera.aperture = 0.2;  // focused on look_at, the back wall
  for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
    std::string options;
    check_paired("cornell glass", glass, m, 13, 5, &options);
    CAPTURE(options);
    if (!options.empty()) CHECK(options.find("-DPATH_LANES") != std::string::npos);
  }
  std::string options;
  check_paired("thin lens", lens, integrator::mis, 13, 5, &options);
  CAPTURE(options);
  if (!options.empty()) CHECK(options.find("-DHAS_THIN_LENS") != std::string::npos);
  if (!options.empty()) CHECK(options.find("-DPATH_LANES") != std::string::npos);
  // No light to sample (a plain background): the light sample's three numbers are drawn all the same.
  scene open;
  const int grey = open.add_material(material::lambertian(rgb(0.5f)));
  open.add(sphere{{0, 0, -1}, 0.5}, grey);
  open.add(sphere{{0, -100.5, -1}, 100}, grey);
  open.background = rgb(0.6f, 0.7f, 0.9f);
  for (integrator m : {integrator::naive, integrator::nee}) {
    check_paired("no light", open, m, 13, 5, &options);
    if (!options.empty()) CHECK(options.find("-DPATH_LANES") != std::string::npos);
  }
  // A spherical light and a world-space checker (book 4.3's scene): the lanes call the one-path
  // loop's sample_light, light_pdf and albedo lane by lane. The furnace: a sphere light sampled
  // from its inside. A plane is still not covered: that scene takes the one-path loop.
  for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
    check_paired("spheres", spheres_scene(), m, 13, 5, &options);
    CAPTURE(options);
    if (!options.empty()) CHECK(options.find("-DPATH_LANES") != std::string::npos);
    if (!options.empty()) CHECK(options.find("-DHAS_SPHERE_LIGHTS") != std::string::npos);
    if (!options.empty()) CHECK(options.find("-DHAS_CHECKER") != std::string::npos);
  }
  check_paired("furnace", furnace_scene(), integrator::mis, 13, 5, &options);
  if (!options.empty()) CHECK(options.find("-DPATH_LANES") != std::string::npos);
  scene flat = open;
  flat.add(plane::from_point_normal({0, -0.5, 0}, {0, 1, 0}), grey);
  CHECK(build_options(pack_scene(flat, 8, 8, method(integrator::mis, 8)).features).find("PATH_LANES") ==
        std::string::npos);
}

TEST_CASE("progressive accumulation: 4 launches of 8 spp are one launch of 32") {
  auto ctx = device();
  if (!ctx) return;
  for (const scene& sc : {spheres_scene(), cornell_box<double>(cornell_variant::glass)}) {  // one path, eight lanes
    const gpu_scene g = pack_scene(sc, 32, 32, method(integrator::mis, 8));
    gpu_renderer a(*ctx, g, 32, 32, 3), b(*ctx, g, 32, 32, 3);
    for (int i = 0; i < 4; ++i) a.launch(8);
    b.launch(32);
    const image ia = a.read_image(), ib = b.read_image();
    CHECK(a.samples() == 32);
    double worst = 0;  // the same samples, summed in float in another grouping: rounding only
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        worst = std::max(worst, double(max_component(glm::abs(ia.at(x, y) - ib.at(x, y)))));
    CHECK(worst < 1e-4);
    a.reset();  // a restart gives the first frame again
    a.launch(32);
    CHECK(a.read_image().at(5, 7) == ib.at(5, 7));
  }
}

TEST_CASE("the display is image_io's to_byte of the running mean, byte for byte") {
  auto ctx = device();
  if (!ctx) return;
  int lit = 0, clamped = 0;
  for (const scene& sc : {spheres_scene(), realtime_scene("cornell")}) {  // the Cornell box's light: > 1
    const gpu_scene g = pack_scene(sc, 48, 32, method(integrator::mis, 8));
    gpu_renderer r(*ctx, g, 48, 32, 9);
    std::vector<std::uint8_t> bytes;
    for (const int n : {1, 3}) {  // after 1 sample and after 4
      r.launch(std::uint32_t(n));
      r.read_display(bytes);
      const image mean = r.read_image();  // top row first; the display is bottom row first
      for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 48; ++x)
          for (int c = 0; c < 3; ++c) {
            const std::uint8_t want = to_byte(mean.at(x, y)[c]);
            const std::uint8_t got = bytes[4 * (std::size_t(31 - y) * 48 + std::size_t(x)) + std::size_t(c)];
            CAPTURE(x);
            CAPTURE(y);
            REQUIRE(int(got) == int(want));
            lit += want > 0 && want < 255;
            clamped += mean.at(x, y)[c] > 1.0f;
          }
    }
  }
  CHECK(lit > 1000);   // the test saw the curve, not only black
  CHECK(clamped > 0);  // and a light, brighter than white
}

TEST_CASE("specialised and all-features kernels compute the same image (spheres, textures, a sky map)") {
  auto ctx = device();
  if (!ctx) return;
  for (const scene& sc : {spheres_scene(), textured_scene(), sky_scene(false)}) {
    const gpu_scene g = pack_scene(sc, 32, 32, method(integrator::mis, 8));
    gpu_renderer s(*ctx, g, 32, 32, 5, false), all(*ctx, g, 32, 32, 5, true);
    CHECK(all.options().find("HAS_TRIANGLES") != std::string::npos);
    CHECK(all.options().find("HAS_ENVIRONMENT") != std::string::npos);
    s.launch(4);
    all.launch(4);
    const image a = s.read_image(), b = all.read_image();
    double worst = 0;  // the same code runs; only the compiler's float contractions may differ
    for (int y = 0; y < 32; ++y)
      for (int x = 0; x < 32; ++x)
        worst = std::max(worst, double(max_component(glm::abs(a.at(x, y) - b.at(x, y)))));
    CAPTURE(s.options());
    CHECK(worst < 1e-3);
  }
  const gpu_scene spheres = pack_scene(spheres_scene(), 8, 8, method(integrator::mis, 8));
  CHECK(build_options(spheres.features).find("HAS_TRIANGLES") == std::string::npos);
  CHECK(build_options(spheres.features).find("HAS_ENVIRONMENT") == std::string::npos);
}

TEST_CASE("errata C7: the thesis's per-pixel seed repeats every frame; ours does not") {
  auto ctx = device();
  if (!ctx) return;
  gpu_scene g = pack_scene(spheres_scene(), 16, 16, method(integrator::mis, 4));
  auto frame_difference = [&](bool weak) {
    g.features.weak_seed = weak;
    gpu_renderer r(*ctx, g, 16, 16, 1);
    r.launch(1);
    const image first = r.read_image();
    r.launch(1);  // the mean of frames 1 and 2
    const image both = r.read_image();
    double d = 0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) d += double(max_component(glm::abs(both.at(x, y) - first.at(x, y))));
    return d;
  };
  CHECK(frame_difference(true) == 0.0);  // frame 2 = frame 1: accumulating never converges
  CHECK(frame_difference(false) > 0.0);
}

// gpu_scene.hpp: a scene packed into the flat arrays the real-time kernel reads, the features it
// uses and the -D switches made from them, and the CPU twin of one kernel sample. No OpenCL
// here (tests/test_realtime.cpp runs the kernel).
#include <zraka/cornell.hpp>
#include <zraka/gpu_scene.hpp>
#include <zraka/realtime.hpp>

#include <doctest/doctest.h>

#include <cstring>

using namespace zraka;

namespace {
bool has(const std::string& options, const std::string& word) {
  return (options + " ").find(" " + word + " ") != std::string::npos;
}
}  // namespace

TEST_CASE("diffuse spheres: only the sphere, checker and emitter switches") {
  const gpu_scene g = pack_scene(spheres_scene(), 64, 32, 8);
  CHECK(g.spheres.size() == 5);
  CHECK(g.quads.empty());
  CHECK(g.triangles.empty());
  CHECK(g.nodes.empty());
  REQUIRE(g.lights.size() == 1);
  CHECK(g.lights[0].kind == 0);  // a sphere
  CHECK(g.lights[0].index == 4);
  CHECK(g.spheres[0].center_radius.w == 1000.0f);
  const std::string o = build_options(g.features);
  CHECK(has(o, "-DHAS_SPHERES"));
  CHECK(has(o, "-DHAS_CHECKER"));
  CHECK(has(o, "-DHAS_EMITTERS"));
  CHECK(has(o, "-DNEE"));
  CHECK(has(o, "-DMAX_DEPTH=8"));
  for (const char* absent : {"-DHAS_QUADS", "-DHAS_PLANES", "-DHAS_TRIANGLES", "-DHAS_METAL",
                             "-DHAS_DIELECTRIC", "-DHAS_THIN_LENS", "-DWEAK_SEED"})
    CHECK_FALSE(has(o, absent));
  const std::string all = build_options(g.features, true);  // every feature, same algorithm
  for (const char* present : {"-DHAS_QUADS", "-DHAS_PLANES", "-DHAS_TRIANGLES", "-DHAS_METAL",
                              "-DHAS_DIELECTRIC", "-DHAS_THIN_LENS", "-DNEE"})
    CHECK(has(all, present));
}

TEST_CASE("the Cornell box with glass: quads, a quad light, a dielectric; NEE can be off") {
  const scene sc = cornell_box<double>(cornell_variant::glass);
  const gpu_scene g = pack_scene(sc, 32, 32, 5, false);
  CHECK(g.quads.size() == 12);  // five walls, the light, six box faces
  CHECK(g.spheres.size() == 1);
  REQUIRE(g.lights.size() == 1);
  CHECK(g.lights[0].kind == 1);
  const gpu_quad& light = g.quads[std::size_t(g.lights[0].index)];
  CHECK(light.normal_area.w == doctest::Approx(0.2).epsilon(1e-6));  // 0.5 x 0.4, float
  CHECK(light.normal_area.y == -1.0f);                                // facing down
  CHECK(g.materials[std::size_t(light.material)].kind == gpu_emitter);
  const std::string o = build_options(g.features);
  CHECK(has(o, "-DHAS_DIELECTRIC"));
  CHECK_FALSE(has(o, "-DHAS_METAL"));
  CHECK_FALSE(has(o, "-DNEE"));
  CHECK(has(o, "-DMAX_DEPTH=5"));
  CHECK(g.materials[std::size_t(g.spheres[0].material)].ior == 1.5f);
}

TEST_CASE("triangles: the triangle BVH's nodes byte for byte, materials by input index") {
  scene sc;
  const int a = sc.add_material(material::lambertian(rgb(0.5f)));
  const int b = sc.add_material(material::mirror());
  sc.add(triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, a);
  mesh m;
  for (int i = 0; i < 20; ++i) {  // a strip of 20 triangles, enough for inner nodes
    const auto base = std::uint32_t(m.positions.size());
    m.positions.push_back({double(i), 0, -1});
    m.positions.push_back({double(i) + 1, 0, -1});
    m.positions.push_back({double(i), 1, -1});
    m.triangles.push_back({base, base + 1, base + 2});
  }
  sc.add(m, b);
  const gpu_scene g = pack_scene(sc, 16, 16, 8);
  REQUIRE(g.triangles.size() == 21);
  CHECK(g.features.triangles);
  CHECK(g.features.metal);
  // The same build on the same float triangles gives the same tree: compare the bytes.
  std::vector<triangle_t<float>> tris{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  for (std::size_t i = 0; i < m.triangle_count(); ++i) {
    const auto t = m.triangle(i);
    tris.push_back({vec3_t<float>(t.a), vec3_t<float>(t.b), vec3_t<float>(t.c)});
  }
  const triangle_bvh bvh(tris);
  REQUIRE(g.nodes.size() == bvh.nodes().size());
  CHECK(std::memcmp(g.nodes.data(), bvh.nodes().data(), g.nodes.size() * sizeof(gpu_node4)) == 0);
  for (const gpu_triangle& t : g.triangles) {
    CHECK(t.material == (t.id == 0 ? a : b));  // input 0 is the lone triangle
    CHECK(t.a.x == tris[t.id].a.x);
    CHECK(t.b.x == tris[t.id].b.x);
    CHECK(t.c.z == tris[t.id].c.z);
  }
}

TEST_CASE_TEMPLATE("a float scene packs like a double one", T, float, double) {
  const gpu_scene g = pack_scene(cornell_box<T>(cornell_variant::spheres), 32, 32, 8);
  const gpu_scene d = pack_scene(cornell_box<double>(cornell_variant::spheres), 32, 32, 8);
  REQUIRE(g.quads.size() == d.quads.size());
  REQUIRE(g.spheres.size() == 2);
  // float vs double rounding of the same decimal inputs: within one float ulp (relative 2^-23)
  CHECK(g.spheres[1].center_radius.w == doctest::Approx(d.spheres[1].center_radius.w).epsilon(1.2e-7));
  CHECK(g.quads[5].normal_area.w == doctest::Approx(d.quads[5].normal_area.w).epsilon(1e-6));
  CHECK(g.camera.corner.x == doctest::Approx(d.camera.corner.x).epsilon(2e-6));  // tan and a few products in float
  CHECK(build_options(g.features) == build_options(d.features));
  CHECK(build_options(g.features).find("-DHAS_METAL") != std::string::npos);
}

TEST_CASE("the camera is prepared for the image's aspect ratio, in float") {
  scene sc = spheres_scene();
  const gpu_scene g = pack_scene(sc, 200, 100, 8);
  camera c = sc.camera;
  c.aspect = 2.0;
  const auto p = c.prepare();
  CHECK(g.camera.origin.z == float(p.origin.z));
  CHECK(g.camera.horizontal.x == float(p.horizontal.x));
  CHECK(g.camera.vertical.y == float(p.vertical.y));
  CHECK(g.camera.lens_radius == 0.0f);
  CHECK_FALSE(g.features.thin_lens);
  sc.camera.aperture = 0.1;
  CHECK(pack_scene(sc, 200, 100, 8).features.thin_lens);
}

TEST_CASE("what the kernel does differently is noted: phong, point lights, vertex normals") {
  scene sc;
  const int p = sc.add_material(material::phong(rgb(0.6f, 0.2f, 0.1f), rgb(0.3f), 40));
  sc.add(sphere{{0, 0, -3}, 1}, p);
  sc.add(point_light_t<double>{{0, 5, 0}, rgb(10)});
  const gpu_scene g = pack_scene(sc, 8, 8, 8);
  REQUIRE(g.notes.size() == 3);
  CHECK(g.notes[0].find("phong") != std::string::npos);
  CHECK(g.notes[1].find("point light") != std::string::npos);
  CHECK(g.notes[2].find("the image is black") != std::string::npos);
  CHECK(g.materials[0].kind == gpu_lambertian);
  CHECK(g.materials[0].albedo_a.x == 0.6f);  // kd
}

TEST_CASE("extreme case: an empty scene packs to empty arrays and the bare options") {
  scene sc;
  sc.background = rgb(0.25f);
  const gpu_scene g = pack_scene(sc, 1, 1, 0);
  CHECK(g.spheres.empty());
  CHECK(g.materials.empty());
  CHECK(g.lights.empty());
  CHECK(g.background.x == 0.25f);
  CHECK(build_options(g.features) == "-cl-std=CL1.2 -DNEE -DMAX_DEPTH=0");
  CHECK_THROWS_AS(pack_scene(sc, 0, 10, 8), error);
}

TEST_CASE("reference_sample draws the pixel jitter first, then the lens, as the kernel does") {
  scene sc;  // nothing to hit: the sample is the background, and only the camera draws numbers
  sc.background = rgb(0.5f, 0.25f, 1.0f);
  camera c = sc.camera;
  const auto pinhole = c.prepare();
  rng g(1, 0, 0);
  std::uint64_t rays = 0;
  const light_set lights(sc);
  const rgb v = reference_sample(sc, lights, pinhole, 0, 0, 4, 4, g, {}, rays);
  CHECK(v == sc.background);
  CHECK(g.dimension() == 4);  // two uniform() draws of two words each
  c.aperture = 0.5;
  rng h(1, 0, 0);
  reference_sample(sc, lights, c.prepare(), 0, 0, 4, 4, h, {}, rays);
  CHECK(h.dimension() == 8);  // and two more for the point on the lens
}

// gpu_scene.hpp: a scene packed into the flat arrays the real-time kernel reads, the features it
// uses and the -D switches made from them, and the CPU twin of one kernel sample. No OpenCL
// here (tests/test_realtime.cpp runs the kernel).
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/gpu/realtime.hpp>
#include <zraka/media/medium.hpp>
#include <zraka/scene/cornell.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <limits>

using namespace zraka;

namespace {
bool has(const std::string& options, const std::string& word) {
  return (options + " ").find(" " + word + " ") != std::string::npos;
}
path_options depth(int d, integrator method = integrator::mis) {
  path_options o;
  o.max_depth = d;
  o.method = method;
  return o;
}
}  // namespace

TEST_CASE("diffuse spheres: only the sphere, checker, emitter and sphere-light switches") {
  const gpu_scene g = pack_scene(spheres_scene(), 64, 32, depth(8));
  CHECK(g.spheres.size() == 5);
  CHECK(g.quads.empty());
  CHECK(g.triangles.empty());
  CHECK(g.nodes.empty());
  REQUIRE(g.lights.size() == 1);
  CHECK(g.lights[0].kind == gpu_light_sphere);
  CHECK(g.lights[0].object == 4);
  CHECK(g.lights[0].pdf == 1.0f);
  CHECK(g.lights[0].cdf == 1.0f);
  CHECK(g.spheres[4].light == 0);  // the lamp knows its light, for MIS
  CHECK(g.spheres[0].light == -1);
  CHECK(g.spheres[0].center_radius.w == 1000.0f);
  const std::string o = build_options(g.features);
  CHECK(o == "-cl-std=CL1.2 -DHAS_SPHERES -DHAS_CHECKER -DHAS_EMITTERS -DHAS_SPHERE_LIGHTS -DMETHOD_MIS "
             "-DMAX_DEPTH=8 -DRR_DEPTH=3 -DPATH_LANES=8");  // the eight-lane loop covers all of it
  const std::string all = build_options(g.features, true);  // every feature, same algorithm
  for (const char* present : {"-DHAS_QUADS", "-DHAS_PLANES", "-DHAS_TRIANGLES", "-DHAS_METAL", "-DHAS_DIELECTRIC",
                              "-DHAS_PHONG", "-DHAS_QUAD_LIGHTS", "-DHAS_TRIANGLE_LIGHTS", "-DHAS_POINT_LIGHTS",
                              "-DHAS_THIN_LENS", "-DMETHOD_MIS"})
    CHECK(has(all, present));
  CHECK(!has(all, "-DPATH_LANES"));  // every feature: the one-path loop
  CHECK_FALSE(has(all, "-DMETHOD_NEE"));
}

TEST_CASE("a checker in uv: the material says 2 (world: 1), and only then HAS_UV_CHECKER") {
  scene sc;
  const int uv = sc.add_material(material::lambertian(texture::checker_uv(rgb(1), rgb(0), 0.25)));
  const int world = sc.add_material(material::lambertian(texture::checker(rgb(1), rgb(0), 0.25)));
  sc.add(sphere{{0, 0, -3}, 1}, uv);
  sc.add(sphere{{2, 0, -3}, 1}, world);
  const gpu_scene g = pack_scene(sc, 16, 16, depth(4));
  CHECK(g.materials[std::size_t(uv)].checker == 2);
  CHECK(g.materials[std::size_t(world)].checker == 1);
  CHECK(has(build_options(g.features), "-DHAS_UV_CHECKER"));
  CHECK_FALSE(has(build_options(pack_scene(spheres_scene(), 16, 16, depth(4)).features), "-DHAS_UV_CHECKER"));
  // As a roughness map it is a texture record of its own kind.
  material rough = material::rough_conductor(0.2, *find_metal("gold"));
  rough.get<material_kinds::rough_conductor>()->roughness.map = texture::checker_uv(rgb(0.1f), rgb(0.5f), 0.5);
  sc.add(sphere{{-2, 0, -3}, 1}, sc.add_material(rough));
  const gpu_scene r = pack_scene(sc, 16, 16, depth(4));
  REQUIRE(r.textures.size() == 1);
  CHECK(r.textures[0].kind == gpu_tex_checker_uv);
}

TEST_CASE("the Cornell box with glass: quads, a quad light, a dielectric; the method is a switch") {
  const scene sc = cornell_box<double>(cornell_variant::glass);
  const gpu_scene g = pack_scene(sc, 32, 32, depth(5, integrator::naive));
  CHECK(g.quads.size() == 12);  // five walls, the light, six box faces
  CHECK(g.spheres.size() == 1);
  REQUIRE(g.lights.size() == 1);
  CHECK(g.lights[0].kind == gpu_light_quad);
  const gpu_quad& light = g.quads[std::size_t(g.lights[0].object)];
  CHECK(light.light == 0);
  CHECK(g.lights[0].area == doctest::Approx(0.2).epsilon(1e-6));
  CHECK(light.normal_area.w == doctest::Approx(0.2).epsilon(1e-6));  // 0.5 x 0.4, float
  CHECK(light.normal_area.y == -1.0f);                                // facing down
  CHECK(g.materials[std::size_t(light.material)].kind == gpu_emitter);
  const std::string o = build_options(g.features);
  CHECK(has(o, "-DHAS_DIELECTRIC"));
  CHECK_FALSE(has(o, "-DHAS_METAL"));
  CHECK(has(o, "-DMETHOD_NAIVE"));
  CHECK(has(o, "-DHAS_QUAD_LIGHTS"));
  CHECK(has(o, "-DMAX_DEPTH=5"));
  CHECK(has(build_options(pack_scene(sc, 32, 32, depth(5, integrator::nee)).features), "-DMETHOD_NEE"));
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
  const gpu_scene g = pack_scene(sc, 16, 16, depth(8));
  // The BVH's positions: 21 triangles and the empty lanes of its blocks of four.
  REQUIRE(g.triangles.size() >= 21);
  CHECK(std::count_if(g.triangles.begin(), g.triangles.end(), [](const gpu_triangle& t) { return t.id != UINT32_MAX; }) == 21);
  CHECK(g.features.triangles);
  CHECK(g.features.metal);
  // The same build on the same float triangles gives the same tree: compare the bytes.
  std::vector<triangle_t<float>> tris{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  for (std::size_t i = 0; i < m.triangle_count(); ++i) {
    const auto t = m.triangle(i);
    tris.push_back({vec3_t<float>(t.a), vec3_t<float>(t.b), vec3_t<float>(t.c)});
  }
  const triangle_bvh4 bvh(tris);
  REQUIRE(g.nodes.size() == bvh.nodes().size());
  CHECK(std::memcmp(g.nodes.data(), bvh.nodes().data(), g.nodes.size() * sizeof(gpu_node4)) == 0);
  CHECK(g.triangles.size() == bvh.positions());
  for (const gpu_triangle& t : g.triangles) {
    if (t.id == UINT32_MAX) {  // an empty lane: never read by the kernel, finite zeros
      CHECK(t.a.x == 0.0f);
      CHECK(t.light == -1);
      continue;
    }
    CHECK(t.material == (t.id == 0 ? a : b));  // input 0 is the lone triangle
    CHECK(t.light == -1);                        // nothing glows
    CHECK(t.a.x == tris[t.id].a.x);
    CHECK(t.b.x == tris[t.id].b.x);
    CHECK(t.c.z == tris[t.id].c.z);
  }
}

TEST_CASE_TEMPLATE("a float scene packs like a double one", T, float, double) {
  const gpu_scene g = pack_scene(cornell_box<T>(cornell_variant::spheres), 32, 32, depth(8));
  const gpu_scene d = pack_scene(cornell_box<double>(cornell_variant::spheres), 32, 32, depth(8));
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
  const gpu_scene g = pack_scene(sc, 200, 100, depth(8));
  camera c = sc.camera;
  c.aspect = 2.0;
  const auto p = c.prepare();
  CHECK(g.camera.origin.z == float(p.origin.z));
  CHECK(g.camera.horizontal.x == float(p.horizontal.x));
  CHECK(g.camera.vertical.y == float(p.vertical.y));
  CHECK(g.camera.lens_radius == 0.0f);
  CHECK_FALSE(g.features.thin_lens);
  sc.camera.aperture = 0.1;
  CHECK(pack_scene(sc, 200, 100, depth(8)).features.thin_lens);
}

TEST_CASE("phong and point lights are packed, not noted: kd, ks, shininess; intensity and position") {
  scene sc;
  const int p = sc.add_material(material::phong(rgb(0.6f, 0.2f, 0.1f), rgb(0.3f), 40));
  sc.add(sphere{{0, 0, -3}, 1}, p);
  sc.add(point_light_t<double>{{0, 5, 0}, rgb(10)});
  const gpu_scene g = pack_scene(sc, 8, 8, depth(8));
  CHECK(g.materials[0].kind == gpu_phong);
  CHECK(g.materials[0].albedo_a.x == 0.6f);  // kd
  CHECK(g.materials[0].albedo_b.x == 0.3f);  // ks
  CHECK(g.materials[0].shininess == 40.0f);
  REQUIRE(g.lights.size() == 1);
  CHECK(g.lights[0].kind == gpu_light_point);
  CHECK(g.lights[0].position.y == 5.0f);
  CHECK(g.lights[0].intensity.x == 10.0f);
  const std::string o = build_options(g.features);
  CHECK(has(o, "-DHAS_PHONG"));
  CHECK(has(o, "-DHAS_POINT_LIGHTS"));
  CHECK_FALSE(has(o, "-DHAS_EMITTERS"));
  // path.hpp's rule, and the same words: naive cannot find a point light.
  CHECK_THROWS_WITH_AS(pack_scene(sc, 8, 8, depth(8, integrator::naive)), doctest::Contains("point light"), error);
}

TEST_CASE("the light table is light_set_t's: power CDF, mesh area CDF, the light of every triangle") {
  scene sc;
  const int white = sc.add_material(material::lambertian(rgb(0.5f)));
  const int dim = sc.add_material(material::emitter(rgb(1.0f)));
  const int bright = sc.add_material(material::emitter(rgb(3.0f), true));
  sc.add(quad{{-1, 0, -1}, {2, 0, 0}, {0, 0, 2}}, white);
  sc.add(triangle{{0, 2, 0}, {0.5, 2, 0}, {0, 2, 0.5}}, dim);
  mesh m;  // two triangles of areas 0.5 and 2
  m.positions = {{0, 3, 0}, {1, 3, 0}, {0, 3, 1}, {2, 3, 0}, {0, 3, 2}};
  m.triangles = {{0, 1, 2}, {1, 3, 4}};
  sc.add(m, bright);
  sc.add(point_light_t<double>{{0, 5, 0}, rgb(2)});
  const light_set lights(sc);
  const gpu_scene g = pack_scene(sc, 8, 8, depth(4));
  REQUIRE(g.lights.size() == lights.size());
  double cdf = 0;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    CHECK(g.lights[i].pdf == float(lights.selection_pdf(int(i))));
    CHECK(g.lights[i].cdf == float(cdf += lights.selection_pdf(int(i))));
  }
  const int tri = lights.index_of({shape_kind::triangle, 0}), mesh_light = lights.index_of({shape_kind::mesh, 0});
  REQUIRE(tri >= 0);
  REQUIRE(mesh_light >= 0);
  const gpu_light& lt = g.lights[std::size_t(tri)];
  CHECK(lt.kind == gpu_light_triangles);
  CHECK(lt.count == 1);
  CHECK(g.light_triangles[std::size_t(lt.first)].b.w == doctest::Approx(0.125));
  const gpu_light& lm = g.lights[std::size_t(mesh_light)];
  CHECK(lm.count == 2);
  CHECK(lm.area == doctest::Approx(0.5 + m.triangle(1).area()));
  CHECK(g.light_triangles[std::size_t(lm.first)].a.w == 0.0f);
  CHECK(g.light_triangles[std::size_t(lm.first) + 1].b.w == doctest::Approx(double(lm.area)));
  for (const gpu_triangle& t : g.triangles)
    CHECK(t.light == (t.id == UINT32_MAX ? -1 : t.id == 0 ? tri : mesh_light));  // -1: an empty lane
  CHECK(g.quads[0].light == -1);
  const std::string o = build_options(g.features);
  CHECK(has(o, "-DHAS_TRIANGLE_LIGHTS"));
  CHECK(has(o, "-DHAS_POINT_LIGHTS"));
  CHECK_FALSE(has(o, "-DHAS_QUAD_LIGHTS"));
}

TEST_CASE("what the kernel cannot run is an error naming it: user shapes, custom BSDFs, float overflow") {
  struct disk final : user_shape_t<double> {
    std::string name() const override { return "my_disk"; }
    aabb_t<double> bounds() const override { return {vec3(-1), vec3(1)}; }
    bool intersect(const ray&, double, double, hit&) const override { return false; }
  };
  scene a;
  a.add(std::make_shared<const disk>(), a.add_material(material::lambertian(rgb(0.5f))));
  CHECK_THROWS_WITH_AS(pack_scene(a, 8, 8, depth(4)), doctest::Contains("user shape ('my_disk')"), error);
  scene far;
  far.add(sphere{{1e300, 0, 0}, 1}, far.add_material(material::lambertian(rgb(0.5f))));
  CHECK_THROWS_WITH_AS(pack_scene(far, 8, 8, depth(4)), doctest::Contains("sphere 0 does not fit in float"), error);
  scene speck;  // a quad of 1e-30 edges: fine in double; in float u x v underflows to 0 and n/|n|^2 is NaN
  speck.add(quad{{0, 0, -3}, {1e-30, 0, 0}, {0, 1e-30, 0}}, speck.add_material(material::lambertian(rgb(0.5f))));
  CHECK_THROWS_WITH_AS(pack_scene(speck, 8, 8, depth(4)), doctest::Contains("quad 0 does not fit in float"), error);
  scene fog;
  fog.add(sphere{{0, 0, -3}, 1}, fog.add_material(material::lambertian(rgb(0.5f))));
  medium m;
  m.name = "fog";
  m.sigma_s = rgb(0.1f);
  fog.global_medium = fog.add_medium(m);
  CHECK_THROWS_WITH_AS(pack_scene(fog, 8, 8, depth(4)), doctest::Contains("participating media ('fog')"), error);
  scene hot;  // an image texel beyond float (an HDR file may hold one): refused, not rendered as inf
  auto img = std::make_shared<image>(2, 2, rgb(0.5f));
  img->at(1, 0) = rgb(std::numeric_limits<float>::infinity(), 0, 0);
  hot.add(sphere{{0, 0, -3}, 1}, hot.add_material(material::lambertian(texture::image_map(img, true, "hot.hdr"))));
  CHECK_THROWS_WITH_AS(pack_scene(hot, 8, 8, depth(4)), doctest::Contains("a texel of a texture"), error);
}

// ---------------------------------------------------------------- the appearance of chapter 5
TEST_CASE("rough materials: the kind, the alpha, the Fresnel preset or F0, and their switches") {
  scene sc;
  const int gold = sc.add_material(material::rough_conductor(0.2, *find_metal("gold")));
  const int f0 = sc.add_material(material::rough_conductor(0.4, conductor_fresnel::from_f0(rgb(0.9f, 0.6f, 0.3f))));
  const int glass = sc.add_material(material::rough_dielectric(0.1, 1.5));
  sc.add(sphere{{-1, 0, -3}, 0.5}, gold);
  sc.add(sphere{{0, 0, -3}, 0.5}, f0);
  sc.add(sphere{{1, 0, -3}, 0.5}, glass);
  const gpu_scene g = pack_scene(sc, 8, 8, depth(4));
  const gpu_material& a = g.materials[std::size_t(gold)];
  CHECK(a.kind == gpu_rough_conductor);
  CHECK(a.roughness == 0.2f);
  CHECK(a.schlick == 0);
  CHECK(a.eta.x == find_metal("gold")->eta.x);
  CHECK(a.k.z == find_metal("gold")->k.z);
  CHECK(a.roughness_texture == -1);
  CHECK(g.materials[std::size_t(f0)].schlick == 1);
  CHECK(g.materials[std::size_t(f0)].eta.y == 0.6f);  // F0 travels in eta
  CHECK(g.materials[std::size_t(glass)].kind == gpu_rough_dielectric);
  CHECK(g.materials[std::size_t(glass)].ior == 1.5f);
  const std::string o = build_options(g.features);
  CHECK(has(o, "-DHAS_ROUGH_CONDUCTOR"));
  CHECK(has(o, "-DHAS_ROUGH_DIELECTRIC"));
  CHECK_FALSE(has(o, "-DHAS_TEXTURES"));
  CHECK_FALSE(has(o, "-DHAS_ENVIRONMENT"));
}

TEST_CASE("image and noise textures: texels as linear floats, a record per texture, triangle uvs") {
  scene sc;
  auto img = std::make_shared<image>(3, 2);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) img->at(x, y) = rgb(0.1f * float(x), 0.5f * float(y), 0.25f);
  const int grid = sc.add_material(material::lambertian(texture::image_map(img, false, "grid.png")));
  material rough = material::rough_conductor(0.3, *find_metal("silver"));
  rough.get<material_kinds::rough_conductor>()->roughness.map = texture::noise(rgb(0.05f), rgb(0.4f), 3.0, 3, false);
  const int metal = sc.add_material(rough);
  sc.add(quad{{-1, -1, -3}, {2, 0, 0}, {0, 2, 0}}, grid);
  mesh m;  // one triangle with texture coordinates
  m.positions = {{0, 0, -2}, {1, 0, -2}, {0, 1, -2}};
  m.texcoords = {{0.25, 0.5}, {0.75, 0.5}, {0.25, 1.0}};
  m.triangles = {{0, 1, 2}};
  sc.add(m, grid);
  sc.add(sphere{{0, 0, -5}, 1}, metal);
  const gpu_scene g = pack_scene(sc, 8, 8, depth(4));
  REQUIRE(g.textures.size() == 2);
  const gpu_texture& t = g.textures[std::size_t(g.materials[std::size_t(grid)].albedo_texture)];
  CHECK(t.kind == gpu_tex_image);
  CHECK(t.width == 3);
  CHECK(t.height == 2);
  CHECK(t.repeat == 0);
  REQUIRE(g.texels.size() == 6);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 3; ++x) {
      const gpu_float4& v = g.texels[std::size_t(t.first + y * 3 + x)];
      CHECK(v.x == img->at(x, y).x);
      CHECK(v.y == img->at(x, y).y);
    }
  const gpu_texture& n = g.textures[std::size_t(g.materials[std::size_t(metal)].roughness_texture)];
  CHECK(n.kind == gpu_tex_noise);
  CHECK(n.octaves == 3);
  CHECK(n.frequency == 3.0f);
  REQUIRE(g.noise_permutation.size() == 512);
  for (std::size_t i = 0; i < 512; ++i) CHECK(g.noise_permutation[i] == int(detail::noise_permutation()[i]));
  // Two per BVH position: the mesh's one triangle, its vertices' (u, v), first in its block.
  REQUIRE(g.triangle_uvs.size() == 2 * g.triangles.size());
  REQUIRE(g.triangles[0].id == 0);
  CHECK(g.triangle_uvs[0].x == 0.25f);
  CHECK(g.triangle_uvs[0].z == 0.75f);
  CHECK(g.triangle_uvs[1].y == 1.0f);
  const std::string o = build_options(g.features);
  for (const char* f : {"-DHAS_TEXTURES", "-DHAS_IMAGE_TEXTURES", "-DHAS_NOISE_TEXTURES", "-DHAS_ROUGH_CONDUCTOR"})
    CHECK(has(o, f));
  CHECK_FALSE(has(o, "-DHAS_ROUGH_DIELECTRIC"));
  // A texture only an unused material has is packed, but switches nothing on.
  scene plain;
  plain.add_material(material::lambertian(texture::image_map(img, true)));
  plain.add(sphere{{0, 0, -3}, 1}, plain.add_material(material::lambertian(rgb(0.5f))));
  CHECK_FALSE(has(build_options(pack_scene(plain, 4, 4, depth(2)).features), "-DHAS_TEXTURES"));
}

TEST_CASE("the environment: its texels and distribution_2d's tables as they are, and its light") {
  scene sc;
  sc.add(sphere{{0, 0, -3}, 1}, sc.add_material(material::lambertian(rgb(0.5f))));
  image sky(4, 3);
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) sky.at(x, y) = rgb(float(1 + x + 4 * y));
  sc.environment = std::make_shared<environment_map>(environment_map::from_image(sky, "sky.hdr", 0.5f, 30));
  const gpu_scene g = pack_scene(sc, 8, 8, depth(4));
  const environment_map& e = *sc.environment;
  const gpu_environment& ge = g.environment;
  CHECK(ge.present == 1);
  CHECK(ge.is_constant == 0);
  CHECK(ge.width == 4);
  CHECK(ge.height == 3);
  CHECK(ge.cos_rotation == float(e.cos_rotation()));
  CHECK(ge.sin_rotation == float(e.sin_rotation()));
  REQUIRE(g.texels.size() == 12);
  CHECK(g.texels[std::size_t(ge.first + 5)].x == e.map().at(1, 1).x);  // scaled by 0.5
  CHECK(g.texels[std::size_t(ge.first + 5)].x == 3.0f);
  // marginal bins [H], its CDF [H + 1], row totals [H], rows' bins [H][W], rows' CDFs [H][W + 1]
  const std::size_t W = 4, H = 3;
  REQUIRE(g.env_tables.size() == H + (H + 1) + H + H * W + H * (W + 1));
  const distribution_2d& d = e.distribution();
  CHECK(ge.marginal_total == float(d.marginal().total()));
  for (std::size_t v = 0; v < H; ++v) {
    CHECK(g.env_tables[v] == float(d.marginal().bins()[v]));
    CHECK(g.env_tables[H + v + 1] == float(d.marginal().cdf()[v + 1]));
    CHECK(g.env_tables[2 * H + 1 + v] == float(d.row(v).total()));
    for (std::size_t u = 0; u < W; ++u) {
      CHECK(g.env_tables[3 * H + 1 + v * W + u] == float(d.row(v).bins()[u]));
      CHECK(g.env_tables[3 * H + 1 + H * W + v * (W + 1) + u + 1] == float(d.row(v).cdf()[u + 1]));
    }
  }
  REQUIRE(g.lights.size() == 1);  // the environment is the only light
  CHECK(g.lights[0].kind == gpu_light_environment);
  CHECK(ge.light == 0);
  CHECK(g.lights[0].pdf == 1.0f);
  CHECK(has(build_options(g.features), "-DHAS_ENVIRONMENT"));
  // A constant sky: its colour, sampled uniformly; a black one is seen but not a light.
  sc.environment = std::make_shared<environment_map>(environment_map::constant(rgb(0.25f)));
  const gpu_scene c = pack_scene(sc, 8, 8, depth(4));
  CHECK(c.environment.is_constant == 1);
  CHECK(c.environment.radiance.y == 0.25f);
  CHECK(c.env_tables.empty());
  sc.environment = std::make_shared<environment_map>(environment_map::constant(rgb(0)));
  const gpu_scene dark = pack_scene(sc, 8, 8, depth(4));
  CHECK(dark.environment.present == 1);
  CHECK(dark.environment.light == -1);
  CHECK(dark.lights.empty());
}

TEST_CASE("extreme case: an empty scene packs to empty arrays and the bare options") {
  scene sc;
  sc.background = rgb(0.25f);
  const gpu_scene g = pack_scene(sc, 1, 1, depth(0));
  CHECK(g.spheres.empty());
  CHECK(g.materials.empty());
  CHECK(g.lights.empty());
  CHECK(g.background.x == 0.25f);
  // Nothing the eight-lane loop lacks: it is chosen (and sees only the background).
  CHECK(build_options(g.features) == "-cl-std=CL1.2 -DMETHOD_MIS -DMAX_DEPTH=0 -DRR_DEPTH=3 -DPATH_LANES=8");
  CHECK_THROWS_AS(pack_scene(sc, 0, 10, depth(8)), error);
  CHECK_THROWS_WITH_AS(pack_scene(sc, 1, 1, depth(-1)), doctest::Contains("depth"), error);
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

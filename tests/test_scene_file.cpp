// links: yaml-cpp
// Scene files: every malformed scene in tests/scenes/bad gives its expected error (file, line,
// column, field); defaults; every key honoured; transforms; mirrored meshes; files found
// relative to the scene, then the resource root; the object BVH and mesh BVHs give the same
// nearest hit as testing everything; rays spawned from a mesh hit never hit it again.
#include <zraka/io/scene_file.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

#include "expected_errors.hpp"

#include <algorithm>
#include <functional>
#include <fstream>

using namespace zraka;
namespace fs = std::filesystem;
using zraka_test::error_of;

namespace {

fs::path temp_dir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("zraka_test_scene_file_" + name);
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
void write(const fs::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
}

}  // namespace

TEST_CASE("scene file: each malformed scene gives the error its first line expects") {
  zraka_test::check_expected_errors(resource_root() / "tests" / "scenes" / "bad", ".yaml", "# expect: ", "", 30, false,
                                    [](const fs::path& f) { (void)load_scene_file(f); });
}

TEST_CASE("scene file: a scene of one sphere has every default of the structs") {
  const loaded_scene ls = parse_scene("objects: [{type: sphere}]", "mini.yaml");
  const scene& sc = ls.sc;
  const render_settings rs;
  CHECK(sc.settings.width == rs.width);
  CHECK(sc.settings.height == rs.height);
  CHECK(sc.settings.spp == rs.spp);
  CHECK(sc.settings.max_depth == rs.max_depth);
  CHECK(sc.settings.seed == rs.seed);
  CHECK(sc.background == rgb(0));
  CHECK(sc.ambient == rgb(0));
  const camera cam;
  CHECK(sc.camera.position == cam.position);
  CHECK(sc.camera.look_at == cam.look_at);
  CHECK(sc.camera.up == cam.up);
  CHECK(sc.camera.vfov_degrees == cam.vfov_degrees);
  REQUIRE(sc.materials.size() == 1);  // "default"
  CHECK(sc.materials[0].is<material_kinds::lambertian>());
  CHECK(sc.materials[0].get<material_kinds::lambertian>()->albedo.a == material_kinds::lambertian{}.albedo.a);
  REQUIRE(sc.spheres.size() == 1);
  CHECK(sc.spheres[0].shape.center == vec3(0));
  CHECK(sc.spheres[0].shape.radius == scene_file_defaults::sphere_radius);
  CHECK(sc.spheres[0].material == 0);
  CHECK(sc.material_names == std::vector<std::string>{"default"});
  CHECK_FALSE(sc.has_object_bvh());
  // The printed scene reads back as the same scene.
  CHECK(parse_scene(ls.resolved, "again.yaml").resolved == ls.resolved);
}

TEST_CASE("scene file: every key is honoured") {
  const fs::path dir = temp_dir("keys");
  write(dir / "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  const std::string text = R"(
settings: {width: 64, height: 32, spp: 3, max_depth: 5, seed: 42, background: [0.1, 0.2, 0.3], ambient: 0.05}
camera: {position: [1, 2, 3], look_at: [0, 1, 0], up: [0, 0, 1], vfov: 55, aperture: 0.1, focus_distance: 2.5}
materials:
  lam: {type: lambertian, albedo: {checker: {even: [1, 0, 0], odd: 0.5, scale: 0.25}}}
  met: {type: metal, albedo: [0.9, 0.8, 0.7], fuzz: 0.3}
  gla: {type: dielectric, ior: 1.7}
  emi: {type: emitter, radiance: [5, 6, 7]}
  pho: {type: phong, kd: [0.1, 0.2, 0.3], ks: 0.4, shininess: 12}
lights:
  - {type: point, position: [0, 9, 0], intensity: [1, 2, 3]}
  - {type: quad, corner: [0, 5, 0], u: [0, 0, 1], v: [1, 0, 0], radiance: 8}
  - {type: sphere, center: [4, 4, 4], radius: 0.5, radiance: 9}
objects:
  - {type: sphere, name: ball, center: [1, 0, 0], radius: 0.5, material: met}
  - {type: plane, point: [0, -1, 0], normal: [0, 2, 0], material: lam}
  - {type: triangle, a: [0, 0, 0], b: [1, 0, 0], c: [0, 1, 0], material: gla}
  - {type: quad, corner: [0, 0, 0], u: [1, 0, 0], v: [0, 0, -1], material: emi}
  - {type: box, min: [0, 0, 0], max: [1, 2, 3], material: pho}
  - {type: mesh, file: tri.obj}
  - {type: bezier, file: teapot.bpt, divs: 2}
)";
  const loaded_scene ls = parse_scene(text, "keys.yaml", dir);
  const scene& sc = ls.sc;
  CHECK(sc.settings.width == 64);
  CHECK(sc.settings.height == 32);
  CHECK(sc.settings.spp == 3);
  CHECK(sc.settings.max_depth == 5);
  CHECK(sc.settings.seed == 42);
  CHECK(sc.background == rgb(0.1f, 0.2f, 0.3f));
  CHECK(sc.ambient == rgb(0.05f));
  CHECK(sc.camera.position == vec3(1, 2, 3));
  CHECK(sc.camera.look_at == vec3(0, 1, 0));
  CHECK(sc.camera.up == vec3(0, 0, 1));
  CHECK(sc.camera.vfov_degrees == 55);
  CHECK(sc.camera.aperture == 0.1);
  CHECK(sc.camera.focus_distance == 2.5);
  // Materials: default, the five, and one per area light.
  REQUIRE(sc.materials.size() == 8);
  const material& lam = sc.materials[1];
  CHECK(lam.get<material_kinds::lambertian>()->albedo.type == texture::kind::checker);
  CHECK(lam.get<material_kinds::lambertian>()->albedo.a == rgb(1, 0, 0));
  CHECK(lam.get<material_kinds::lambertian>()->albedo.b == rgb(0.5f));
  CHECK(lam.get<material_kinds::lambertian>()->albedo.cell == 0.25);
  CHECK(sc.materials[2].is<material_kinds::fuzzy_metal>());
  CHECK(sc.materials[2].get<material_kinds::fuzzy_metal>()->albedo.a == rgb(0.9f, 0.8f, 0.7f));
  CHECK(sc.materials[2].get<material_kinds::fuzzy_metal>()->fuzz == 0.3);
  CHECK(sc.materials[3].get<material_kinds::dielectric>()->ior == 1.7);
  CHECK(sc.materials[4].radiance == rgb(5, 6, 7));
  CHECK(sc.materials[5].get<material_kinds::phong>()->kd == rgb(0.1f, 0.2f, 0.3f));
  CHECK(sc.materials[5].get<material_kinds::phong>()->ks == rgb(0.4f));
  CHECK(sc.materials[5].get<material_kinds::phong>()->shininess == 12);
  CHECK(sc.materials[6].radiance == rgb(8));
  CHECK(sc.materials[7].radiance == rgb(9));
  REQUIRE(sc.lights.size() == 1);
  const auto* point = sc.lights[0].get<light_kinds::point>();  // lights/point.hpp
  REQUIRE(point);
  CHECK(point->position == vec3(0, 9, 0));
  CHECK(point->intensity == rgb(1, 2, 3));
  // Area lights: the light quad, the light sphere, and the emitter quad object.
  CHECK(light_set(sc).size() == 4);  // and the point light
  REQUIRE(sc.spheres.size() == 2);
  CHECK(sc.spheres[1].shape.center == vec3(1, 0, 0));
  CHECK(sc.spheres[1].shape.radius == 0.5);
  CHECK(sc.spheres[1].material == 2);
  REQUIRE(sc.planes.size() == 1);
  CHECK(sc.planes[0].shape.normal == vec3(0, 1, 0));  // normalised
  CHECK(sc.planes[0].shape.point == vec3(0, -1, 0));
  REQUIRE(sc.triangles.size() == 1);
  CHECK(sc.triangles[0].material == 3);
  CHECK(sc.quads.size() == 1 + 1 + 6);  // light, emitter object, box
  REQUIRE(sc.meshes.size() == 2);
  CHECK(sc.meshes[0].shape.triangle_count() == 1);
  CHECK(sc.meshes[0].material == 0);
  CHECK(sc.meshes[1].shape.triangle_count() == 32 * 2 * 2 * 2);  // 32 patches, 2 divs^2 each
  CHECK(sc.has_object_bvh());  // 2 + 1 + 8 + 2 = 13 bounded objects > 8
  CHECK(describe_built(sc).find("object BVH over 13 objects") != std::string::npos);
  CHECK(ls.resolved.find("name: ball") != std::string::npos);
}

TEST_CASE("scene file: transforms scale, then rotate, then translate") {
  const loaded_scene ls = parse_scene(R"(
objects:
  - {type: sphere, center: [1, 0, 0], radius: 0.5,
     transform: {scale: 2, rotate: {axis: [0, 0, 1], degrees: 90}, translate: [10, 0, 0]}}
  - {type: quad, corner: [1, 0, 0], u: [1, 0, 0], v: [0, 1, 0], transform: {scale: [2, 3, 1], translate: [0, 0, 5]}}
  - {type: triangle, a: [0, 0, 0], b: [1, 0, 0], c: [0, 1, 0], transform: {rotate: {axis: [1, 0, 0], degrees: 90}}}
  - {type: plane, normal: [0, 1, 0], transform: {rotate: {axis: [0, 0, 1], degrees: -90}, translate: [0, 3, 0]}}
)",
                                      "t.yaml");
  const scene& sc = ls.sc;
  // (1,0,0) scaled by 2 is (2,0,0), turned 90 degrees about z is (0,2,0), moved is (10,2,0).
  // Tolerance 1e-12: cos(pi/2) is 6e-17, not 0.
  CHECK(glm::length(sc.spheres[0].shape.center - vec3(10, 2, 0)) < 1e-12);
  CHECK(sc.spheres[0].shape.radius == 1.0);
  CHECK(sc.quads[0].shape.corner == vec3(2, 0, 5));
  CHECK(sc.quads[0].shape.u == vec3(2, 0, 0));
  CHECK(sc.quads[0].shape.v == vec3(0, 3, 0));
  CHECK(glm::length(sc.triangles[0].shape.c - vec3(0, 0, 1)) < 1e-12);  // y turned into z
  CHECK(glm::length(sc.planes[0].shape.normal - vec3(1, 0, 0)) < 1e-12);  // up turned to +x
  CHECK(glm::length(sc.planes[0].shape.point - vec3(0, 3, 0)) < 1e-12);
}

TEST_CASE("scene file: a mirrored OBJ mesh keeps its faces pointing out") {
  const fs::path dir = temp_dir("obj");
  // A mirroring transform keeps the faces pointing out (the winding is turned back).
  const loaded_scene ls =
      parse_scene("objects: [{type: mesh, file: meshes/cube.obj, transform: {scale: [-1, 1, 1]}}]", "m.yaml", dir);
  const mesh& mirrored = ls.sc.meshes[0].shape;
  for (std::size_t i = 0; i < 12; ++i) {
    const triangle t = mirrored.triangle(i);
    CHECK(glm::dot(t.normal(), (t.a + t.b + t.c) / 3.0) > 0);
  }
}

TEST_CASE("scene file: files next to the scene come first, then the resource root") {
  const fs::path dir = temp_dir("paths");
  fs::create_directories(dir / "meshes");
  // A one-triangle "cube.obj" next to the scene hides the resource root's twelve-triangle one.
  write(dir / "meshes" / "cube.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write(dir / "near.yaml", "objects: [{type: mesh, file: meshes/cube.obj}]\n");
  CHECK(load_scene_file(dir / "near.yaml").sc.meshes[0].shape.triangle_count() == 1);
  fs::remove(dir / "meshes" / "cube.obj");
  CHECK(load_scene_file(dir / "near.yaml").sc.meshes[0].shape.triangle_count() == 12);  // scenes/meshes
  // Scene files themselves are found through the resource root too.
  CHECK(load_scene_file("scenes/teapot.yaml").sc.meshes.size() == 1);
}

TEST_CASE("scene file: the object BVH and the mesh BVHs find what testing everything finds") {
  std::string text = "materials: {m: {type: metal}}\nobjects:\n"
                     "  - {type: plane, point: [0, -3, 0]}\n"
                     "  - {type: bezier, file: teapot.bpt, divs: 4, transform: {scale: 0.5}}\n"
                     "  - {type: mesh, file: meshes/icosphere.obj, transform: {translate: [2, 1, 0]}}\n";
  rng g(3);
  for (int i = 0; i < 30; ++i) {
    const vec3 c = 4.0 * (vec3(g.uniform(), g.uniform(), g.uniform()) - 0.5);
    text += "  - {type: sphere, center: [" + std::to_string(c.x) + ", " + std::to_string(c.y) + ", " +
            std::to_string(c.z) + "], radius: " + std::to_string(0.1 + 0.3 * g.uniform()) + "}\n";
    text += "  - {type: quad, corner: [" + std::to_string(c.z) + ", " + std::to_string(c.x) + ", " +
            std::to_string(c.y) + "], u: [0.5, 0.1, 0], v: [0, 0.3, 0.6]}\n";
  }
  text += "  - {type: box, min: [-1, -1, -1], max: [-0.5, 0, 2]}\n";
  const loaded_scene ls = parse_scene(text, "many.yaml");
  REQUIRE(ls.sc.has_object_bvh());
  scene brute = ls.sc;
  brute.accel = {};
  REQUIRE_FALSE(brute.has_object_bvh());
  int hits = 0, shadowed = 0;
  for (int i = 0; i < 3000; ++i) {
    const vec3 o = 6.0 * sample_uniform_sphere(g.uniform2());
    const vec3 target = 2.0 * (vec3(g.uniform(), g.uniform(), g.uniform()) - 0.5);
    const ray r(o, target - o);
    scene_hit a, b;
    const bool fa = nearest_hit(ls.sc, r, a), fb = nearest_hit(brute, r, b);
    REQUIRE(fa == fb);
    if (!fa) continue;
    ++hits;
    CHECK(a.h.t == b.h.t);  // the same tests on the same objects: the same bits
    CHECK(a.object.kind == b.object.kind);
    CHECK(a.object.index == b.object.index);
    const segment_t<double> s = spawn_segment(a.h, vec3(0, 10, 0));
    const bool oa = occluded(ls.sc, s);
    CHECK(oa == occluded(brute, s));
    shadowed += oa;
  }
  CHECK(hits > 1500);
  CHECK(shadowed > 100);
}

TEST_CASE("scene file: rays spawned from a mesh hit never hit the same triangle again") {
  // The mesh BVH tests in float; the hit is rebuilt in double with p_error widened to float's
  // rounding, so spawned rays and shadow segments clear the surface (no acne). Teapot scaled to
  // 1e-2 .. 1e3 to span magnitudes.
  for (const double scale : {0.01, 1.0, 1000.0}) {
    const loaded_scene ls = parse_scene("objects: [{type: bezier, file: teapot.bpt, divs: 6, transform: {scale: " +
                                            std::to_string(scale) + ", translate: [" + std::to_string(scale) + ", 0, 0]}}]",
                                        "tp.yaml");
    const scene& sc = ls.sc;
    rng g(11);
    int tested = 0;
    for (int i = 0; i < 4000; ++i) {
      const vec3 o = 10.0 * scale * sample_uniform_sphere(g.uniform2()) + vec3(scale, 0, 0);
      const vec3 target = scale * vec3(1 + g.uniform() - 0.5, 1.5 * g.uniform(), g.uniform() - 0.5);
      scene_hit sh;
      if (!nearest_hit(sc, ray(o, target - o), sh)) continue;
      ++tested;
      // A direction leaving on the side the ray came from, in the cosine lobe around the normal.
      const vec3 n = sh.h.facing_normal();
      const vec3 w = onb(n).to_world(sample_cosine_hemisphere(g.uniform2()));
      if (!(glm::dot(w, n) > 1e-3)) continue;
      scene_hit again;
      const bool hit_again = nearest_hit(sc, spawn_ray(sh.h, w), again);
      CHECK_FALSE((hit_again && again.triangle == sh.triangle));
    }
    CHECK(tested > 1000);
  }
}

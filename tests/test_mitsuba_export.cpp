#include <zraka/mitsuba_export.hpp>

#include <doctest/doctest.h>

#include <cstdlib>
#include <string>

using namespace zraka;

namespace {

std::size_t count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

// The number after `key` (e.g. "\"radius\": "), read back as a double.
double number_after(const std::string& s, const std::string& key) {
  const std::size_t p = s.find(key);
  REQUIRE(p != std::string::npos);
  return std::strtod(s.c_str() + p + key.size(), nullptr);
}

scene small_scene() {
  scene sc;
  sc.materials.push_back(material::lambertian(rgb(0.5f, 0.25f, 0.125f)));
  sc.materials.push_back(material::emitter(rgb(4.0f)));
  sc.add(sphere_t<double>{{0.1, 0.2, -3.0}, 0.1}, 0);
  sc.add(parallelogram_t<double>{{-1, 1, -4}, {2, 0, 0}, {0, 0, 2}}, 1);
  sc.add(triangle_t<double>{{0, 0, -5}, {1, 0, -5}, {0, 1, -5}}, 0);
  sc.add(point_light_t<double>{{0, 2, 0}, rgb(10.0f)});
  return sc;
}

}  // namespace

TEST_CASE("mitsuba_export: every object, material and light is written, numbers to the last bit") {
  const scene sc = small_scene();
  const std::string j = mitsuba_scene_json(sc, 64, 48, 7);
  CHECK(j.find("\"width\": 64, \"height\": 48, \"max_depth\": 7") != std::string::npos);
  CHECK(count(j, "{\"center\"") == 1);
  CHECK(count(j, "{\"corner\"") == 1);
  CHECK(count(j, "{\"a\"") == 1);
  CHECK(count(j, "\"intensity\"") == 1);  // the point light
  CHECK(count(j, "\"type\": \"lambertian\"") == 1);
  CHECK(count(j, "\"type\": \"emitter\"") == 1);
  CHECK(number_after(j, "\"radius\": ") == 0.1);  // 17 digits: the double comes back exactly
  CHECK(number_after(j, "{\"center\": [") == 0.1);
  // Balanced, so a JSON reader gets to the end.
  CHECK(count(j, "{") == count(j, "}"));
  CHECK(count(j, "[") == count(j, "]"));
}

TEST_CASE("mitsuba_export: a mesh is written as its triangles") {
  scene sc = small_scene();
  mesh_t<double> m;
  m.positions = {{0, 0, -6}, {1, 0, -6}, {1, 1, -6}, {0, 1, -6}};
  m.normals.assign(4, {0, 0, 1});
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  sc.add(std::move(m), 0);
  const std::string j = mitsuba_scene_json(sc, 8, 8, 1);
  CHECK(count(j, "{\"a\"") == 3);  // the loose one and the mesh's two
}

TEST_CASE("mitsuba_export: what the converter cannot express is refused by name") {
  scene with_plane = small_scene();
  with_plane.add(plane_t<double>::from_point_normal({0, -1, 0}, {0, 1, 0}), 0);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(with_plane, 8, 8, 1), doctest::Contains("infinite plane"), error);

  scene unknown_kind = small_scene();
  unknown_kind.materials[1].kind = static_cast<material_kind>(99);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(unknown_kind, 8, 8, 1), doctest::Contains("material 1"), error);
}

TEST_CASE("mitsuba_export: a homogeneous medium is written with the material that bounds it") {
  scene sc = small_scene();
  medium fog;
  fog.name = "fog";
  fog.sigma_a = rgb(0.25f), fog.sigma_s = rgb(0.5f, 0.5f, 0.75f), fog.g = 0.3;
  sc.materials[0].interior = sc.add_medium(fog);
  sc.global_medium = 0;
  const std::string j = mitsuba_scene_json(sc, 8, 8, 1);
  CHECK(j.find("\"global_medium\": 0") != std::string::npos);
  CHECK(count(j, "{\"name\": \"fog\"") == 1);
  CHECK(number_after(j, "\"g\": ") == 0.3);
  CHECK(count(j, "\"interior\": 0") == 1);
  CHECK(count(j, "\"interior\": -1") == 1);  // the emitter bounds no medium
}

TEST_CASE("mitsuba_export: a density grid, an environment and a rough material are refused by name") {
  scene grid = small_scene();
  medium smoke;
  smoke.name = "smoke";
  smoke.sigma_s = rgb(1.0f);
  smoke.density = std::make_shared<density_grid>(density_grid::noise(aabb{vec3(-1.0), vec3(1.0)}, 4, 2.0, 1));
  grid.add_medium(smoke);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(grid, 8, 8, 1), doctest::Contains("medium 'smoke' is a density grid"), error);

  scene sky = small_scene();
  sky.environment = std::make_shared<environment_map>(environment_map::constant(rgb(1.0f), 1.0f, 0.0));
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(sky, 8, 8, 1), doctest::Contains("environment light"), error);

  scene rough = small_scene();
  rough.materials[0].kind = material_kind::rough_conductor;
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(rough, 8, 8, 1), doctest::Contains("is a rough_conductor, which cannot be exported yet"), error);
}

TEST_CASE("mitsuba_export: image and noise textures are refused by name") {
  scene sc = small_scene();
  sc.materials[0].albedo = texture::noise(rgb(0), rgb(1), 2.0, 3, true);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(sc, 8, 8, 1), doctest::Contains("material 0 has a marble texture"), error);
}

#include <zraka/io/mitsuba_export.hpp>

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

  // A material of C++ code (a custom BSDF), which no kind's writer describes.
  struct opaque : custom_bsdf {
    vec3 eval(const bsdf_frame&, const vec3&, const vec3&) const override { return vec3(0); }
    std::optional<custom_sample> sample(const bsdf_frame&, const vec3&, const vec3&) const override { return {}; }
    double pdf(const bsdf_frame&, const vec3&, const vec3&) const override { return 0; }
  };
  scene unknown_kind = small_scene();
  unknown_kind.materials[1] = material::custom(std::make_shared<opaque>());
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

TEST_CASE("mitsuba_export: a density grid is refused by name") {
  scene grid = small_scene();
  medium smoke;
  smoke.name = "smoke";
  smoke.sigma_s = rgb(1.0f);
  smoke.density = std::make_shared<density_grid>(density_grid::noise(aabb{vec3(-1.0), vec3(1.0)}, 4, 2.0, 1));
  grid.add_medium(smoke);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(grid, 8, 8, 1), doctest::Contains("medium 'smoke' is a density grid"), error);
}

TEST_CASE("mitsuba_export: rough materials are written with alpha and the conductor's complex index") {
  scene sc = small_scene();
  sc.materials.push_back(material::rough_conductor(0.3, *find_metal("gold")));
  sc.materials.push_back(material::rough_dielectric(0.2, 1.5));
  const std::string j = mitsuba_scene_json(sc, 8, 8, 1);
  CHECK(count(j, "\"type\": \"rough_conductor\"") == 1);
  CHECK(count(j, "\"type\": \"rough_dielectric\"") == 1);
  CHECK(number_after(j, "\"alpha\": ") == 0.3);
  CHECK(number_after(j, "\"eta\": [") == double(metal_presets()[0].eta.x));  // gold's, to the last bit
  CHECK(number_after(j, "\"k\": [") == double(metal_presets()[0].k.x));
  CHECK(count(j, "\"alpha\": 0.20000000000000001") == 1);
  CHECK(count(j, "\"eta\"") == 1);  // the dielectric has an ior, no complex index
}

TEST_CASE("mitsuba_export: an RGB f0, a roughness texture, a noise texture are refused by name") {
  scene f0 = small_scene();
  f0.material_names = {"brass"};
  f0.materials[0] = material::rough_conductor(0.2, conductor_fresnel::from_f0(rgb(0.9f, 0.7f, 0.3f)));
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(f0, 8, 8, 1), doctest::Contains("material 'brass' is a rough_conductor given by an RGB f0"), error);

  scene rough_map = small_scene();
  rough_map.materials[0] = material::rough_dielectric(0.2, 1.5);
  rough_map.materials[0].get<material_kinds::rough_dielectric>()->roughness.map = texture::noise(rgb(0.1f), rgb(0.5f), 2.0, 1, false);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(rough_map, 8, 8, 1), doctest::Contains("material 0 has a roughness texture (a noise texture)"), error);

  scene marble = small_scene();
  marble.materials[0].get<material_kinds::lambertian>()->albedo = texture::noise(rgb(0), rgb(1), 2.0, 3, true);
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(marble, 8, 8, 1), doctest::Contains("material 0 has a marble texture"), error);
}

namespace {
// A 2x1 image: a red texel on the left, a blue one on the right.
std::shared_ptr<const image> two_texels() {
  auto img = std::make_shared<image>(2, 1);
  img->at(0, 0) = rgb(1.0f, 0.0f, 0.0f);
  img->at(1, 0) = rgb(0.0f, 0.0f, 0.25f);
  return img;
}
}  // namespace

TEST_CASE("mitsuba_export: an image texture on a lambertian quad is written as its linear texels") {
  scene sc = small_scene();
  sc.spheres.clear(), sc.triangles.clear();  // textures go on quads only
  sc.materials[0] = material::lambertian(texture::image_map(two_texels(), false, "a \"quoted\" name.png"));
  sc.quads[0].material = 0;
  const std::string j = mitsuba_scene_json(sc, 8, 8, 1);
  CHECK(j.find("\"texture\": {\"source\": \"a \\\"quoted\\\" name.png\", \"repeat\": false, \"width\": 2, \"height\": 1, "
               "\"texels\": [1, 0, 0, 0, 0, 0.25]}") != std::string::npos);
  CHECK(count(j, "\"texture\"") == 1);  // the emitter has none
  CHECK(count(j, "{") == count(j, "}"));
  CHECK(count(j, "[") == count(j, "]"));
}

TEST_CASE("mitsuba_export: an image texture anywhere but on a lambertian quad is refused by name") {
  scene on_sphere = small_scene();
  on_sphere.material_names = {"grid"};
  on_sphere.materials[0] = material::lambertian(texture::image_map(two_texels(), true, "uv-grid.png"));
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(on_sphere, 8, 8, 1),
                       doctest::Contains("material 'grid' has an image texture ('uv-grid.png') on a sphere"), error);
  on_sphere.spheres.clear();
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(on_sphere, 8, 8, 1), doctest::Contains("on a triangle"), error);

  scene metal = small_scene();
  metal.materials[0] = material::mirror();
  metal.materials[0].get<material_kinds::fuzzy_metal>()->albedo = texture::image_map(two_texels(), true, "uv-grid.png");
  CHECK_THROWS_WITH_AS(mitsuba_scene_json(metal, 8, 8, 1), doctest::Contains("material 0 is a metal with an image texture"), error);
}

TEST_CASE("mitsuba_export: the environment is written: a constant sky, or a map's scaled texels and its rotation") {
  scene plain = small_scene();
  CHECK(plain.background == rgb(0));
  CHECK(mitsuba_scene_json(plain, 8, 8, 1).find("\"environment\": null") != std::string::npos);

  scene sky = small_scene();
  sky.environment = std::make_shared<environment_map>(environment_map::constant(rgb(0.5f, 1.0f, 2.0f), 2.0f, 30.0));
  CHECK(mitsuba_scene_json(sky, 8, 8, 1).find("\"environment\": {\"type\": \"constant\", \"radiance\": [1, 2, 4]}") != std::string::npos);

  scene map = small_scene();
  map.environment = std::make_shared<environment_map>(environment_map::from_image(*two_texels(), "sky.hdr", 4.0f, -12.5));
  const std::string j = mitsuba_scene_json(map, 8, 8, 1);
  CHECK(j.find("\"environment\": {\"type\": \"map\", \"source\": \"sky.hdr\", \"rotate\": -12.5, "
               "\"width\": 2, \"height\": 1, \"texels\": [4, 0, 0, 0, 0, 1]}") != std::string::npos);
  CHECK(count(j, "{") == count(j, "}"));
  CHECK(count(j, "[") == count(j, "]"));

  // A texel near float's top survives with its 9 digits (no "inf" in the JSON).
  image hot(1, 1, rgb(3e38f, 1e-30f, 0.0f));
  map.environment = std::make_shared<environment_map>(environment_map::from_image(hot, "hot.pfm"));
  const std::string h = mitsuba_scene_json(map, 8, 8, 1);
  CHECK(float(number_after(h, "\"texels\": [")) == 3e38f);
  CHECK(h.find("inf") == std::string::npos);
}

TEST_CASE("mitsuba_export: a file name with control characters is escaped, so the JSON stays valid") {
  CHECK(detail::json_escape("a\\b\"c\nd") == "a\\\\b\\\"c\\u000ad");
}

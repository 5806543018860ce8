// links: yaml-cpp
// Textures: the checker's cells; the image lookup's bilinear weights, wrap modes and sRGB
// decoding; noise's range, lattice zeros, continuity and determinism; OBJ texture coordinates
// reaching a hit; textures in scene files and their errors.
#include <zraka/io/obj_file.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/scene/scene_query.hpp>
#include <zraka/textures/texture.hpp>
#include <zraka/textures/texture_file.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

using namespace zraka;

namespace {
const vec2 no_uv(0);
rgb at(const texture& t, vec3 p, vec3 n = vec3(0, 1, 0), vec2 uv = vec2(0)) { return evaluate(t, p, n, uv); }
}  // namespace

TEST_CASE("texture: the checker alternates and ignores rounding across the surface's own plane") {
  const texture t = texture::checker(rgb(1), rgb(0), 0.5);
  CHECK(at(t, vec3(0.1, 0, 0.1)) == rgb(1));
  CHECK(at(t, vec3(0.6, 0, 0.1)) == rgb(0));
  CHECK(at(t, vec3(0.6, 0, 0.6)) == rgb(1));
  CHECK(at(t, vec3(-0.1, 0, 0.1)) == rgb(0));  // floor, not truncation towards zero
  // Hit points a rounding above or below the floor plane get the same cell.
  CHECK(at(t, vec3(0.1, 1e-17, 0.1)) == at(t, vec3(0.1, -1e-17, 0.1)));
  // A wall x = 0 uses y and z.
  CHECK(at(t, vec3(-1e-17, 0.1, 0.1), vec3(1, 0, 0)) == at(t, vec3(1e-17, 0.1, 0.1), vec3(1, 0, 0)));
  CHECK(at(texture::solid(rgb(0.3f)), vec3(5, 5, 5)) == rgb(0.3f));
}

TEST_CASE("texture: a uv checker alternates in (u, v), whatever the point, and survives NaN and huge uv") {
  const texture t = texture::checker_uv(rgb(1), rgb(0), 0.5);  // Mitsuba's checkerboard
  const vec3 p(7, 3, -2), n(0, 0, 1);
  CHECK(at(t, p, n, vec2(0.1, 0.1)) == rgb(1));   // (0, 0): even
  CHECK(at(t, p, n, vec2(0.6, 0.1)) == rgb(0));   // (1, 0): odd
  CHECK(at(t, p, n, vec2(0.6, 0.7)) == rgb(1));   // (1, 1): even
  CHECK(at(t, p, n, vec2(-0.1, 0.1)) == rgb(0));  // floor: (-1, 0)
  CHECK(at(t, vec3(100), vec3(1, 0, 0), vec2(0.1, 0.6)) == rgb(0));  // the point and normal do not matter
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  CHECK(at(t, p, n, vec2(nan, 0.1)) == rgb(1));   // NaN reads as 0
  CHECK(at(t, p, n, vec2(inf, -inf)) == rgb(1));
  CHECK(at(t, p, n, vec2(1e300, 1e300)) == rgb(1));  // beyond 2^53 every cell is even: no overflow
  CHECK(at(t, p, n, vec2(1e300, 0.6)) == rgb(0));
  CHECK(describe(t) == "a uv checker texture");
}

TEST_CASE("texture: an image is bilinear between texel centres, repeats or clamps, and survives NaN and huge uv") {
  auto img = std::make_shared<image>(2, 2);
  img->at(0, 0) = rgb(1, 0, 0), img->at(1, 0) = rgb(0, 1, 0);  // top row
  img->at(0, 1) = rgb(0, 0, 1), img->at(1, 1) = rgb(1, 1, 1);  // bottom row
  const texture rep = texture::image_map(img, true), clamp = texture::image_map(img, false);
  auto near = [](rgb a, rgb b) { return glm::all(glm::lessThan(glm::abs(a - b), rgb(1e-6f))); };
  // Texel centres: u = (i + 1/2) / 2, v = 1 - (j + 1/2) / 2 (v runs bottom to top).
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {0.25, 0.75}), rgb(1, 0, 0)));
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {0.75, 0.75}), rgb(0, 1, 0)));
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {0.25, 0.25}), rgb(0, 0, 1)));
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {0.5, 0.5}), rgb(0.5f)));  // the mean of all four
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {0.5, 0.75}), rgb(0.5f, 0.5f, 0)));  // halfway along the top row
  // Outside [0, 1]: repeat wraps to the opposite edge, clamp keeps the edge texel.
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {1.25, 0.75}), rgb(1, 0, 0)));
  CHECK(near(at(rep, vec3(0), vec3(0, 1, 0), {0.0, 0.75}), rgb(0.5f, 0.5f, 0)));  // the seam: both edge texels
  CHECK(near(at(clamp, vec3(0), vec3(0, 1, 0), {0.0, 0.75}), rgb(1, 0, 0)));
  CHECK(near(at(clamp, vec3(0), vec3(0, 1, 0), {-5.0, 7.0}), rgb(1, 0, 0)));
  for (const double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 1e300, -1e300})
    for (const texture* t : {&rep, &clamp}) {
      const rgb c = at(*t, vec3(0), vec3(0, 1, 0), {bad, bad});
      CHECK(std::isfinite(c.x + c.y + c.z));
    }
}

TEST_CASE("texture: a PNG is decoded from sRGB, or read as linear values, and refused when it is not one") {
  // A 1x1 PNG of (128, 0, 255), written by zraka's own writer from its linear value.
  image one(1, 1, rgb(srgb_to_linear(128.0f / 255), 0, 1));
  const auto dir = std::filesystem::temp_directory_path() / "zraka-test-texture";
  std::filesystem::create_directories(dir);
  write_png(one, dir / "one.png");
  const image s = load_texture_image(dir / "one.png", true), l = load_texture_image(dir / "one.png", false);
  CHECK(s.at(0, 0).x == doctest::Approx(srgb_to_linear(128.0f / 255)).epsilon(1e-6));
  CHECK(s.at(0, 0).z == doctest::Approx(1.0));
  CHECK(l.at(0, 0).x == doctest::Approx(128.0 / 255).epsilon(1e-6));
  write_file_atomically(dir / "text.png", "not a png");
  CHECK_THROWS_WITH_AS(load_texture_image(dir / "text.png"), doctest::Contains("text.png: not a PNG image"), error);
  CHECK_THROWS_WITH_AS(load_texture_image(dir / "one.bmp"), doctest::Contains("unknown texture image type '.bmp'"), error);
  image hot(1, 1, rgb(2.0f));
  write_pfm(hot, dir / "hot.pfm");
  CHECK_THROWS_WITH_AS(load_texture_image(dir / "hot.pfm"), doctest::Contains("an albedo must be in [0, 1]"), error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("noise: in [-1, 1], zero on the lattice, continuous, the same every call; turbulence in [0, 1]") {
  double lo = 1, hi = -1;
  for (int i = 0; i < 20000; ++i) {
    const vec3 q(0.37 * i, 0.11 * i - 300, std::sin(double(i)) * 1000);
    const double n = noise(q);
    lo = std::min(lo, n), hi = std::max(hi, n);
    CHECK(n == noise(q));
    const double t = turbulence(q, 6);
    CHECK((t >= 0 && t <= 1));
  }
  CHECK(lo >= -1);
  CHECK(hi <= 1);
  CHECK(hi - lo > 1);  // it does vary
  for (const vec3 q : {vec3(0), vec3(3, -7, 12), vec3(-1e6, 2e6, 5)}) CHECK(noise(q) == doctest::Approx(0).scale(1e-12));
  const vec3 q(1.3, 2.7, -0.4);  // continuity: a small step, a small change
  CHECK(std::abs(noise(q + vec3(1e-7, 0, 0)) - noise(q)) < 1e-5);
  for (int axis = 0; axis < 3; ++axis) {  // across a cell wall: the fade hides the seam
    vec3 below = q, above = q;
    below[axis] = 2 - 1e-9, above[axis] = 2 + 1e-9;
    CHECK(std::abs(noise(above) - noise(below)) < 1e-7);
  }
  for (const double far : {1e15, -3e17}) {  // far from the origin: still a number in [-1, 1]
    const double n = noise(vec3(far, 0.5, 0.25));
    CHECK((n >= -1 && n <= 1));
  }
  CHECK(noise(vec3(std::numeric_limits<double>::quiet_NaN())) == 0);
  CHECK(noise(vec3(std::numeric_limits<double>::infinity())) == 0);
  // A noise texture mixes its two colours; marble too.
  for (const bool marble : {false, true}) {
    const texture t = texture::noise(rgb(0), rgb(1), 3.0, marble ? 5 : 1, marble);
    const rgb c = at(t, vec3(0.3, 0.2, 0.9));
    CHECK((c.x >= 0 && c.x <= 1 && c.x == c.y));
  }
}

TEST_CASE("texture: OBJ texture coordinates reach the hit; without them uv are barycentric") {
  const mesh m = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0.5 0.5\nvt 1 0.5\nvt 0.5 1\nf 1/1 2/2 3/3\n", "uv.obj");
  REQUIRE(m.texcoords.size() == 3);
  scene sc;
  sc.add(mesh(m), sc.add_material(material{}));
  scene_hit sh;
  REQUIRE(nearest_hit(sc, ray({0.25, 0.25, 1}, {0, 0, -1}), sh));
  CHECK(sh.h.uv.x == doctest::Approx(0.625));  // 0.5 (0.5) + 0.25 (1) + 0.25 (0.5)
  CHECK(sh.h.uv.y == doctest::Approx(0.625));
  const mesh bare = parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "bare.obj");
  CHECK(bare.texcoords.empty());
  // A corner without vt: none are kept (like normals).
  CHECK(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n", "some.obj").texcoords.empty());
  CHECK_THROWS_WITH_AS(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0 0 0\nf 1 2 3\n", "w.obj"),
                       doctest::Contains("w.obj:4"), error);
}

TEST_CASE("texture: scene files read image and noise textures, and name what is wrong") {
  const auto dir = std::filesystem::temp_directory_path() / "zraka-test-texture-scene";
  std::filesystem::create_directories(dir);
  write_png(image(4, 2, rgb(0.5f)), dir / "wood.png");
  const std::string head = "objects: [{type: sphere, material: m}]\nmaterials:\n  m: {albedo: ";
  auto load = [&](const std::string& albedo) {
    write_file_atomically(dir / "s.yaml", head + albedo + "}\n");
    return load_scene_file(dir / "s.yaml");
  };
  const loaded_scene img = load("{image: {file: wood.png, wrap: clamp}}");
  const texture& t = img.sc.materials[1].get<material_kinds::lambertian>()->albedo;
  CHECK(t.type == texture::kind::image);
  CHECK(t.map->width == 4);
  CHECK(!t.repeat);
  CHECK(img.resolved.find("image: {file: wood.png, srgb: true, wrap: clamp}") != std::string::npos);
  const loaded_scene mar = load("{noise: {frequency: 2, octaves: 6, marble: true}}");
  CHECK(mar.sc.materials[1].get<material_kinds::lambertian>()->albedo.type == texture::kind::noise);
  CHECK(mar.sc.materials[1].get<material_kinds::lambertian>()->albedo.octaves == 6);
  CHECK_THROWS_WITH_AS(load("{image: {file: nope.png}}"), doctest::Contains("materials.m.albedo.image.file"), error);
  CHECK_THROWS_WITH_AS(load("{image: {file: wood.png, wrap: mirror}}"), doctest::Contains("must be repeat or clamp"), error);
  CHECK_THROWS_WITH_AS(load("{image: {file: wood.png, srgb: maybe}}"), doctest::Contains("expected true or false"), error);
  CHECK_THROWS_WITH_AS(load("{noise: {octaves: 40}}"), doctest::Contains("materials.m.albedo.noise.octaves"), error);
  CHECK_THROWS_WITH_AS(load("{noise: {frequency: -1}}"), doctest::Contains("must be in (0, 1e6]"), error);
  CHECK_THROWS_WITH_AS(load("{noise: {colour: 1}}"), doctest::Contains("unknown key"), error);
  const loaded_scene uv = load("{checker: {even: 0.9, odd: 0.1, scale: 0.25, space: uv}}");
  CHECK(uv.sc.materials[1].get<material_kinds::lambertian>()->albedo.uv_space);
  CHECK(uv.sc.materials[1].get<material_kinds::lambertian>()->albedo.cell == 0.25);
  CHECK(uv.resolved.find("space: uv") != std::string::npos);
  CHECK_FALSE(load("{checker: {space: world}}").sc.materials[1].get<material_kinds::lambertian>()->albedo.uv_space);
  CHECK(load("{checker: {}}").resolved.find("space") == std::string::npos);  // world is the default, not printed
  CHECK_THROWS_WITH_AS(load("{checker: {space: xyz}}"), doctest::Contains("materials.m.albedo.checker.space: must be world or uv"),
                       error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("texture: a roughness texture sets the GGX alpha point by point, kept in [0.001, 1]") {
  hit h;
  h.normal = vec3(0, 1, 0);
  const vec3 wo = glm::normalize(vec3(0.3, 1, 0)), wi = glm::normalize(vec3(-0.5, 1, 0.2));
  const material plain = material::rough_conductor(0.3, conductor_fresnel::from_f0(rgb(0.9f)));
  material textured = plain;
  textured.get<material_kinds::rough_conductor>()->roughness.alpha = 0.7;  // ignored once a map is set
  textured.get<material_kinds::rough_conductor>()->roughness.map = texture::solid(rgb(0.2f, 0.3f, 0.4f));  // mean 0.3
  CHECK(textured.get<material_kinds::rough_conductor>()->roughness.at(h) == doctest::Approx(0.3).epsilon(1e-7));
  CHECK(brdf_cos(textured, h, wo, wi).x == doctest::Approx(brdf_cos(plain, h, wo, wi).x).epsilon(1e-6));
  CHECK(scatter_pdf(textured, h, wo, wi) == doctest::Approx(scatter_pdf(plain, h, wo, wi)).epsilon(1e-6));
  // A checker of two alphas: each cell is its own roughness; a black texel is not a mirror.
  textured.get<material_kinds::rough_conductor>()->roughness.map = texture::checker(rgb(0.05f), rgb(1.0f), 1.0);
  h.p = vec3(0.5, 0, 0.5);
  const double a0 = textured.get<material_kinds::rough_conductor>()->roughness.at(h);
  h.p = vec3(1.5, 0, 0.5);
  const double a1 = textured.get<material_kinds::rough_conductor>()->roughness.at(h);
  CHECK(std::min(a0, a1) == doctest::Approx(0.05).epsilon(1e-6));
  CHECK(std::max(a0, a1) == 1.0);
  textured.get<material_kinds::rough_conductor>()->roughness.map = texture::solid(rgb(0));
  CHECK(textured.get<material_kinds::rough_conductor>()->roughness.at(h) == 1e-3);
  CHECK(std::isfinite(brdf_cos(textured, h, wo, wi).x));
  // In a scene file: a texture where a number would be, or an error naming the field.
  const auto dir = std::filesystem::temp_directory_path() / "zraka-test-roughness-texture";
  std::filesystem::create_directories(dir);
  auto load = [&](const std::string& roughness) {
    write_file_atomically(dir / "s.yaml", "objects: [{type: sphere, material: m}]\nmaterials:\n  m: {type: rough_conductor, "
                                          "metal: gold, roughness: " + roughness + "}\n");
    return load_scene_file(dir / "s.yaml");
  };
  const loaded_scene ls = load("{noise: {low: 0.05, high: 0.5, frequency: 3}}");
  REQUIRE(ls.sc.materials[1].get<material_kinds::rough_conductor>()->roughness.map);
  CHECK(ls.sc.materials[1].get<material_kinds::rough_conductor>()->roughness.map->type == texture::kind::noise);
  CHECK(ls.resolved.find("roughness: {noise: {low: [0.05") != std::string::npos);
  CHECK(!load("0.25").sc.materials[1].get<material_kinds::rough_conductor>()->roughness.map);
  CHECK_THROWS_WITH_AS(load("{checker: {even: 1.5}}"), doctest::Contains("materials.m.roughness: the texture's values are GGX alphas"), error);
  CHECK_THROWS_WITH_AS(load("{noise: {low: 0}}"), doctest::Contains("must be in (0, 1]"), error);
  CHECK_THROWS_WITH_AS(load("{marble: 1}"), doctest::Contains("materials.m.roughness"), error);
  std::filesystem::remove_all(dir);
}

// links: yaml-cpp
// A built-in material kind added through the one door (materials/README.md, "Adding a material"):
// conductor.hpp, the smooth metal. Its physics (the mirror direction weighted by the Fresnel
// reflectance, no numbers drawn), its scene-file entry read, resolved and read again, its errors,
// and the renderers that cannot draw it refusing it by name.
#include "expected_errors.hpp"

#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/mitsuba_export.hpp>
#include <zraka/io/scene_file.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace zraka;
using zraka_test::error_of;

namespace {

hit facing_up() {
  hit h;
  h.p = vec3(0);
  h.normal = vec3(0, 0, 1);
  h.set_face(vec3(0, 0, -1));
  return h;
}

}  // namespace

TEST_CASE("conductor: the mirror direction, weighted by the metal's Fresnel reflectance, drawing no number") {
  const conductor_fresnel gold = *find_metal("gold");
  const material m = material::of(material_kinds::conductor{gold});
  CHECK(is_specular(m));
  CHECK_FALSE(has_density(m));
  CHECK(std::string(kind_name(m.kind)) == "conductor");
  const hit h = facing_up();
  for (const double theta : {0.0, 0.5, 1.2, 1.5}) {
    const vec3 d = glm::normalize(vec3(std::sin(theta), 0, -std::cos(theta)));
    rng g(9), untouched(9);
    const auto s = scatter(m, d, h, g);
    REQUIRE(s);
    CHECK(g.uniform() == untouched.uniform());  // the path's later numbers are not shifted
    CHECK(s->specular);
    CHECK(s->pdf == 0);
    CHECK(glm::length(s->direction - vec3(d.x, d.y, -d.z)) < 1e-12);
    const rgb F = gold.eval(std::cos(theta));
    CHECK(s->weight == F);
    CHECK(s->weight.x > s->weight.z);  // gold: more red than blue reflected
    CHECK(brdf_cos(m, h, -d, s->direction) == rgb(0));  // a delta: nothing for light sampling
    CHECK(scatter_pdf(m, h, -d, s->direction) == 0);
  }
  // Towards grazing angles every metal reflects nearly everything: white, unlike a mirror's albedo.
  const vec3 grazing = glm::normalize(vec3(1, 0, -1e-3));
  rng g(1);
  const rgb F = scatter(m, grazing, h, g)->weight;
  CHECK(F.z > 0.95f);
  // A Schlick F0 of 1 is a perfect mirror.
  const material perfect = material::of(material_kinds::conductor{conductor_fresnel::from_f0(rgb(1))});
  CHECK(scatter(perfect, vec3(0.6, 0, -0.8), h, g)->weight == rgb(1));
}

TEST_CASE("conductor: read from a scene file, written resolved, read back the same") {
  const loaded_scene ls = parse_scene(R"(
materials:
  gold: {type: conductor, metal: gold}
  tinted: {type: conductor, f0: [0.9, 0.6, 0.4]}
  plain: {type: conductor}
objects:
  - {type: sphere, material: gold}
  - {type: sphere, center: [2, 0, 0], material: tinted}
  - {type: sphere, center: [4, 0, 0], material: plain}
)", "c.yaml");
  const auto* gold = ls.sc.materials[1].get<material_kinds::conductor>();
  REQUIRE(gold);
  CHECK(gold->fresnel.eta == find_metal("gold")->eta);
  CHECK(ls.sc.materials[2].get<material_kinds::conductor>()->fresnel.schlick);
  CHECK(ls.sc.materials[3].get<material_kinds::conductor>()->fresnel.eta == find_metal("silver")->eta);
  CHECK(ls.resolved.find("type: conductor") != std::string::npos);
  const loaded_scene again = parse_scene(ls.resolved, "resolved.yaml");
  for (std::size_t i = 1; i < 4; ++i) {
    const auto* a = ls.sc.materials[i].get<material_kinds::conductor>();
    const auto* b = again.sc.materials[i].get<material_kinds::conductor>();
    REQUIRE(b);
    CHECK(a->fresnel.schlick == b->fresnel.schlick);
    CHECK(a->fresnel.f0 == b->fresnel.f0);
    CHECK(glm::length(vec3(a->fresnel.eta - b->fresnel.eta)) < 1e-6);
    CHECK(glm::length(vec3(a->fresnel.k - b->fresnel.k)) < 1e-5);
  }
  auto load = [](const std::string& entry) {
    return error_of([&] { (void)parse_scene("materials: {m: " + entry + "}\nobjects: [{type: sphere, material: m}]", "t.yaml"); });
  };
  CHECK(load("{type: conductor, f0: 2}") == "t.yaml:1:38: materials.m.f0: a reflectance must be at most 1");
  CHECK(load("{type: conductor, f0: 1, metal: gold}") == "t.yaml:1:16: materials.m: a conductor takes one of: metal, eta and k, f0");
  CHECK(load("{type: conductor, roughness: 0.1}") ==
        "t.yaml:1:34: materials.m.roughness: unknown key (expected one of: type, metal, eta, k, f0)");
  CHECK(load("{type: conductor, metal: tin}").find("materials.m.metal: unknown metal 'tin'") != std::string::npos);
  // A course cannot take its name: it is built in, registered like the others.
  scene_registry reg;
  CHECK(error_of([&] { reg.add_material("conductor", {}, [](const scene_node&) { return material{}; }); }) ==
        "scene registry: material type 'conductor' is built in; a registered type must have a new name");
}

TEST_CASE("conductor: Whitted reflects it; the kernel does not render it and says so by name") {
  scene sc;
  const int metal = sc.add_material(material::of(material_kinds::conductor{*find_metal("copper")}));
  sc.add(sphere{{0, 0, -3}, 1}, metal);
  sc.materials[std::size_t(metal)].radiance = rgb(0);
  sc.settings.width = sc.settings.height = 8;
  CHECK(error_of([&] { check_whitted_scene(sc); }) == "(no error)");
  sc.background = rgb(1);
  const light_set lights(sc);
  rng g(1);
  std::uint64_t rays = 0;
  const rgb c = whitted_radiance(sc, lights, ray{{0, 0, 0}, {0, 0, -1}}, g, whitted_options{}, rays);
  CHECK(c == find_metal("copper")->eval(1.0));  // head on: F(0) of the white sky
  CHECK(error_of([&] { (void)pack_scene(sc, 8, 8, path_options{}); }) ==
        "realtime: material 0 is a conductor, which the OpenCL kernel does not render; render it with pathtrace");
  // The Mitsuba export writes its complex index (the reference tool then refuses the type by name).
  const std::string j = mitsuba_scene_json(sc, 8, 8, 2);
  CHECK(j.find("\"type\": \"conductor\"") != std::string::npos);
  CHECK(j.find("\"eta\": [") != std::string::npos);
}

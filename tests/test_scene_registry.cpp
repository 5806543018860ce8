// links: yaml-cpp
// The scene registry (scene_registry.hpp): an outside project's types by name in a scene file.
// The types are those of book/assignments/external (a disk user shape with area sampling and a
// glossy custom BSDF), registered by its register_types(): loaded from YAML text, rendered by
// the path tracer against closed forms (a disk light over a floor; the glossy disk in a white
// sky); the errors (unknown types list the registered ones, bad fields of a user type with their
// place, shadowing a built-in name); Whitted and the realtime packer refuse them by name.
#include "../book/assignments/external/register.hpp"

#include <zraka/app/testing.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/integrators/integrator_door.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/sampling/estimator.hpp>

#include <doctest/doctest.h>

#include "expected_errors.hpp"

#include <functional>
#include <memory>
#include <string>

using namespace zraka;
namespace zt = zraka::testing;
using zraka_test::error_of;

namespace {

scene_registry course_types() {
  scene_registry reg;
  mycourse::register_types(reg);
  return reg;
}
loaded_scene parse(const std::string& text) { return parse_scene(text, "t.yaml", ".", course_types()); }
std::string parse_error(const std::string& text) {
  return error_of([&] { (void)parse(text); });
}

// The red channel of n path-traced samples along one ray.
estimator along(const scene& sc, integrator method, const ray& r, int n = 40000) {
  path_options o;
  o.method = method;
  o.max_depth = 4;
  const path_tracer tracer(sc, o);
  estimator e;
  std::uint64_t rays = 0;
  for (int i = 0; i < n; ++i) {
    rng g(3, 0, std::uint32_t(i));
    e.add(double(tracer(r, g, rays).x));
  }
  return e;
}

const integrator all_methods[] = {integrator::naive, integrator::nee, integrator::mis};

}  // namespace

TEST_CASE("scene registry: a registered disk light over a floor gives the closed form") {
  // A one-sided disk of radius R at height h facing down, radiance Le, over a Lambertian floor
  // of albedo rho. On the axis the irradiance is E = pi Le R^2 / (h^2 + R^2), so the floor there
  // reflects L = rho E / pi = rho Le R^2 / (h^2 + R^2) = 0.5 * 2 * 0.25 / 1.25 = 0.2. Light the
  // floor sends up meets the disk's black back or the black sky: no other bounce adds anything.
  const loaded_scene ls = parse(R"(
materials:
  lamp: {type: emitter, radiance: 2}
  white: {type: lambertian, albedo: 0.5}
objects:
  - {type: plane, material: white}
  - {type: disk, center: [0, 1, 0], normal: [0, -1, 0], radius: 0.5, material: lamp}
)");
  REQUIRE(ls.sc.user_shapes.size() == 1);
  CHECK(ls.sc.user_shapes[0].shape->name() == "disk");
  CHECK(ls.sc.user_shapes[0].material == 1);
  const light_set lights(ls.sc);
  CHECK(lights.size() == 1);  // sampled, not hit only: the disk gives its area
  CHECK(lights.hit_only().empty());
  const ray r(vec3(2, 0.5, 0), vec3(-2, -0.5, 0));  // to the floor under the disk's centre
  for (integrator m : all_methods) {
    const estimator e = along(ls.sc, m, r);
    const auto res = zt::mean_within(e, 0.2, 5);
    CHECK_MESSAGE(res.ok, name(m) << ": " << res.message);
  }
}

TEST_CASE("scene registry: a registered glossy disk in a white sky gives its closed-form albedo") {
  // Background 1 from every direction; the camera ray meets the flat disk at normal incidence,
  // and everything it reflects goes to the sky: L = albedo(n) = kd + ks A(s) exactly.
  const loaded_scene ls = parse(R"(
settings: {background: 1}
materials:
  g: {type: glossy, kd: 0.2, ks: 0.7, exponent: 20}
objects:
  - {type: disk, normal: [0, 1, 0], radius: 1, material: g}
)");
  const double expected = mycourse::glossy(vec3(0.2), vec3(0.7), 20).normal_albedo().x;
  REQUIRE(is_custom(ls.sc.materials[1]));
  CHECK(ls.sc.materials[1].get<material_kinds::custom>()->bsdf->name() == "glossy");
  const ray r(vec3(0, 2, 0), vec3(0, -1, 0));
  for (integrator m : all_methods) {
    const estimator e = along(ls.sc, m, r);
    const auto res = zt::mean_within(e, expected, 5);
    CHECK_MESSAGE(res.ok, name(m) << ": " << res.message);
  }
}

TEST_CASE("scene registry: the resolved scene has the user types' defaults and reads back") {
  const loaded_scene ls = parse("materials: {g: {type: glossy}}\nobjects: [{type: disk, material: g}]");
  INFO(ls.resolved);
  CHECK(ls.resolved.find("type: disk, center: [0, 0, 0], normal: [0, 1, 0], radius: 1, material: g") !=
        std::string::npos);
  CHECK(ls.resolved.find("g: {type: glossy, kd: [0.2, 0.2, 0.2], ks: [0.6, 0.6, 0.6], exponent: 50}") !=
        std::string::npos);
  CHECK(parse(ls.resolved).resolved == ls.resolved);
  // Without the registry the same file is an error, not a silent default.
  CHECK(error_of([&] { (void)parse_scene(ls.resolved, "t.yaml"); }).find("unknown material type 'glossy'") !=
        std::string::npos);
}

TEST_CASE("scene registry: unknown types list the built-in and the registered names") {
  CHECK(parse_error("objects: [{type: dsk}]") ==
        "t.yaml:1:18: objects[0].type: unknown object type 'dsk' (expected sphere, plane, triangle, quad, box, "
        "mesh or bezier; registered: disk)");
  CHECK(parse_error("materials: {m: {type: glosy}}\nobjects: [{type: disk}]") ==
        "t.yaml:1:23: materials.m.type: unknown material type 'glosy' (expected lambertian, metal, dielectric, "
        "emitter, phong, rough_conductor, rough_dielectric, boundary or conductor; registered: glossy)");
  // Without registered types the list is the built-in one alone.
  CHECK(error_of([] { (void)parse_scene("objects: [{type: disk}]", "t.yaml"); }) ==
        "t.yaml:1:18: objects[0].type: unknown object type 'disk' (expected sphere, plane, triangle, quad, box, "
        "mesh or bezier)");
}

TEST_CASE("scene registry: a user type's bad fields are reported with their place, as built-in ones") {
  CHECK(parse_error("objects:\n  - {type: disk, radius: -1}") == "t.yaml:2:26: objects[0].radius: must be positive");
  CHECK(parse_error("objects:\n  - {type: disk, radius: [1, 2]}") ==
        "t.yaml:2:26: objects[0].radius: expected a number, got a list");
  CHECK(parse_error("objects:\n  - {type: disk, radius: .nan}") ==
        "t.yaml:2:26: objects[0].radius: must be finite, got .nan");
  CHECK(parse_error("objects:\n  - {type: disk, center: [0, 1]}") ==
        "t.yaml:2:26: objects[0].center: expected [x, y, z], got a list");
  CHECK(parse_error("objects:\n  - {type: disk, normal: [0, 0, 0]}") ==
        "t.yaml:2:26: objects[0].normal: a direction must not be zero");
  CHECK(parse_error("objects:\n  - {type: disk, name: lid, radius: 0}") ==
        "t.yaml:2:37: objects[0] (lid).radius: must be positive");
  // Unknown and duplicated keys, before the factory runs; a transform is not among a disk's keys.
  CHECK(parse_error("objects:\n  - {type: disk, size: 2}") ==
        "t.yaml:2:18: objects[0].size: unknown key for a disk (expected one of: type, name, material, center, "
        "normal, radius)");
  CHECK(parse_error("objects:\n  - {type: disk, transform: {scale: 2}}").find(
            "objects[0].transform: unknown key for a disk") != std::string::npos);
  CHECK(parse_error("objects:\n  - {type: disk, radius: 1, radius: 2}") ==
        "t.yaml:2:29: objects[0].radius: duplicate key");
  CHECK(parse_error("objects:\n  - {type: disk, material: gold}") ==
        "t.yaml:2:28: objects[0].material: unknown material 'gold' (defined: default)");
  // Materials: colours, and the type's own rule (kd + ks <= 1) at the field it names.
  CHECK(parse_error("materials:\n  m: {type: glossy, kd: -1}\nobjects: [{type: disk}]") ==
        "t.yaml:2:25: materials.m.kd: a colour must not be negative");
  CHECK(parse_error("materials:\n  m: {type: glossy, kd: 0.5, ks: 0.6}\nobjects: [{type: disk}]") ==
        "t.yaml:2:34: materials.m.ks: kd + ks must not exceed 1 (the surface would make light)");
  CHECK(parse_error("materials:\n  m: {type: glossy, ior: 1.5}\nobjects: [{type: disk}]") ==
        "t.yaml:2:21: materials.m.ior: unknown key for a glossy (expected one of: type, kd, ks, exponent)");
}

TEST_CASE("scene registry: errors a factory throws itself get the entry's place") {
  scene_registry reg;
  reg.add_shape("lid", {"r"}, [](const scene_node&) -> user_shape_ptr<double> { throw error("lid: no good"); });
  reg.add_shape("nothing", {}, [](const scene_node&) { return user_shape_ptr<double>(); });
  reg.add_shape("sloppy", {"r"}, [](const scene_node& n) -> user_shape_ptr<double> {
    (void)n.number("radius", 1);  // not registered: a bug in the program
    return nullptr;
  });
  auto err = [&](const std::string& t) { return error_of([&] { (void)parse_scene(t, "t.yaml", ".", reg); }); };
  CHECK(err("objects:\n  - {type: lid}") == "t.yaml:2:5: objects[0]: lid: no good");
  CHECK(err("objects:\n  - {type: nothing}") == "t.yaml:2:5: objects[0]: the factory for 'nothing' made no shape");
  CHECK(err("objects:\n  - {type: sloppy}") ==
        "t.yaml:2:5: objects[0]: scene registry: the factory for 'sloppy' reads key 'radius', which it did not "
        "register");
  // scene_t::add refusing the shape (here: bounds that are not finite) is reported at the entry.
  reg.add_shape("huge", {}, [](const scene_node&) {
    return std::make_shared<const mycourse::disk>(vec3(1e308), vec3(1, 1, 1), 1e308);
  });
  CHECK(err("objects:\n  - {type: huge}") ==
        "t.yaml:2:5: objects[0]: user shape 'disk': its bounds must be a finite, non-empty box");
}

TEST_CASE("scene registry: names that shadow built-in types, repeats and bad names are refused") {
  scene_registry reg;
  auto shape = [](const scene_node&) { return user_shape_ptr<double>(); };
  auto mat = [](const scene_node&) { return material{}; };
  for (const std::string& t : builtin_object_types())
    CHECK(error_of([&] { reg.add_shape(t, {}, shape); }) ==
          "scene registry: object type '" + t + "' is built in; a registered type must have a new name");
  REQUIRE(reg.builtin_materials().size() == 9);  // registered by materials/builtin.hpp
  for (const std::string& t : reg.builtin_materials())
    CHECK(error_of([&] { reg.add_material(t, {}, mat); }) ==
          "scene registry: material type '" + t + "' is built in; a registered type must have a new name");
  reg.add_shape("disk", {}, shape);
  CHECK(error_of([&] { reg.add_shape("disk", {}, shape); }) == "scene registry: object type 'disk' is registered twice");
  CHECK(error_of([&] { reg.add_material("disk", {}, mat); }) == "(no error)");  // materials are another list
  CHECK(error_of([&] { reg.add_shape("My-Disk", {}, shape); }) ==
        "scene registry: object type 'My-Disk': a type is a word of a-z, 0-9 and _");
  CHECK(error_of([&] { reg.add_shape("", {}, shape); }).find("a type is a word") != std::string::npos);
  CHECK(error_of([&] { reg.add_shape("cap", {"material"}, shape); }) ==
        "scene registry: object type 'cap': key 'material' is common to every object");
  CHECK(error_of([&] { reg.add_shape("cap", {"r", "r"}, shape); }) ==
        "scene registry: object type 'cap': key 'r' is listed twice");
  CHECK(error_of([&] { reg.add_shape("cap", {}, nullptr); }) ==
        "scene registry: the factory for object type 'cap' is empty");
}

TEST_CASE("scene registry: the built-in lists are the types the loader knows") {
  // The registry refuses exactly the names the loader takes as its own.
  for (const std::string& t : builtin_object_types()) {
    const std::string e = error_of([&] { (void)parse_scene("objects: [{type: " + t + "}]", "t.yaml"); });
    CHECK_MESSAGE(e.find("unknown object type") == std::string::npos, t << ": " << e);
  }
  const scene_registry builtins;
  for (const std::string& t : builtins.builtin_materials()) {
    const std::string e =
        error_of([&] { (void)parse_scene("materials: {m: {type: " + t + "}}\nobjects: [{type: sphere}]", "t.yaml"); });
    // Known: no error, or only a field it requires (a boundary names its medium).
    CHECK_MESSAGE((e == "(no error)" || e.find("required, but missing") != std::string::npos), t << ": " << e);
  }
}

TEST_CASE("scene registry: Whitted and the realtime packer refuse the user types by name") {
  const loaded_scene disk_only = parse(R"(
materials: {lamp: {type: emitter}}
objects:
  - {type: plane}
  - {type: disk, center: [0, 1, 0], normal: [0, -1, 0], material: lamp}
)");
  // Whitted renders a user shape (it goes through scene_query like any shape) ...
  CHECK(error_of([&] { check_whitted_scene(disk_only.sc); }) == "(no error)");
  // ... but the kernel cannot run C++ code.
  // Chapter 2.3's pathtrace cannot load these scenes (it has no registry): the refusals name the
  // course's own program instead (render_it_with.hpp).
  CHECK(error_of([&] { (void)pack_scene(disk_only.sc, 8, 8, path_options{}); }) ==
        "realtime: objects[1] is a user shape ('disk'), which the OpenCL kernel cannot run; render it with your "
        "course's program built on zraka::pathtrace_main (its registry has 'disk'; chapter 2.3's pathtrace has "
        "the built-in kinds only)");
  const loaded_scene glossy_only = parse("materials: {g: {type: glossy}}\nobjects: [{type: sphere, material: g}]");
  CHECK(error_of([&] { check_whitted_scene(glossy_only.sc); }) ==
        "whitted: material 'g' is a custom BSDF ('glossy'), which the Whitted ray tracer cannot shade; render it "
        "with your course's program built on zraka::pathtrace_main (its registry has 'glossy'; chapter 2.3's "
        "pathtrace has the built-in kinds only)");
  CHECK(error_of([&] { (void)pack_scene(glossy_only.sc, 8, 8, path_options{}); }) ==
        "realtime: material 'g' is a custom BSDF ('glossy'), which the OpenCL kernel cannot run; render it with "
        "your course's program built on zraka::pathtrace_main (its registry has 'glossy'; chapter 2.3's "
        "pathtrace has the built-in kinds only)");
}

TEST_CASE("scene registry: integrators by name, the built-ins registered as a course's own") {
  auto flat = [](const scene&, const path_options&) {
    return scene_registry::radiance_fn([](const ray&, rng&, std::uint64_t&) { return rgb(0.5f); });
  };
  scene_registry reg;
  reg.add_integrator("flat", flat);
  CHECK(error_of([&] { reg.add_integrator("flat", flat); }) == "scene registry: integrator type 'flat' is registered twice");
  CHECK(error_of([&] { reg.add_integrator("Flat", flat); }) ==
        "scene registry: integrator type 'Flat': a type is a word of a-z, 0-9 and _");
  CHECK(error_of([&] { reg.add_integrator("none", nullptr); }) == "scene registry: the factory for integrator 'none' is empty");
  CHECK(integrator_choices(reg) == "naive, nee or mis; registered: flat");
  CHECK(integrator_choices(scene_registry{}) == "naive, nee or mis");
  CHECK(error_of([&] { (void)find_integrator("fog", reg); }) == "unknown integrator 'fog' (naive, nee, mis; registered: flat)");

  const loaded_scene ls = parse("objects: [{type: sphere}]\n");
  // The built-ins' factories give the path tracer itself, with their method: what the program
  // calls directly (app/pathtrace_main.hpp), as before the door.
  CHECK(builtin_integrators().integrators().size() == 3);
  for (const integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
    const scene_registry::radiance_fn fn = find_integrator(name(m), reg)(ls.sc, path_options{});
    const path_tracer* t = fn.target<path_tracer>();
    REQUIRE(t != nullptr);
    CHECK(t->opt.method == m);
  }
  // A course's comes back as it was made.
  const scene_registry::radiance_fn own = find_integrator("flat", reg)(ls.sc, path_options{});
  CHECK(own.target<path_tracer>() == nullptr);
  rng g(1, 0, 0);
  std::uint64_t rays = 0;
  CHECK(own(ray(vec3(0), vec3(0, 0, 1)), g, rays) == rgb(0.5f));
}

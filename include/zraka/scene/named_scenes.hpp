#pragma once
// The registry of named scenes: what `--scene NAME` means in every program (issue 12). A name is
// either built here in C++ (the default scene, the Cornell boxes, the furnace, the spheres of book 4.3) or stands
// for a file scenes/NAME.yaml under the resource root. A `.yaml` path is a file of its own; see
// scene_argument.hpp, which loads either. This header needs no YAML library, so the real-time
// chapter, its tests and its benchmark use it as they are.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/scene/cornell.hpp>
#include <zraka/scene/default_scene.hpp>
#include <zraka/scene/scene.hpp>

#include <array>
#include <string>
#include <string_view>

namespace zraka {

// Diffuse spheres on a checkered ground sphere under a blue sky, lit by a small glowing sphere:
// only spheres and Lambertian materials, the scene the specialised kernel is fastest on.
ZRAKA_COMPILED_FN scene spheres_scene();

// The furnace (book 2.3): the camera inside a sphere of albedo a that glows with L_e on its
// inside. Every path sees L_e at each bounce, weighted a^k, so L = L_e (1 + a + a^2 + ...) =
// L_e / (1 - a), or L_e (1 - a^(D+1)) / (1 - a) when paths stop after D bounces.
constexpr double furnace_albedo = 0.5, furnace_Le = 1.0;
ZRAKA_COMPILED_FN scene furnace_scene();

struct named_scene {
  std::string_view name;
  scene (*build)();       // built in C++, or nullptr: the file scenes/<name>.yaml
  std::string_view what;  // one line for --help
};

// Every accepted name, in the order --help lists them. scenes/cornell*.yaml hold the same
// Cornell boxes as the C++ (chapter 2.3's smoke test checks it bit for bit).
inline constexpr std::array<named_scene, 17> named_scenes{{
    {"cornell", [] { return cornell_box<double>(cornell_variant::boxes); }, "the Cornell box with two white boxes"},
    {"cornell-glass", [] { return cornell_box<double>(cornell_variant::glass); }, "the tall box and a glass sphere"},
    {"cornell-spheres", [] { return cornell_box<double>(cornell_variant::spheres); }, "a mirror and a glass sphere"},
    {"furnace", furnace_scene, "inside a glowing sphere (closed form)"},
    {"spheres", spheres_scene, "diffuse spheres under a sky (book 4.3)"},
    {"default", default_scene, "one ball of each material, a cube, two lights (book 2.2)"},
    {"box", nullptr, "scenes/box.yaml"},
    {"teapot", nullptr, "scenes/teapot.yaml"},
    {"glass-both", nullptr, "scenes/glass-both.yaml"},
    {"glass-reflect", nullptr, "scenes/glass-reflect.yaml"},
    {"glass-refract", nullptr, "scenes/glass-refract.yaml"},
    // The stiff scenes (book 6.2): light that one way of sampling paths finds and another does not.
    {"caustic-box", nullptr, "scenes/caustic-box.yaml: a glass ball's caustic"},
    {"ajar-door", nullptr, "scenes/ajar-door.yaml: lit through a door's gap"},
    {"tiny-light", nullptr, "scenes/tiny-light.yaml: a light of 0.5 mm, 1e6 times as bright"},
    {"smallpt-walls", nullptr, "scenes/smallpt-walls.yaml: walls that are spheres of radius 1e5"},
    // Participating media (book 6.1).
    {"fog-cornell", nullptr, "scenes/fog-cornell.yaml: the Cornell box in smoke, lit through a hole"},
    {"milk-glass", nullptr, "scenes/milk-glass.yaml: a glass ball full of milk"},
}};

// "cornell, cornell-glass, ..." for --help and error messages.
ZRAKA_COMPILED_FN std::string named_scene_list();

// nullptr for a name that is not in the registry.
inline const named_scene* find_named_scene(std::string_view name) {
  for (const named_scene& n : named_scenes)
    if (n.name == name) return &n;
  return nullptr;
}

// A scene that is built in C++; a name that stands for a YAML file is refused (load it with
// scene_argument.hpp's load_scene_argument, which reads YAML).
inline scene builtin_scene(std::string_view name) {
  const named_scene* n = find_named_scene(name);
  if (!n) throw error("unknown scene '" + std::string(name) + "' (" + named_scene_list() + ", or a .yaml file)");
  if (!n->build) throw error("scene '" + std::string(name) + "' is a scene file (" + std::string(n->what) + "); this program reads no YAML");
  return n->build();
}

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN scene furnace_scene() {
  scene sc;
  material m = material::lambertian(rgb(float(furnace_albedo)));
  m.radiance = rgb(float(furnace_Le));
  m.two_sided = true;  // it glows towards the inside, where the camera is
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(m));
  sc.camera.position = {0.2, -0.1, 0.3};
  sc.camera.look_at = {0, 0, -1};
  sc.settings.width = sc.settings.height = 64;
  return sc;
}

// [listing spheres-scene]
ZRAKA_COMPILED_FN scene spheres_scene() {
  scene sc;
  const int ground = sc.add_material(material::lambertian(texture::checker(rgb(0.75f), rgb(0.3f), 0.5)));
  const int red = sc.add_material(material::lambertian(rgb(0.7f, 0.15f, 0.1f)));
  const int blue = sc.add_material(material::lambertian(rgb(0.15f, 0.3f, 0.7f)));
  const int white = sc.add_material(material::lambertian(rgb(0.8f)));
  const int lamp = sc.add_material(material::emitter(rgb(12.0f, 10.0f, 7.0f)));
  sc.add(sphere{{0, -1000, 0}, 1000}, ground);
  sc.add(sphere{{-1.1, 0.5, 0}, 0.5}, red);
  sc.add(sphere{{0, 0.7, -0.6}, 0.7}, white);
  sc.add(sphere{{1.1, 0.45, 0.3}, 0.45}, blue);
  sc.add(sphere{{1.5, 2.6, 1.5}, 0.5}, lamp);
  sc.background = rgb(0.35f, 0.45f, 0.6f);
  sc.camera.position = {0, 1.4, 4.2};
  sc.camera.look_at = {0, 0.5, 0};
  sc.camera.vfov_degrees = 40;
  return sc;
}
// [end]

ZRAKA_COMPILED_FN std::string named_scene_list() {
  std::string s;
  for (const named_scene& n : named_scenes) s += (s.empty() ? "" : ", ") + std::string(n.name);
  return s;
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

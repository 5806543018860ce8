#pragma once
// Which program can render a scene that a renderer refuses (whitted.hpp, gpu_scene.hpp): the path
// tracer renders every kind, built in or a course's own. A course's shapes, materials and lights
// (user shapes, custom BSDFs, custom lights: scene_registry.hpp) exist only in its C++ code, so
// chapter 2.3's `pathtrace` cannot load a scene that uses them; the refusal then names the program that can, the course's
// own, built on zraka::pathtrace_main (app/pathtrace_main.hpp) with the registry that has them.
#include <zraka/materials/material.hpp>
#include <zraka/scene/scene.hpp>

#include <algorithm>
#include <string>
#include <vector>

namespace zraka {

// "render it with pathtrace", or for a scene with a course's kinds "render it with your course's
// program built on zraka::pathtrace_main (its registry has 'torus'; chapter 2.3's pathtrace has
// the built-in kinds only)".
template <class T> std::string render_it_with(const scene_t<T>& sc) {
  std::vector<std::string> own;  // the kinds' names, in the scene's order, once each
  auto note = [&](const std::string& n) {
    if (std::find(own.begin(), own.end(), n) == own.end()) own.push_back(n);
  };
  for (const auto& u : sc.user_shapes) note(u.shape->name());
  for (const material& m : sc.materials)  // every material: an unused one also stops the loader
    if (is_custom(m)) note(m.get<material_kinds::custom>()->bsdf->name());
  for (const light& l : sc.lights)  // lights/light.hpp: a course's light kind
    if (l.is<light_kinds::custom>()) note(light_type(l));
  if (own.empty()) return "render it with pathtrace";
  std::string list;
  for (std::size_t i = 0; i < own.size(); ++i)
    list += (i == 0 ? "" : i + 1 == own.size() ? " and " : ", ") + ("'" + own[i] + "'");
  return "render it with your course's program built on zraka::pathtrace_main (its registry has " + list +
         "; chapter 2.3's pathtrace has the built-in kinds only)";
}

}  // namespace zraka

#pragma once
// The built-in light kinds of scene files, registered by name exactly as a course registers its
// own (scene_registry::add_light: the type, the keys its entry may have besides `type`, and the
// reader that makes the light). One line per kind; a scene_registry starts with them.
// Registry is scene_registry (scene/scene_registry.hpp), the readers' node its scene_node
// (io/scene_file.hpp): this file needs neither, so the light layer stays below both.
#include <zraka/lights/light.hpp>

namespace zraka {

// [listing builtin-lights]
template <class Registry> void register_builtin_lights(Registry& r) {
  using namespace light_kinds;
  r.add_light("point", point::keys(), [](const auto& n) { return light(point::read(n)); });
}
// [end]

}  // namespace zraka

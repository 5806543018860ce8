#pragma once
// The project's types by name, for scene files (zraka/scene/scene_registry.hpp):
//   objects:   - {type: disk, center: [x, y, z], normal: [x, y, z], radius: r, material: NAME}
//   materials: NAME: {type: glossy, kd: colour, ks: colour, exponent: s}
// The factories read their fields through zraka::scene_node, so a wrong field is reported as
// "scene.yaml:LINE:COLUMN: objects[2].radius: must be positive", as for zraka's own types.
#include "disk.hpp"
#include "glossy.hpp"

#include <zraka/io/scene_file.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <memory>

namespace mycourse {

// [listing register-types]
inline void register_types(zraka::scene_registry& reg) {
  reg.add_shape("disk", {"center", "normal", "radius"}, [](const zraka::scene_node& n) {
    const zraka::vec3 c = n.point("center", zraka::vec3(0)), normal = n.direction("normal", {0, 1, 0});
    const double r = n.number("radius", 1.0);
    if (!(r > 0)) n.fail("radius", "must be positive");
    return std::make_shared<const disk>(c, normal, r);
  });
  reg.add_material("glossy", {"kd", "ks", "exponent"}, [](const zraka::scene_node& n) {
    const zraka::vec3 kd(n.colour("kd", zraka::rgb(0.2f))), ks(n.colour("ks", zraka::rgb(0.6f)));
    const double s = n.number("exponent", 50);
    if (!(s >= 0)) n.fail("exponent", "must not be negative");
    for (int i = 0; i < 3; ++i)
      if (kd[i] + ks[i] > 1) n.fail("ks", "kd + ks must not exceed 1 (the surface would make light)");
    return zraka::material::custom(std::make_shared<const glossy>(kd, ks, s));
  });
}
// [end]

}  // namespace mycourse

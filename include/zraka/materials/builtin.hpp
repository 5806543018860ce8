#pragma once
// The built-in material types of scene files, registered by name exactly as a course registers
// its own (scene_registry::add_material: the type, the keys its entry may have besides `type`,
// and the reader that makes the material). One line per type; a scene_registry starts with them.
// Registry is scene_registry (scene/scene_registry.hpp), the readers' node its scene_node
// (io/scene_file.hpp): this file needs neither, so the material layer stays below both.
#include <zraka/materials/material.hpp>

namespace zraka {

// A material of kind K read by K's reader, which may set the common fields (emitter, dielectric).
template <class K, class Node> material read_material(const Node& n) {
  material m;
  m.kind = K::read(n, m);
  return m;
}

// [listing builtin-materials]
template <class Registry> void register_builtin_materials(Registry& r) {
  using namespace material_kinds;
  r.add_material("lambertian", lambertian::keys(), [](const auto& n) { return read_material<lambertian>(n); });
  r.add_material("metal", fuzzy_metal::keys(), [](const auto& n) { return read_material<fuzzy_metal>(n); });
  r.add_material("dielectric", dielectric::keys(), [](const auto& n) { return read_material<dielectric>(n); });
  r.add_material("emitter", emitter::keys(), [](const auto& n) { return read_material<emitter>(n); });
  r.add_material("phong", phong::keys(), [](const auto& n) { return read_material<phong>(n); });
  r.add_material("rough_conductor", rough_conductor::keys(), [](const auto& n) { return read_material<rough_conductor>(n); });
  r.add_material("rough_dielectric", rough_dielectric::keys(), [](const auto& n) { return read_material<rough_dielectric>(n); });
  r.add_material("boundary", dielectric::boundary_keys(), [](const auto& n) {  // book 6.1: a medium's shape
    material m;
    m.kind = dielectric::read_boundary(n, m);
    return m;
  });
  r.add_material("conductor", conductor::keys(), [](const auto& n) { return read_material<conductor>(n); });
}
// [end]

}  // namespace zraka

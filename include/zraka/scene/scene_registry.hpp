#pragma once
// Types of one's own in scene files (book 4.1, 2.3 "Extending zraka"): a registry that a program
// fills before it loads a scene, so that a YAML file can say `type: disk` for a user shape
// (user_shape.hpp) or `{type: glossy, ...}` for a material with a custom BSDF (custom_bsdf.hpp):
//
//     zraka::scene_registry reg;
//     reg.add_shape("disk", {"center", "normal", "radius"}, [](const zraka::scene_node& n) {
//       const double r = n.number("radius", 1.0);
//       if (!(r > 0)) n.fail("radius", "must be positive");
//       return std::make_shared<my_disk>(n.point("center", zraka::vec3(0)), n.direction("normal"), r);
//     });
//     const auto ls = zraka::load_scene_file("my.yaml", reg);
//
// A type is registered with the keys its entry may have besides the common ones (objects: type,
// name, material; materials: type). The loader checks the keys before it calls the factory, so
// an unknown or duplicated key is an error as for a built-in type; the factory reads the fields
// through a scene_node (scene_file.hpp), whose readers are those of the built-in types and whose
// errors say "FILE:LINE:COLUMN: objects[2].radius: ...". A name that is already built in, or
// registered twice, is refused when it is registered.
// The built-in materials come through the same door: a registry starts with them, each
// registered by add_material in materials/builtin.hpp, one line per kind.
// Lights that are not shapes come through one door: a registry starts with the built-in kinds,
// each registered by add_light in lights/builtin.hpp, one line per kind, and a course adds its
// own (a spot light: lights/custom_light.hpp) with the same call.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/scene/scene.hpp>

#include <algorithm>
#include <cstdint>
#include <functional>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace zraka {

class scene_node;     // the reader a factory gets (scene_file.hpp)
struct path_options;  // the path tracer's options, which an integrator's factory gets (path.hpp)

// The types the scene format itself knows; a registered name must differ from all of them.
inline const std::vector<std::string>& builtin_object_types() {
  static const std::vector<std::string> v = {"sphere", "plane", "triangle", "quad", "box", "mesh", "bezier"};
  return v;
}

class scene_registry {
 public:
  using shape_factory = std::function<user_shape_ptr<double>(const scene_node&)>;
  using material_factory = std::function<material(const scene_node&)>;
  using light_factory = std::function<light(const scene_node&)>;
  template <class F> struct entry {
    std::vector<std::string> keys;  // allowed besides the common ones
    F make;
    bool builtin = false;  // registered by the registry itself (materials/builtin.hpp, lights/builtin.hpp)
  };

  // The built-in material types (materials/builtin.hpp) and light kinds (lights/builtin.hpp),
  // registered with add_material and add_light. Defined in scene_file.hpp, where their readers'
  // scene_node is.
  scene_registry();

  // A shape: the factory returns the shape; the object's material is the entry's `material`.
  ZRAKA_COMPILED_FN void add_shape(const std::string& type, std::vector<std::string> keys, shape_factory make);
  // A material: the factory returns the whole material, usually material::custom(bsdf), with
  // radiance or two_sided set if it glows.
  ZRAKA_COMPILED_FN void add_material(const std::string& type, std::vector<std::string> keys, material_factory make);
  // A light that is not a shape (lights/light.hpp), in a scene file's lights section: the
  // factory returns it; a course's is light(light_kinds::custom{std::make_shared<my_light>(...)}).
  ZRAKA_COMPILED_FN void add_light(const std::string& type, std::vector<std::string> keys, light_factory make);

  ZRAKA_COMPILED_FN const entry<shape_factory>* shape(const std::string& type) const;
  ZRAKA_COMPILED_FN const entry<material_factory>* material_type(const std::string& type) const;
  ZRAKA_COMPILED_FN const entry<light_factory>* light_entry(const std::string& type) const;
  // The built-in material types, in the order of builtin.hpp: "lambertian", "metal", ...
  const std::vector<std::string>& builtin_materials() const { return builtin_materials_; }
  bool empty() const {
    return shapes_.empty() && materials_.size() == builtin_materials_.size() && course_lights_ == 0;
  }

  // An integrator (the --integrator door, book 2.3 "A program of one's own"): what estimates the
  // radiance of one camera sample, given the camera ray, the sample's own random stream and a
  // counter of the rays it traces (render.hpp's sample_context). The factory makes it once per
  // render, for the scene and the command line's path options (max_depth, rr_depth, lights).
  // The built-ins naive, nee and mis come through this same call (integrators/integrator_door.hpp).
  using radiance_fn = std::function<rgb(const ray&, rng&, std::uint64_t&)>;
  using integrator_factory = std::function<radiance_fn(const zraka::scene&, const path_options&)>;
  ZRAKA_COMPILED_FN void add_integrator(const std::string& name, integrator_factory make);
  ZRAKA_COMPILED_FN const integrator_factory* integrator_type(const std::string& name) const;
  const std::map<std::string, integrator_factory>& integrators() const { return integrators_; }

  // "sphere, plane, ... or bezier; registered: disk" for an unknown-type message.
  ZRAKA_COMPILED_FN std::string object_types() const;
  ZRAKA_COMPILED_FN std::string material_types() const;
  // "point, quad or sphere; registered: spot" (quad and sphere: shapes that glow, which the
  // lights section makes itself).
  ZRAKA_COMPILED_FN std::string light_types() const;

 private:
  std::map<std::string, entry<shape_factory>> shapes_;
  std::map<std::string, entry<material_factory>> materials_;  // the built-in ones too
  std::vector<std::string> builtin_materials_;  // in the order of builtin.hpp, for messages
  std::vector<std::string> material_order_;     // every material type, in the order registered
  std::map<std::string, entry<light_factory>> lights_;  // the built-in ones too
  std::vector<std::string> builtin_lights_;  // in the order of builtin.hpp, then quad and sphere
  std::vector<std::string> light_order_;     // every light type, in the order registered
  std::size_t course_lights_ = 0;            // of them, registered by a program

  template <class M> static const typename M::mapped_type* find(const M& m, const std::string& type);
  template <class M>
  static void check_name(const std::string& type, const std::vector<std::string>& builtin, const M& registered,
                         const char* what, std::initializer_list<const char*> common,
                         const std::vector<std::string>& keys);
  template <class M> static std::string listing(const std::vector<std::string>& builtin, const M& registered);

  std::map<std::string, integrator_factory> integrators_;  // the integrator door, built-ins apart
};

// The members are compiled once into zraka::compiled (compiled.hpp): the maps' code is then not
// instantiated in every unit that reads a scene.
#if ZRAKA_COMPILED_DEFINITIONS
ZRAKA_COMPILED_FN void scene_registry::add_shape(const std::string& type, std::vector<std::string> keys,
                                                 shape_factory make) {
  check_name(type, builtin_object_types(), shapes_, "object", {"type", "name", "material"}, keys);
  if (!make) throw error("scene registry: the factory for object type '" + type + "' is empty");
  shapes_[type] = {std::move(keys), std::move(make)};
}
ZRAKA_COMPILED_FN void scene_registry::add_material(const std::string& type, std::vector<std::string> keys,
                                                    material_factory make) {
  check_name(type, builtin_materials_, materials_, "material", {"type"}, keys);
  if (!make) throw error("scene registry: the factory for material type '" + type + "' is empty");
  materials_[type] = {std::move(keys), std::move(make)};
  material_order_.push_back(type);
}
ZRAKA_COMPILED_FN void scene_registry::add_light(const std::string& type, std::vector<std::string> keys,
                                                 light_factory make) {
  check_name(type, builtin_lights_, lights_, "light", {"type"}, keys);
  if (!make) throw error("scene registry: the factory for light type '" + type + "' is empty");
  lights_[type] = {std::move(keys), std::move(make)};
  light_order_.push_back(type);
  if (!builtin_lights_.empty()) ++course_lights_;  // the constructor has registered the built-in ones
}
ZRAKA_COMPILED_FN const scene_registry::entry<scene_registry::light_factory>* scene_registry::light_entry(
    const std::string& type) const {
  return find(lights_, type);
}
ZRAKA_COMPILED_FN std::string scene_registry::light_types() const { return listing(builtin_lights_, lights_); }
ZRAKA_COMPILED_FN const scene_registry::entry<scene_registry::shape_factory>* scene_registry::shape(
    const std::string& type) const {
  return find(shapes_, type);
}
ZRAKA_COMPILED_FN const scene_registry::entry<scene_registry::material_factory>* scene_registry::material_type(
    const std::string& type) const {
  return find(materials_, type);
}
ZRAKA_COMPILED_FN std::string scene_registry::object_types() const { return listing(builtin_object_types(), shapes_); }
ZRAKA_COMPILED_FN std::string scene_registry::material_types() const {
  return listing(builtin_materials_, materials_);
}
ZRAKA_COMPILED_FN void scene_registry::add_integrator(const std::string& name, integrator_factory make) {
  check_name(name, {}, integrators_, "integrator", {}, {});
  if (!make) throw error("scene registry: the factory for integrator '" + name + "' is empty");
  integrators_[name] = std::move(make);
}
ZRAKA_COMPILED_FN const scene_registry::integrator_factory* scene_registry::integrator_type(const std::string& name) const {
  return find(integrators_, name);
}

template <class M> const typename M::mapped_type* scene_registry::find(const M& m, const std::string& type) {
  const auto it = m.find(type);
  return it == m.end() ? nullptr : &it->second;
}
// A name is a plain word (what a YAML scalar can be without quotes) and new.
template <class M>
void scene_registry::check_name(const std::string& type, const std::vector<std::string>& builtin, const M& registered,
                                const char* what, std::initializer_list<const char*> common,
                                const std::vector<std::string>& keys) {
  const std::string which = std::string(what) + " type '" + type + "'";
  const bool word = !type.empty() && std::all_of(type.begin(), type.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
  });
  if (!word) throw error("scene registry: " + which + ": a type is a word of a-z, 0-9 and _");
  if (std::find(builtin.begin(), builtin.end(), type) != builtin.end())
    throw error("scene registry: " + which + " is built in; a registered type must have a new name");
  if (registered.count(type)) throw error("scene registry: " + which + " is registered twice");
  for (std::size_t i = 0; i < keys.size(); ++i) {
    for (const char* c : common)
      if (keys[i] == c) throw error("scene registry: " + which + ": key '" + keys[i] + "' is common to every " + what);
    for (std::size_t j = 0; j < i; ++j)
      if (keys[i] == keys[j]) throw error("scene registry: " + which + ": key '" + keys[i] + "' is listed twice");
  }
}
template <class M> std::string scene_registry::listing(const std::vector<std::string>& builtin, const M& registered) {
  std::string s;
  for (std::size_t i = 0; i < builtin.size(); ++i)
    s += (i == 0 ? "" : i + 1 == builtin.size() ? " or " : ", ") + builtin[i];
  bool first = true;
  for (const auto& kv : registered) {
    if (kv.second.builtin) continue;
    s += (first ? "; registered: " : ", ") + kv.first;
    first = false;
  }
  return s;
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

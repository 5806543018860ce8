#pragma once
// Scene files (book 4.1): a short YAML file that gives only what differs from the defaults
// (scenes/README.md lists every key) becomes a zraka::scene.
//
//   const zraka::loaded_scene ls = zraka::load_scene_file("scenes/box.yaml");
//   render with ls.sc;  std::cout << ls.resolved;   // the scene with every default filled in
//
// Strict by design: a student's typo must not silently become a default. An unknown or
// duplicated key, a wrong type, a missing required field, a NaN, an infinite or out-of-range
// number, an unknown material name, a missing file or a degenerate camera or shape each throw
// zraka::error with "FILE:LINE:COLUMN: FIELD: what is wrong" (LINE and COLUMN from yaml-cpp's
// Mark, counted from 1).
//
// The defaults come from the structs themselves (render_settings, camera_t, material, texture,
// point_light_t) and from scene_file_defaults below, so there is one place for each.
// Sizes are bounded by limits() (limits.hpp): YAML nodes after alias expansion, the triangles
// of the whole scene (checked before a mesh is tessellated), pixels and samples, file sizes; and
// every coordinate, also after its transform, lies within max_coordinate.
// Types a program adds (a user shape, a custom BSDF) are read by name through a scene_registry
// (scene_registry.hpp) passed to parse_scene / load_scene_file, with the same checks (scene_node).
// Needs yaml-cpp (link yaml-cpp).
#include <zraka/core/affine.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/image/image.hpp>
#include <zraka/io/bpt.hpp>
#include <zraka/io/obj_file.hpp>
#include <zraka/lights/environment_file.hpp>
#include <zraka/textures/texture_file.hpp>
// PLY and glTF meshes (mesh_file.hpp) where zraka::compiled was built with assimp, or header-only
// with ZRAKA_WITH_ASSIMP (the program then links assimp); otherwise a mesh is OBJ only.
#if defined(ZRAKA_COMPILED_MESH_FILE) || defined(ZRAKA_WITH_ASSIMP)
#include <zraka/io/mesh_file.hpp>
#define ZRAKA_SCENE_MESH_FILES 1
#else
#define ZRAKA_SCENE_MESH_FILES 0
#endif
#include <zraka/geometry/tessellate.hpp>
#include <zraka/lights/builtin.hpp>
#include <zraka/materials/builtin.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <yaml-cpp/depthguard.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

// Reading a scene is compiled once into zraka::compiled when zraka is built with yaml-cpp
// (ZRAKA_COMPILED_SCENE_FILE, see compiled.hpp): ~60% of a scene-loading chapter's object code.
// Under it the readers below are only declared: a program's unit then parses none of their
// ~1000 lines nor instantiates what they use (about 1.3 CPU-s of each scene-loading chapter).
// The resource root is an argument: only the program knows its own (ZRAKA_RESOURCE_DIR).
#if defined(ZRAKA_COMPILED_SCENE_FILE)
#define ZRAKA_SCENE_FILE_FN
#else
#define ZRAKA_SCENE_FILE_FN inline
#endif
#if !defined(ZRAKA_COMPILED_SCENE_FILE) || defined(ZRAKA_COMPILING)
#define ZRAKA_SCENE_FILE_DEFINITIONS 1
#else
#define ZRAKA_SCENE_FILE_DEFINITIONS 0
#endif
namespace zraka {

// Defaults that belong to no struct.
struct scene_file_defaults {
  static constexpr double sphere_radius = 1.0;
  static constexpr float area_light_radiance = material_kinds::emitter::default_radiance;
  static constexpr int bezier_divs = 8;
  static constexpr int max_spp = 65536;
  static constexpr int max_depth = 64;
  static constexpr std::size_t object_bvh_threshold = 4;  // an object BVH above this many (book 4.1 measures it)
};

struct loaded_scene {
  scene sc;
  std::string resolved;  // YAML: the scene with every default filled in
};

namespace detail {

// The OBJ reader moved to obj_file.hpp (issue 12); the old name stays for callers.
using zraka::load_obj;

class scene_reader;

}  // namespace detail

// [listing scene-node]
// What a registered type's factory (scene_registry.hpp) reads its entry with: the readers of the
// built-in types, by key. Each checks what a built-in field is checked for (a finite number, a
// point [x, y, z], a colour not negative, a unit direction that is not zero) and throws
// "FILE:LINE:COLUMN: objects[2].radius: ..." when it is wrong; the variants without a fallback
// make the field required. What is read, fallbacks included, goes into the resolved scene.
class scene_node {
 public:
  const std::string& type() const { return type_; }
  bool has(const std::string& key) const { return bool(get(key)); }
  double number(const std::string& key) const;
  double number(const std::string& key, double fallback) const;
  long long integer(const std::string& key, long long lo, long long hi, long long fallback) const;
  vec3 point(const std::string& key) const;
  vec3 point(const std::string& key, const vec3& fallback) const;
  vec3 direction(const std::string& key) const;  // normalised; zero is an error
  vec3 direction(const std::string& key, const vec3& fallback) const;
  rgb colour(const std::string& key) const;
  rgb colour(const std::string& key, const rgb& fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
  int medium(const std::string& key) const;  // a name in the media section; its index
  bool is_map(const std::string& key) const;
  std::string scalar(const std::string& key) const;  // the field as written, for messages
  // An error at the field (or at the entry, if the field is absent): "must be positive".
  [[noreturn]] void fail(const std::string& key, const std::string& what) const;
  [[noreturn]] void fail(const std::string& what) const;  // at the entry
  std::string field(const std::string& key) const { return path_ + "." + key; }
  // A colour or a texture, as a material's albedo: {checker: ...}, {image: ...}, {noise: ...}.
  zraka::texture texture(const std::string& key) const;
  // [end]

 private:
  friend class detail::scene_reader;  // the only one that makes them
  scene_node(const detail::scene_reader& r, YAML::Node n, std::string path, std::string type,
             const std::vector<std::string>& keys, YAML::Node resolved)
      : r_(r), n_(std::move(n)), path_(std::move(path)), type_(std::move(type)), keys_(keys), resolved_(resolved) {}
  const detail::scene_reader& r_;
  YAML::Node n_;
  std::string path_, type_;
  const std::vector<std::string>& keys_;
  mutable YAML::Node resolved_;  // a handle: writes go to the resolved entry
  YAML::Node get(const std::string& key) const;
  YAML::Node need(const std::string& key) const;
};

#if ZRAKA_SCENE_FILE_DEFINITIONS
namespace detail {

class scene_reader {
 public:
  // `root`: the resource root (resources.hpp), passed in, see parse_scene.
  scene_reader(std::string name, std::filesystem::path dir, const scene_registry& reg, std::filesystem::path root)
      : name_(std::move(name)), dir_(std::move(dir)), root_(std::move(root)), registry_(reg) {}

  loaded_scene read(const std::string& text) {
    YAML::Node loaded;
    try {
      loaded = YAML::Load(text);
    } catch (const YAML::DeepRecursion& e) {
      throw error(where(e.mark) + "YAML nesting deeper than " + std::to_string(e.depth() - 1) + " levels");
    } catch (const YAML::Exception& e) {  // ParserException, DeepRecursion (nesting beyond yaml-cpp's 2000)
      throw error(where(e.mark) + "YAML syntax: " + e.msg);
    }
    const YAML::Node& root = loaded;  // const: looking up a key must not add it
    check_yaml_size(root);
    if (!root || root.IsNull()) throw error(name_ + ": the scene file is empty");
    if (!root.IsMap()) fail(root, "", "a scene file is a map with the sections settings, camera, materials, lights, objects");
    keys(root, "", {"settings", "camera", "media", "materials", "lights", "objects", "environment"});

    media(root["media"]);  // first: settings and materials name media
    settings(root["settings"]);
    environment(root["environment"], root);
    camera(root["camera"]);
    materials(root["materials"]);
    lights(root["lights"]);
    objects(root["objects"], root);
    out_.sc.build_acceleration(scene_file_defaults::object_bvh_threshold);

    YAML::Emitter em;
    em << resolved_;
    out_.resolved = em.c_str();
    return std::move(out_);
  }

 private:
  friend class zraka::scene_node;
  std::string name_;
  std::filesystem::path dir_;
  std::filesystem::path root_;
  scene_registry registry_;  // a copy: a temporary registry may be passed
  std::map<int, YAML::Node> registered_resolved_;  // material index -> its resolved entry
  loaded_scene out_;
  YAML::Node resolved_;
  std::map<std::string, int> material_index_;
  std::map<std::string, int> medium_index_;
  std::uint64_t triangles_ = 0;  // so far, against limits().triangles

  // ---------------------------------------------------------------- errors
  std::string where(const YAML::Mark& m) const {
    if (m.is_null()) return name_ + ": ";
    return name_ + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1) + ": ";
  }
  [[noreturn]] void fail(const YAML::Node& n, const std::string& field, const std::string& what) const {
    throw error(where(n.Mark()) + (field.empty() ? "" : field + ": ") + what);
  }
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string scalar_text(const YAML::Node& n) {
    if (n.IsScalar()) return "'" + n.Scalar() + "'";
    if (n.IsSequence() && n.size() == 0) return "an empty list";
    return n.IsSequence() ? "a list" : n.IsMap() ? "a map" : "nothing";
  }

  // ---------------------------------------------------------------- limits
  // Counts the nodes as a reader walking the tree meets them: an alias counts each time it is
  // used, so a few lines that double at every level (the "billion laughs") stop here, not in the
  // memory; an alias inside its own anchor (a cycle) stops here too.
  void check_yaml_size(const YAML::Node& root) const {
    const std::uint64_t limit = limits().yaml_nodes;
    std::uint64_t count = 0;
    std::vector<YAML::Node> todo{root};
    while (!todo.empty()) {
      const YAML::Node n = todo.back();
      todo.pop_back();
      ++count;
      const std::uint64_t children = n.IsSequence() ? n.size() : n.IsMap() ? 2 * n.size() : 0;
      if (count + todo.size() + children > limit)
        fail(n, "", "the scene has more than " + std::to_string(limit) +
                        " YAML nodes (an alias counts each time it is used) " + raise_hint("yaml_nodes"));
      if (n.IsSequence())
        for (const auto& c : n) todo.push_back(c);
      else if (n.IsMap())
        for (const auto& kv : n) todo.push_back(kv.first), todo.push_back(kv.second);
    }
  }
  // Every triangle of the scene counts against limits().triangles, before it is made.
  void add_triangles(std::uint64_t n, const YAML::Node& at, const std::string& field) {
    const std::uint64_t limit = limits().triangles;
    if (n > limit || triangles_ > limit - n)
      fail(at, field, "the scene would have " + std::to_string(triangles_ + n) + " triangles, more than the limit of " +
                          std::to_string(limit) + " " + raise_hint("triangles"));
    triangles_ += n;
  }
  // A point or vector after its transform: finite and within max_coordinate.
  template <class V> void check_placed(const V& v, const YAML::Node& at, const std::string& field) const {
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(double(v[i])) <= max_coordinate))
        fail(at, field, "after the transform a coordinate is " + num(double(v[i])).Scalar() +
                            ", beyond +-1e18 (its square would overflow)");
  }

  // [listing strict-keys]
  // Every key of map n must be one of `allowed`, and appear once.
  void keys(const YAML::Node& n, const std::string& path, std::initializer_list<const char*> allowed) const {
    if (!n.IsMap()) fail(n, path, "expected a map ({key: value, ...}), got " + scalar_text(n));
    std::set<std::string> seen;
    for (const auto& kv : n) {
      const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : "?";
      if (!seen.insert(k).second) fail(kv.first, join(path, k), "duplicate key");
      bool ok = false;
      std::string list;
      for (const char* a : allowed) {
        ok = ok || k == a;
        list += (list.empty() ? "" : ", ") + std::string(a);
      }
      if (!ok) fail(kv.first, join(path, k), "unknown key (expected one of: " + list + ")");
    }
  }
  // [end]

  // ---------------------------------------------------------------- values
  double number(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar()) fail(n, field, "expected a number, got " + scalar_text(n));
    double x;
    try {
      x = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, field, "expected a number, got " + scalar_text(n));
    }
    if (!std::isfinite(x)) fail(n, field, "must be finite, got " + n.Scalar());
    if (std::abs(x) > max_coordinate) fail(n, field, "must be within +-1e18 (its square would overflow), got " + n.Scalar());
    return x;
  }
  bool boolean(const YAML::Node& n, const std::string& field) const {
    if (n.IsScalar()) {
      const std::string v = n.Scalar();
      if (v == "true") return true;
      if (v == "false") return false;
    }
    fail(n, field, "expected true or false, got " + scalar_text(n));
  }
  long long integer(const YAML::Node& n, const std::string& field, long long lo, long long hi) const {
    if (!n.IsScalar()) fail(n, field, "expected an integer, got " + scalar_text(n));
    long long x;
    try {
      x = n.as<long long>();
    } catch (const YAML::Exception&) {
      fail(n, field, "expected an integer, got " + scalar_text(n));
    }
    if (x < lo || x > hi)
      fail(n, field, "must be in " + std::to_string(lo) + ".." + std::to_string(hi) + ", got " + n.Scalar());
    return x;
  }
  vec3 vector3(const YAML::Node& n, const std::string& field) const {
    if (!n.IsSequence() || n.size() != 3) fail(n, field, "expected [x, y, z], got " + scalar_text(n));
    return {number(n[0], field + "[0]"), number(n[1], field + "[1]"), number(n[2], field + "[2]")};
  }
  rgb colour(const YAML::Node& n, const std::string& field) const {
    vec3 c;
    if (n.IsScalar()) c = vec3(number(n, field));
    else if (n.IsSequence() && n.size() == 3) c = vector3(n, field);
    else fail(n, field, "expected a colour: a number or [r, g, b], got " + scalar_text(n));
    if (c.x < 0 || c.y < 0 || c.z < 0) fail(n, field, "a colour must not be negative");
    return rgb(c);
  }
  std::string text(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar()) fail(n, field, "expected a name, got " + scalar_text(n));
    return n.Scalar();
  }
  // By value: assigning yaml-cpp nodes rebinds what they refer to, copying does not.
  YAML::Node required(const YAML::Node& map, const char* key, const std::string& path) const {
    const YAML::Node found = map[key];
    if (!found) fail(map, join(path, key), "required, but missing");
    return found;
  }

  // A number as a person would type it: 7 significant digits (yaml-cpp would write all 17 of
  // the binary value, 0.60000002384185791 for a float 0.6).
  static YAML::Node num(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.7g", x);
    return YAML::Node(std::string(buf));
  }
  static YAML::Node flow(const vec3& v) {
    YAML::Node s;
    for (int i = 0; i < 3; ++i) s.push_back(num(v[i]));
    s.SetStyle(YAML::EmitterStyle::Flow);
    return s;
  }
  static YAML::Node flow(const rgb& c) { return flow(vec3(c)); }

  // ---------------------------------------------------------------- sections
  void settings(const YAML::Node& n) {
    render_settings& s = out_.sc.settings;
    if (n) {
      keys(n, "settings", {"width", "height", "spp", "max_depth", "seed", "background", "ambient", "medium", "integrator"});
      if (n["medium"]) out_.sc.global_medium = medium_named(n["medium"], "settings.medium");
      const long long big = 1LL << 40;
      if (n["width"]) s.width = int(integer(n["width"], "settings.width", 1, image::max_side));
      if (n["height"]) s.height = int(integer(n["height"], "settings.height", 1, image::max_side));
      if (n["spp"]) s.spp = int(integer(n["spp"], "settings.spp", 1, scene_file_defaults::max_spp));
      if (n["max_depth"])
        s.max_depth = int(integer(n["max_depth"], "settings.max_depth", 1, scene_file_defaults::max_depth));
      if (n["seed"]) s.seed = std::uint64_t(integer(n["seed"], "settings.seed", 0, big));
      if (n["background"]) out_.sc.background = colour(n["background"], "settings.background");
      if (n["ambient"]) out_.sc.ambient = colour(n["ambient"], "settings.ambient");
      // Looked up by the program that renders (integrators/integrator_door.hpp): its registry has the course's.
      if (n["integrator"]) s.integrator = text(n["integrator"], "settings.integrator");
      try {
        image::check_size(s.width, s.height);
        check_render_size(s.width, s.height, s.spp);
      } catch (const error& e) {
        fail(n, "settings", e.what());
      }
    }
    YAML::Node r = resolved_["settings"];
    r["width"] = s.width;
    r["height"] = s.height;
    r["spp"] = s.spp;
    r["max_depth"] = s.max_depth;
    r["seed"] = s.seed;
    r["background"] = flow(out_.sc.background);
    r["ambient"] = flow(out_.sc.ambient);
    if (!s.integrator.empty()) r["integrator"] = s.integrator;
    if (out_.sc.global_medium >= 0) r["medium"] = out_.sc.media[std::size_t(out_.sc.global_medium)].name;
  }

  // [listing media-section]
  // media: {fog: {sigma_a: 0.01, sigma_s: [0.1, 0.1, 0.12], g: 0.3,
  //               density: {min: [..], max: [..], resolution: 24, frequency: 2.5, seed: 1}}}
  // A density makes the medium heterogeneous: sigma times a noise cloud in [0, 1] over the box.
  void media(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsMap()) fail(n, "media", "expected a map of name: {sigma_a, sigma_s, g, density}, got " + scalar_text(n));
    for (const auto& kv : n) {
      if (!kv.first.IsScalar()) fail(kv.first, "media", "a medium name must be a plain word");
      const std::string name = kv.first.Scalar(), path = "media." + name;
      if (medium_index_.count(name)) fail(kv.first, path, "duplicate name");
      const YAML::Node m = kv.second;
      keys(m, path, {"sigma_a", "sigma_s", "g", "density"});
      medium md;
      md.name = name;
      if (m["sigma_a"]) md.sigma_a = colour(m["sigma_a"], path + ".sigma_a");
      if (m["sigma_s"]) md.sigma_s = colour(m["sigma_s"], path + ".sigma_s");
      if (m["g"]) {
        md.g = number(m["g"], path + ".g");
        if (!(md.g > -1 && md.g < 1)) fail(m["g"], path + ".g", "must be in (-1, 1), got " + m["g"].Scalar());
      }
      YAML::Node r;
      r["sigma_a"] = flow(md.sigma_a);
      r["sigma_s"] = flow(md.sigma_s);
      r["g"] = num(md.g);
      if (const YAML::Node d = m["density"]) {
        const std::string dp = path + ".density";
        keys(d, dp, {"min", "max", "resolution", "frequency", "seed"});
        const vec3 lo = vector3(required(d, "min", dp), dp + ".min"), hi = vector3(required(d, "max", dp), dp + ".max");
        if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) fail(d, dp, "min must be below max on every axis");
        const int res = d["resolution"] ? int(integer(d["resolution"], dp + ".resolution", 2, 256)) : 24;
        const double freq = d["frequency"] ? number(d["frequency"], dp + ".frequency") : 2.5;
        if (!(freq > 0 && freq <= 64)) fail(d["frequency"], dp + ".frequency", "must be in (0, 64]");
        const auto seed = std::uint64_t(d["seed"] ? integer(d["seed"], dp + ".seed", 0, 1LL << 40) : 1);
        md.density = std::make_shared<density_grid>(density_grid::noise(aabb{lo, hi}, res, freq, seed));
        YAML::Node rd;
        rd["min"] = flow(lo);
        rd["max"] = flow(hi);
        rd["resolution"] = res;
        rd["frequency"] = num(freq);
        rd["seed"] = seed;
        r["density"] = rd;
      }
      try {
        md.check();
      } catch (const error& e) {
        fail(m, path, e.what());
      }
      medium_index_[name] = out_.sc.add_medium(md);
      resolved_["media"][name] = r;
    }
  }
  int medium_named(const YAML::Node& n, const std::string& field) const {
    const std::string name = text(n, field);
    const auto it = medium_index_.find(name);
    if (it == medium_index_.end()) {
      std::string list;
      for (const auto& [k, v] : medium_index_) list += (list.empty() ? "" : ", ") + k;
      fail(n, field, "unknown medium '" + name + "' (the media section has: " + (list.empty() ? "none" : list) + ")");
    }
    return it->second;
  }
  // [end]

  // [listing scene-environment]
  // environment: {file: sky.hdr, scale: 1, rotate: 0}  or  {color: [r, g, b], scale: 1}
  void environment(const YAML::Node& n, const YAML::Node& root) {
    if (!n) return;
    if (!n.IsMap()) fail(n, "environment", "expected {file: ..., scale: ..., rotate: ...} or {color: [r, g, b]}, got " + scalar_text(n));
    keys(n, "environment", {"file", "color", "scale", "rotate"});
    if (bool(n["file"]) == bool(n["color"])) fail(n, "environment", "give exactly one of file and color");
    if (root["settings"] && root["settings"]["background"])
      fail(root["settings"]["background"], "settings.background",
           "the scene has an environment, which rays that leave the scene see; give one or the other");
    const double scale = n["scale"] ? number(n["scale"], "environment.scale") : 1.0;
    if (scale < 0) fail(n["scale"], "environment.scale", "must not be negative, got " + n["scale"].Scalar());
    const double rotate = n["rotate"] ? number(n["rotate"], "environment.rotate") : 0.0;
    YAML::Node r = resolved_["environment"];
    if (n["color"]) {
      const rgb c = colour(n["color"], "environment.color");
      out_.sc.environment = std::make_shared<environment_map>(environment_map::constant(c, float(scale), rotate));
      r["color"] = flow(c);
    } else {
      const std::filesystem::path file = find_file(n["file"], "environment.file");
      try {
        out_.sc.environment = std::make_shared<environment_map>(load_environment(file, float(scale), rotate));
      } catch (const error& e) {  // name the file as the scene does, not by its full path
        std::string msg = e.what();
        if (msg.rfind(file.string(), 0) == 0) msg = n["file"].Scalar() + msg.substr(file.string().size());
        fail(n["file"], "environment.file", msg);
      }
      r["file"] = n["file"].Scalar();
    }
    r["scale"] = num(scale);
    r["rotate"] = num(rotate);
    resolved_["settings"].remove("background");  // the resolved scene must load again
  }
  // [end]

  void camera(const YAML::Node& n) {
    camera_t<double>& c = out_.sc.camera;
    if (n) {
      keys(n, "camera", {"position", "look_at", "up", "vfov", "aperture", "focus_distance"});
      if (n["position"]) c.position = vector3(n["position"], "camera.position");
      if (n["look_at"]) c.look_at = vector3(n["look_at"], "camera.look_at");
      if (n["up"]) c.up = vector3(n["up"], "camera.up");
      if (n["vfov"]) c.vfov_degrees = number(n["vfov"], "camera.vfov");
      if (n["aperture"]) c.aperture = number(n["aperture"], "camera.aperture");
      if (n["focus_distance"]) c.focus_distance = number(n["focus_distance"], "camera.focus_distance");
    }
    try {
      const auto p = out_.sc.prepared_camera();  // throws for a camera that defines no view
      for (const vec3& v : {p.corner, p.horizontal, p.vertical})
        if (!is_finite(v) || std::abs(v.x) > max_coordinate || std::abs(v.y) > max_coordinate ||
            std::abs(v.z) > max_coordinate)
          throw error("the image plane reaches beyond +-1e18 (focus_distance or the distance to look_at too large)");
    } catch (const error& e) {
      std::string msg = e.what();
      if (msg.rfind("camera: ", 0) == 0) msg = msg.substr(8);
      fail(n ? n : YAML::Node(), "camera", msg);
    }
    YAML::Node r = resolved_["camera"];
    r["position"] = flow(c.position);
    r["look_at"] = flow(c.look_at);
    r["up"] = flow(c.up);
    r["vfov"] = num(c.vfov_degrees);
    r["aperture"] = num(c.aperture);
    r["focus_distance"] = num(c.focus_distance);
  }

  // [listing scene-texture]
  // albedo: a colour, {checker: {even, odd, scale, space}}, {image: {file, srgb, wrap}} or
  // {noise: {low, high, frequency, octaves, marble}}
  texture albedo(const YAML::Node& n, const std::string& field) const {
    if (!n.IsMap()) return texture::solid(colour(n, field));
    if (n.size() == 1 && n["image"]) return image_texture(n["image"], field + ".image");
    if (n.size() == 1 && n["noise"]) return noise_texture(n["noise"], field + ".noise");
    if (n.size() != 1 || !n["checker"])
      fail(n, field, "expected a colour, {checker: {...}}, {image: {file, ...}} or {noise: {...}}");
    const YAML::Node c = n["checker"];
    keys(c, field + ".checker", {"even", "odd", "scale", "space"});
    texture t = texture::checker(texture{}.a, texture{}.b, texture{}.cell);
    if (c["even"]) t.a = colour(c["even"], field + ".checker.even");
    if (c["odd"]) t.b = colour(c["odd"], field + ".checker.odd");
    if (c["scale"]) {
      t.cell = number(c["scale"], field + ".checker.scale");
      if (!(t.cell > 0)) fail(c["scale"], field + ".checker.scale", "must be positive");
    }
    if (c["space"]) {  // world (the default) or uv: the hit's surface coordinates
      const std::string space = text(c["space"], field + ".checker.space");
      if (space != "world" && space != "uv") fail(c["space"], field + ".checker.space", "must be world or uv, got '" + space + "'");
      t.uv_space = space == "uv";
    }
    return t;
  }
  texture image_texture(const YAML::Node& n, const std::string& field) const {
    if (!n.IsMap()) fail(n, field, "expected {file: ..., srgb: true, wrap: repeat}, got " + scalar_text(n));
    keys(n, field, {"file", "srgb", "wrap"});
    const YAML::Node f = required(n, "file", field);
    const std::filesystem::path file = find_file(f, field + ".file");
    const bool srgb = n["srgb"] ? boolean(n["srgb"], field + ".srgb") : true;
    const std::string wrap = n["wrap"] ? text(n["wrap"], field + ".wrap") : "repeat";
    if (wrap != "repeat" && wrap != "clamp") fail(n["wrap"], field + ".wrap", "must be repeat or clamp, got '" + wrap + "'");
    try {
      texture t = texture::image_map(std::make_shared<const image>(load_texture_image(file, srgb)), wrap == "repeat",
                                     f.Scalar());
      t.srgb = srgb;
      return t;
    } catch (const error& e) {  // name the file as the scene does, not by its full path
      std::string msg = e.what();
      if (msg.rfind(file.string(), 0) == 0) msg = f.Scalar() + msg.substr(file.string().size());
      fail(f, field + ".file", msg);
    }
  }
  texture noise_texture(const YAML::Node& n, const std::string& field) const {
    if (!n.IsMap()) fail(n, field, "expected {low, high, frequency, octaves, marble}, got " + scalar_text(n));
    keys(n, field, {"low", "high", "frequency", "octaves", "marble"});
    texture t = texture::noise(rgb(0.1f), rgb(0.9f), 4.0, 1, false);
    if (n["low"]) t.a = colour(n["low"], field + ".low");
    if (n["high"]) t.b = colour(n["high"], field + ".high");
    if (n["frequency"]) {
      t.frequency = number(n["frequency"], field + ".frequency");
      if (!(t.frequency > 0 && t.frequency <= 1e6)) fail(n["frequency"], field + ".frequency", "must be in (0, 1e6]");
    }
    if (n["octaves"]) t.octaves = int(integer(n["octaves"], field + ".octaves", 1, 16));
    if (n["marble"]) t.marble = boolean(n["marble"], field + ".marble");
    return t;
  }
  // [end]
  static YAML::Node albedo_node(const texture& t) {
    if (t.type == texture::kind::solid) return flow(t.a);
    if (t.type == texture::kind::image) {
      YAML::Node n, c;
      c["file"] = t.source;
      c["srgb"] = t.srgb;
      c["wrap"] = t.repeat ? "repeat" : "clamp";
      n["image"] = c;
      n.SetStyle(YAML::EmitterStyle::Flow);
      return n;
    }
    if (t.type == texture::kind::noise) {
      YAML::Node n, c;
      c["low"] = flow(t.a);
      c["high"] = flow(t.b);
      c["frequency"] = num(t.frequency);
      c["octaves"] = t.octaves;
      c["marble"] = t.marble;
      n["noise"] = c;
      n.SetStyle(YAML::EmitterStyle::Flow);
      return n;
    }
    YAML::Node n, c;
    c["even"] = flow(t.a);
    c["odd"] = flow(t.b);
    c["scale"] = num(t.cell);
    if (t.uv_space) c["space"] = "uv";
    n["checker"] = c;
    n.SetStyle(YAML::EmitterStyle::Flow);
    return n;
  }

  // What a material kind's write() (materials/) fills the resolved scene's entry with.
  struct resolved_writer {
    const scene_reader& r;
    YAML::Node& node;
    void number(const char* key, double x) { node[key] = num(x); }
    void colour(const char* key, const rgb& c) { node[key] = flow(c); }
    void texture(const char* key, const zraka::texture& t) { node[key] = albedo_node(t); }
    void medium(const char* key, int index) { node[key] = r.out_.sc.media[std::size_t(index)].name; }
  };

  void materials(const YAML::Node& n) {
    out_.sc.add_material(material{});  // "default"
    out_.sc.material_names.push_back("default");
    material_index_["default"] = 0;
    if (n) {
      if (!n.IsMap()) fail(n, "materials", "expected a map of name: {type: ..., ...}, got " + scalar_text(n));
      keys_any(n, "materials");
      for (const auto& kv : n) {
        const std::string name = kv.first.Scalar();
        if (name == "from-file")
          fail(kv.first, "materials.from-file", "the name is reserved: a mesh's 'material: from-file' takes its file's material");
        const int index = material_index_.count(name) ? material_index_[name] : out_.sc.add_material(material{});
        if (!material_index_.count(name)) out_.sc.material_names.push_back(name);
        material_index_[name] = index;
        registered_resolved_.erase(index);
        out_.sc.materials[std::size_t(index)] = one_material(kv.second, "materials." + name, index);
      }
    }
    for (std::size_t i = 0; i < out_.sc.material_names.size(); ++i) {
      const material& m = out_.sc.materials[i];
      YAML::Node r;
      if (const auto it = registered_resolved_.find(int(i)); it != registered_resolved_.end()) {
        resolved_["materials"][out_.sc.material_names[i]] = it->second;
        continue;
      }
      r["type"] = kind_name(m.kind);
      std::visit([&](const auto& k) {
        if constexpr (requires { k.write(std::declval<resolved_writer&>(), m); }) {
          resolved_writer w{*this, r};
          k.write(w, m);
        }
      }, m.kind);
      r.SetStyle(YAML::EmitterStyle::Flow);
      resolved_["materials"][out_.sc.material_names[i]] = r;
    }
  }
  // A map whose keys are names (materials): only duplicates are errors.
  void keys_any(const YAML::Node& n, const std::string& path) const {
    std::set<std::string> seen;
    for (const auto& kv : n) {
      if (!kv.first.IsScalar()) fail(kv.first, path, "a material name must be a plain word");
      if (!seen.insert(kv.first.Scalar()).second) fail(kv.first, join(path, kv.first.Scalar()), "duplicate name");
    }
  }

  material one_material(const YAML::Node& n, const std::string& path, int index) {
    if (!n.IsMap()) fail(n, path, "expected {type: ..., ...}, got " + scalar_text(n));
    const std::string type = n["type"] ? text(n["type"], path + ".type") : "lambertian";
    const auto* reg = registry_.material_type(type);  // the built-in ones too (materials/builtin.hpp)
    if (!reg) fail(n["type"], path + ".type", "unknown material type '" + type + "' (expected " + registry_.material_types() + ")");
    return registered_material(n, path, type, *reg, index);
  }

  void lights(const YAML::Node& n) {
    if (!n) return;
    if (!n.IsSequence()) fail(n, "lights", "expected a list (- {type: point, ...}), got " + scalar_text(n));
    for (std::size_t i = 0; i < n.size(); ++i) {
      const YAML::Node l = n[i];
      const std::string path = "lights[" + std::to_string(i) + "]";
      if (!l.IsMap()) fail(l, path, "expected {type: ..., ...}, got " + scalar_text(l));
      const std::string type = text(required(l, "type", path), path + ".type");
      YAML::Node r;
      r["type"] = type;
      if (type == "quad" || type == "sphere") {  // shapes that glow, made here
        material m = material::emitter(rgb(scene_file_defaults::area_light_radiance));
        if (type == "quad") {
          keys(l, path, {"type", "corner", "u", "v", "radiance"});
        } else {
          keys(l, path, {"type", "center", "radius", "radiance"});
        }
        if (l["radiance"]) m.radiance = colour(l["radiance"], path + ".radiance");
        const int mat = out_.sc.add_material(m);
        out_.sc.material_names.push_back("");
        if (type == "quad") {
          const quad q = quad_of(l, path);
          out_.sc.add(q, mat);
          r["corner"] = flow(q.corner);
          r["u"] = flow(q.u);
          r["v"] = flow(q.v);
        } else {
          const vec3 c = l["center"] ? vector3(l["center"], path + ".center") : vec3(0);
          const double rad = radius(required(l, "radius", path), path + ".radius");
          out_.sc.add(sphere{c, rad}, mat);
          r["center"] = flow(c);
          r["radius"] = num(rad);
        }
        r["radiance"] = flow(m.radiance);
      } else if (const auto* reg = registry_.light_entry(type)) {  // lights/builtin.hpp's and a course's
        strict_keys(l, path, reg->builtin ? "" : type, {"type"}, reg->keys);
        light made;
        located(l, path, [&] { made = reg->make(scene_node(*this, l, path, type, reg->keys, r)); });
        out_.sc.add(std::move(made));
      } else {
        fail(l["type"], path + ".type", "unknown light type '" + type + "' (expected " + registry_.light_types() + ")");
      }
      r.SetStyle(YAML::EmitterStyle::Flow);
      resolved_["lights"].push_back(r);
    }
  }

  double radius(const YAML::Node& n, const std::string& field) const {
    const double r = number(n, field);
    if (!(r > 0)) fail(n, field, "must be positive, got " + n.Scalar());
    return r;
  }
  quad quad_of(const YAML::Node& n, const std::string& path) const {
    const quad q{vector3(required(n, "corner", path), path + ".corner"), vector3(required(n, "u", path), path + ".u"),
                 vector3(required(n, "v", path), path + ".v")};
    if (!q.valid()) fail(n, path, "u and v are parallel (or zero): the quad has no area");
    return q;
  }

  // scale, then rotate, then translate.
  affine transform(const YAML::Node& n, const std::string& path, vec3& scale_out) {
    keys(n, path, {"scale", "rotate", "translate"});
    affine a;
    vec3 s(1);
    if (n["scale"]) {
      s = n["scale"].IsSequence() ? vector3(n["scale"], path + ".scale") : vec3(number(n["scale"], path + ".scale"));
      if (s.x == 0 || s.y == 0 || s.z == 0) fail(n["scale"], path + ".scale", "a scale must not be zero");
      a = affine::scale(s);
    }
    if (n["rotate"]) {
      const YAML::Node r = n["rotate"];
      keys(r, path + ".rotate", {"axis", "degrees"});
      const vec3 axis = vector3(required(r, "axis", path + ".rotate"), path + ".rotate.axis");
      if (normalize_or_zero(axis) == vec3(0)) fail(r["axis"], path + ".rotate.axis", "the axis must not be zero");
      const double deg = number(required(r, "degrees", path + ".rotate"), path + ".rotate.degrees");
      a = affine::rotate(normalize_or_zero(axis), deg * pi<double> / 180) * a;
    }
    if (n["translate"]) a = affine::translate(vector3(n["translate"], path + ".translate")) * a;
    scale_out = s;
    return a;
  }

  // [listing find-file]
  std::filesystem::path find_file(const YAML::Node& n, const std::string& field) const {
    const std::filesystem::path p(text(n, field));
    if (p.is_absolute()) {
      if (std::filesystem::exists(p)) return p;
      fail(n, field, "file " + p.string() + " not found");
    }
    for (const auto& base : {dir_, root_, root_ / "scenes"})
      if (std::filesystem::exists(base / p)) return base / p;
    fail(n, field, "file '" + p.string() + "' not found (looked next to the scene file, in " +
                       root_.string() + " and in its scenes/)");
  }
  // [end]

  void objects(const YAML::Node& n, const YAML::Node& root) {
    if (!n) fail(root, "objects", "the scene has no objects: add a list 'objects:'");
    if (!n.IsSequence() || n.size() == 0)
      fail(n, "objects", "expected a non-empty list (- {type: sphere, ...}), got " + scalar_text(n));
    for (std::size_t i = 0; i < n.size(); ++i) one_object(n[i], "objects[" + std::to_string(i) + "]");
  }

  void one_object(const YAML::Node& o, const std::string& path) {
    if (!o.IsMap()) fail(o, path, "expected {type: ..., ...}, got " + scalar_text(o));
    const std::string type = text(required(o, "type", path), path + ".type");
    static const std::map<std::string, std::vector<const char*>> own = {
        {"sphere", {"center", "radius"}}, {"plane", {"point", "normal"}}, {"triangle", {"a", "b", "c"}},
        {"quad", {"corner", "u", "v"}},   {"box", {"min", "max"}},        {"mesh", {"file"}},
        {"bezier", {"file", "divs"}}};
    const auto it = own.find(type);
    if (it == own.end()) {
      if (const auto* reg = registry_.shape(type)) return registered_object(o, path, type, *reg);
      fail(o["type"], path + ".type", "unknown object type '" + type + "' (expected " + registry_.object_types() + ")");
    }
    {
      std::set<std::string> seen;
      std::string list = "type, name, material, transform";
      for (const char* k : it->second) list += std::string(", ") + k;
      for (const auto& kv : o) {
        const std::string k = kv.first.Scalar();
        if (!seen.insert(k).second) fail(kv.first, join(path, k), "duplicate key");
        bool ok = k == "type" || k == "name" || k == "material" || k == "transform";
        for (const char* a : it->second) ok = ok || k == a;
        if (!ok) fail(kv.first, join(path, k), "unknown key for a " + type + " (expected one of: " + list + ")");
      }
    }
    YAML::Node r;
    r["type"] = type;
    std::string label = path, mat_name;
    int mat = object_material(o, path, r, label, mat_name, type == "mesh");  // -1: from-file
    vec3 s(1);
    affine a;
    if (o["transform"]) a = transform(o["transform"], label + ".transform", s);
    scene& sc = out_.sc;

    if (type == "sphere") {
      const vec3 c = o["center"] ? vector3(o["center"], label + ".center") : vec3(0);
      const double rad = o["radius"] ? radius(o["radius"], label + ".radius") : scene_file_defaults::sphere_radius;
      if (!(std::abs(s.x) == std::abs(s.y) && std::abs(s.y) == std::abs(s.z)))
        fail(o["transform"], label + ".transform.scale", "a sphere takes only a uniform scale");
      const sphere sp{a.point(c), rad * std::abs(s.x)};
      check_placed(sp.center, o, label + ".center");
      check_placed(vec3(sp.radius), o, label + ".radius");
      sc.add(sp, mat);
      r["center"] = flow(c);
      r["radius"] = num(rad);
    } else if (type == "plane") {
      const vec3 p = o["point"] ? vector3(o["point"], label + ".point") : vec3(0);
      const vec3 nn = o["normal"] ? vector3(o["normal"], label + ".normal") : vec3(0, 1, 0);
      if (normalize_or_zero(nn) == vec3(0)) fail(o["normal"], label + ".normal", "the normal must not be zero");
      check_placed(a.point(p), o, label + ".point");
      if (normalize_or_zero(a.normal(nn)) == vec3(0)) fail(o, label + ".normal", "the transformed normal is zero or not finite");
      sc.add(plane::from_point_normal(a.point(p), a.normal(nn)), mat);
      r["point"] = flow(p);
      r["normal"] = flow(nn);
    } else if (type == "triangle") {
      const triangle t{vector3(required(o, "a", label), label + ".a"), vector3(required(o, "b", label), label + ".b"),
                       vector3(required(o, "c", label), label + ".c")};
      if (t.normal() == vec3(0)) fail(o, label, "the three vertices are on one line: the triangle has no area");
      for (const vec3& v : {t.a, t.b, t.c}) check_placed(a.point(v), o, label);
      add_triangles(1, o, label);
      sc.add(triangle{a.point(t.a), a.point(t.b), a.point(t.c)}, mat);
      r["a"] = flow(t.a);
      r["b"] = flow(t.b);
      r["c"] = flow(t.c);
    } else if (type == "quad") {
      const quad q = quad_of(o, label);
      check_placed(a.point(q.corner), o, label + ".corner");
      check_placed(a.point(q.corner + q.u + q.v), o, label);
      check_placed(a.vector(q.u), o, label + ".u");
      check_placed(a.vector(q.v), o, label + ".v");
      sc.add(quad{a.point(q.corner), a.vector(q.u), a.vector(q.v)}, mat);
      r["corner"] = flow(q.corner);
      r["u"] = flow(q.u);
      r["v"] = flow(q.v);
    } else if (type == "box") {
      const vec3 lo = vector3(required(o, "min", label), label + ".min");
      const vec3 hi = vector3(required(o, "max", label), label + ".max");
      if (!(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z)) fail(o, label, "min must be below max on every axis");
      for (const vec3& v : {hi - lo, lo, hi, vec3(lo.x, hi.y, lo.z), vec3(hi.x, lo.y, lo.z), vec3(lo.x, lo.y, hi.z)})
        check_placed(v == hi - lo ? v : a.point(v), o, label);  // the extents, and the corners placed
      for (const vec3& v : {vec3(hi.x, hi.y, lo.z), vec3(hi.x, lo.y, hi.z), vec3(lo.x, hi.y, hi.z)})
        check_placed(a.point(v), o, label);
      for (const quad& q : box_faces(lo, hi)) sc.add(quad{a.point(q.corner), a.vector(q.u), a.vector(q.v)}, mat);
      r["min"] = flow(lo);
      r["max"] = flow(hi);
    } else if (type == "mesh" || type == "bezier") {
      const std::filesystem::path file = find_file(required(o, "file", label), label + ".file");
      r["file"] = o["file"].Scalar();
      const int divs = o["divs"] ? int(integer(o["divs"], label + ".divs", 1, max_tessellation_divs))
                                 : scene_file_defaults::bezier_divs;
      if (type == "bezier") r["divs"] = divs;
      mesh msh;
      patch_set ps;
      std::optional<texture> file_albedo;
      std::string no_file_albedo = "an OBJ's materials (mtllib) are not read";
      try {
        if (type == "mesh") {
#if ZRAKA_SCENE_MESH_FILES
          mesh_file_contents c = load_mesh_file(file);
          msh = std::move(c.geometry);
          file_albedo = std::move(c.base_colour);
          no_file_albedo = c.base_colour_problem;
#else
          if (file.extension() != ".obj")
            throw error(file.string() + ": a '" + file.extension().string() + "' mesh needs assimp, and this program was " +
                        "built without it (Debian's libassimp-dev; header-only, define ZRAKA_WITH_ASSIMP and link assimp)");
          msh = load_obj(file);
#endif
        } else {
          ps = load_bpt(file);
        }
      } catch (const error& e) {  // name the file as the scene does, not by its full path
        std::string msg = e.what();
        if (msg.rfind(file.string(), 0) == 0) msg = o["file"].Scalar() + msg.substr(file.string().size());
        fail(o["file"], label + ".file", msg);
      }
      if (mat < 0 && !file_albedo) fail(o["material"], label + ".material", "from-file: " + o["file"].Scalar() + ": " + no_file_albedo);
      if (mat < 0) {  // the file's base colour on a diffuse material
        mat = sc.add_material(material::lambertian(*file_albedo));
        sc.material_names.push_back("from-file (" + o["file"].Scalar() + ")");
      }
      if (type == "mesh") {
        add_triangles(msh.triangles.size(), o["file"], label + ".file");
        transform_mesh(msh, a);
      } else {
        // Before the work: P patches at divs give P * 2 divs^2 triangles.
        add_triangles(ps.patches.size() * triangles_per_patch(divs), o["divs"] ? o["divs"] : o, label + ".divs");
        try {
          msh = tessellate(ps.all_patches(), divs, a);
        } catch (const error& e) {
          fail(o, label, e.what());
        }
      }
      for (const vec3& p : msh.positions) check_placed(p, o, label);
      sc.add(std::move(msh), mat);
    }
    r["material"] = mat_name;
    if (o["transform"]) r["transform"] = o["transform"];
    r.SetStyle(YAML::EmitterStyle::Flow);
    resolved_["objects"].push_back(r);
  }

  // The object's name (into r and the label used in messages) and its material's index.
  int object_material(const YAML::Node& o, const std::string& path, YAML::Node& r, std::string& label,
                      std::string& mat_name, bool from_file_allowed = false) const {
    if (o["name"]) {
      r["name"] = text(o["name"], path + ".name");
      label = path + " (" + o["name"].Scalar() + ")";
    }
    mat_name = "default";
    if (o["material"]) mat_name = text(o["material"], label + ".material");
    if (mat_name == "from-file" && from_file_allowed) return -1;
    if (mat_name == "from-file") fail(o["material"], label + ".material", "only a mesh takes its material from its file");
    const auto m = material_index_.find(mat_name);
    if (m == material_index_.end()) {
      std::string known;
      for (const auto& kv : material_index_) known += (known.empty() ? "" : ", ") + kv.first;
      fail(o["material"], label + ".material", "unknown material '" + mat_name + "' (defined: " + known + ")");
    }
    return m->second;
  }

  // ---------------------------------------------------------------- registered types (scene_registry.hpp)
  // [listing registered-object]
  // Keys first (the common ones and those the type registered), then the factory reads its
  // fields through a scene_node. An error the factory throws itself is given the entry's place.
  void registered_object(const YAML::Node& o, const std::string& path, const std::string& type,
                         const scene_registry::entry<scene_registry::shape_factory>& reg) {
    strict_keys(o, path, type, {"type", "name", "material"}, reg.keys);
    YAML::Node r;
    r["type"] = type;
    std::string label = path, mat_name;
    const int mat = object_material(o, path, r, label, mat_name);
    user_shape_ptr<double> shape;
    located(o, label, [&] { shape = reg.make(scene_node(*this, o, label, type, reg.keys, r)); });
    if (!shape) fail(o, label, "the factory for '" + type + "' made no shape");
    located(o, label, [&] { out_.sc.add(std::move(shape), mat); });
    out_.sc.user_shape_labels.resize(out_.sc.user_shapes.size() - 1);  // for refusals by name
    out_.sc.user_shape_labels.push_back(o["name"] ? "object '" + o["name"].Scalar() + "'" : path);
    r["material"] = mat_name;
    r.SetStyle(YAML::EmitterStyle::Flow);
    resolved_["objects"].push_back(r);
  }
  // [end]
  material registered_material(const YAML::Node& n, const std::string& path, const std::string& type,
                               const scene_registry::entry<scene_registry::material_factory>& reg, int index) {
    strict_keys(n, path, reg.builtin ? "" : type, {"type"}, reg.keys);
    YAML::Node r;
    r["type"] = type;
    material m;
    located(n, path, [&] { m = reg.make(scene_node(*this, n, path, type, reg.keys, r)); });
    r.SetStyle(YAML::EmitterStyle::Flow);
    // A built-in kind writes its own entry (materials(): every default filled in, a preset as
    // its numbers); a course's type is written as its reader read it.
    if (!reg.builtin) registered_resolved_[index] = r;
    return m;
  }
  // Every key of n is one of `common` or `own`, once. type: named in the message ("unknown key
  // for a disk"), or "" for a built-in kind, whose message is that of every other section.
  void strict_keys(const YAML::Node& n, const std::string& path, const std::string& type,
                   std::initializer_list<const char*> common, const std::vector<std::string>& own) const {
    std::string list;
    for (const char* k : common) list += (list.empty() ? "" : ", ") + std::string(k);
    for (const std::string& k : own) list += ", " + k;
    std::set<std::string> seen;
    for (const auto& kv : n) {
      const std::string k = kv.first.IsScalar() ? kv.first.Scalar() : "?";
      if (!seen.insert(k).second) fail(kv.first, join(path, k), "duplicate key");
      bool ok = std::find(own.begin(), own.end(), k) != own.end();
      for (const char* c : common) ok = ok || k == c;
      if (!ok) fail(kv.first, join(path, k), "unknown key" + (type.empty() ? "" : " for a " + type) + " (expected one of: " + list + ")");
    }
  }
  // Runs f; a zraka::error without this file's place (thrown by user code) gets the entry's.
  template <class F> void located(const YAML::Node& n, const std::string& path, F&& f) const {
    try {
      f();
    } catch (const error& e) {
      const std::string msg = e.what();
      if (msg.rfind(name_ + ":", 0) == 0) throw;
      fail(n, path, msg);
    } catch (const std::exception& e) {
      fail(n, path, std::string("the factory failed: ") + e.what());
    }
  }

  // Six quads facing out (u x v along the outward normal).
  static std::vector<quad> box_faces(const vec3& lo, const vec3& hi) {
    const vec3 d = hi - lo;
    const vec3 dx(d.x, 0, 0), dy(0, d.y, 0), dz(0, 0, d.z);
    return {quad{lo, dz, dy},           quad{vec3(hi.x, lo.y, lo.z), dy, dz},   // -x, +x
            quad{lo, dx, dz},           quad{vec3(lo.x, hi.y, lo.z), dz, dx},   // -y, +y
            quad{lo, dy, dx},           quad{vec3(lo.x, lo.y, hi.z), dx, dy}};  // -z, +z
  }

  static void transform_mesh(mesh& m, const affine& a) {
    for (vec3& p : m.positions) p = a.point(p);
    for (vec3& n : m.normals) n = a.normal(n);
    if (glm::determinant(a.linear) < 0)  // a mirror turns the winding: turn it back
      for (auto& t : m.triangles) std::swap(t[1], t[2]);
  }
};

}  // namespace detail

// ---------------------------------------------------------------- scene_node
ZRAKA_SCENE_FILE_FN YAML::Node scene_node::get(const std::string& key) const {
  // A factory reading a key it did not register is a bug in the program, not in the scene.
  if (std::find(keys_.begin(), keys_.end(), key) == keys_.end())
    throw error("scene registry: the factory for '" + type_ + "' reads key '" + key + "', which it did not register");
  const YAML::Node& n = n_;  // const: looking up a key must not add it
  return n[key];
}
ZRAKA_SCENE_FILE_FN YAML::Node scene_node::need(const std::string& key) const {
  const YAML::Node v = get(key);
  if (!v) r_.fail(n_, field(key), "required, but missing");
  return v;
}
ZRAKA_SCENE_FILE_FN void scene_node::fail(const std::string& key, const std::string& what) const {
  const YAML::Node v = get(key);
  r_.fail(v ? v : n_, field(key), what);
}
ZRAKA_SCENE_FILE_FN double scene_node::number(const std::string& key) const {
  const double x = r_.number(need(key), field(key));
  resolved_[key] = r_.num(x);
  return x;
}
ZRAKA_SCENE_FILE_FN double scene_node::number(const std::string& key, double fallback) const {
  return has(key) ? number(key) : (resolved_[key] = r_.num(fallback), fallback);
}
ZRAKA_SCENE_FILE_FN long long scene_node::integer(const std::string& key, long long lo, long long hi, long long fallback) const {
  const long long x = has(key) ? r_.integer(get(key), field(key), lo, hi) : fallback;
  resolved_[key] = x;
  return x;
}
ZRAKA_SCENE_FILE_FN vec3 scene_node::point(const std::string& key) const {
  const vec3 p = r_.vector3(need(key), field(key));
  resolved_[key] = r_.flow(p);
  return p;
}
ZRAKA_SCENE_FILE_FN vec3 scene_node::point(const std::string& key, const vec3& fallback) const {
  return has(key) ? point(key) : (resolved_[key] = r_.flow(fallback), fallback);
}
ZRAKA_SCENE_FILE_FN vec3 scene_node::direction(const std::string& key) const {
  const vec3 d = r_.vector3(need(key), field(key));
  const vec3 u = normalize_or_zero(d);
  if (u == vec3(0) || !is_finite(u)) fail(key, "a direction must not be zero");
  resolved_[key] = r_.flow(d);
  return u;
}
ZRAKA_SCENE_FILE_FN vec3 scene_node::direction(const std::string& key, const vec3& fallback) const {
  return has(key) ? direction(key) : (resolved_[key] = r_.flow(fallback), normalize_or_zero(fallback));
}
ZRAKA_SCENE_FILE_FN rgb scene_node::colour(const std::string& key) const {
  const rgb c = r_.colour(need(key), field(key));
  resolved_[key] = r_.flow(c);
  return c;
}
ZRAKA_SCENE_FILE_FN rgb scene_node::colour(const std::string& key, const rgb& fallback) const {
  return has(key) ? colour(key) : (resolved_[key] = r_.flow(fallback), fallback);
}
ZRAKA_SCENE_FILE_FN std::string scene_node::text(const std::string& key, const std::string& fallback) const {
  const std::string s = has(key) ? r_.text(get(key), field(key)) : fallback;
  resolved_[key] = s;
  return s;
}
ZRAKA_SCENE_FILE_FN int scene_node::medium(const std::string& key) const {
  const int i = r_.medium_named(need(key), field(key));
  resolved_[key] = r_.out_.sc.media[std::size_t(i)].name;
  return i;
}
ZRAKA_SCENE_FILE_FN bool scene_node::is_map(const std::string& key) const { return get(key).IsMap(); }
ZRAKA_SCENE_FILE_FN std::string scene_node::scalar(const std::string& key) const {
  const YAML::Node v = get(key);
  return v.IsScalar() ? v.Scalar() : detail::scene_reader::scalar_text(v);
}
ZRAKA_SCENE_FILE_FN void scene_node::fail(const std::string& what) const { r_.fail(n_, path_, what); }
ZRAKA_SCENE_FILE_FN texture scene_node::texture(const std::string& key) const {
  const zraka::texture t = r_.albedo(need(key), field(key));
  resolved_[key] = detail::scene_reader::albedo_node(t);
  return t;
}

// ---------------------------------------------------------------- scene_registry
// Here, not in scene_registry.hpp: the built-in readers (materials/builtin.hpp, lights/builtin.hpp)
// read a scene_node.
ZRAKA_SCENE_FILE_FN scene_registry::scene_registry() {
  register_builtin_materials(*this);
  builtin_materials_ = material_order_;
  for (auto& kv : materials_) kv.second.builtin = true;
  register_builtin_lights(*this);
  for (auto& kv : lights_) kv.second.builtin = true;
  builtin_lights_ = light_order_;
  builtin_lights_.insert(builtin_lights_.end(), {"quad", "sphere"});  // the lights section's glowing shapes
}
#endif  // ZRAKA_SCENE_FILE_DEFINITIONS

namespace detail {
ZRAKA_SCENE_FILE_FN loaded_scene parse_scene_in(const std::string& text, const std::string& name,
                                                const std::filesystem::path& dir, const scene_registry& types,
                                                const std::filesystem::path& resource_root)
#if ZRAKA_SCENE_FILE_DEFINITIONS
{
  return scene_reader(name, dir, types, resource_root).read(text);
}
#else
    ;
#endif
}  // namespace detail

// Reads a scene from YAML text; `name` is used in error messages and `dir` to find the files
// the scene names; `types` are the types the program registered (scene_registry.hpp).
inline loaded_scene parse_scene(const std::string& text, const std::string& name,
                                const std::filesystem::path& dir = ".", const scene_registry& types = {}) {
  return detail::parse_scene_in(text, name, dir, types, resource_root());
}

namespace detail {
ZRAKA_SCENE_FILE_FN loaded_scene load_scene_file_in(const std::filesystem::path& path, const scene_registry& types,
                                                    const std::filesystem::path& root)
#if ZRAKA_SCENE_FILE_DEFINITIONS
{
  const std::filesystem::path p = resource_path_in(path.string(), root);
  return parse_scene_in(read_input_file(p), path.string(), p.parent_path(), types, root);
}
#else
    ;
#endif
}  // namespace detail

// Reads a scene file: a path as given, or relative to the resource root (resources.hpp).
inline loaded_scene load_scene_file(const std::filesystem::path& path, const scene_registry& types = {}) {
  return detail::load_scene_file_in(path, types, resource_root());
}

}  // namespace zraka

#pragma once
// Mitsuba 3 XML scenes, read (book 4.1): a documented subset of Mitsuba's scene format becomes
// the zraka scene it describes, so that one file renders in both (scenes/mitsuba/).
//
//   const zraka::loaded_scene ls = zraka::load_mitsuba_xml("scenes/mitsuba/cornell-box.xml");
//   std::cout << ls.resolved;   // the same scene as zraka YAML (scenes/README.md)
//
// The XML becomes zraka YAML text, which scene_file.hpp then reads: one reader builds scenes, and
// the YAML is what `scenes --scene file.xml` prints. Only what zraka models exactly is taken:
//   sensor perspective (fov, fov_axis, near/far clip left out) with to_world, film hdrfilm
//   (width, height, a box rfilter), sampler independent (sample_count, seed), integrator path
//   (max_depth: Mitsuba counts path segments, zraka bounces, so zraka's max_depth is one less);
//   shapes sphere, rectangle, cube, obj and ply (mesh_file.hpp; face_normals: zraka's path tracers shade meshes flat),
//   and disk when the program registered one (below);
//   a bitmap or checkerboard texture as a diffuse reflectance, on rectangles (whose uv were checked); BSDFs twosided around diffuse, conductor (material
//   'none') or roughconductor, and dielectric, roughdielectric (both GGX); emitters area (on a
//   shape whose BSDF is black), point, constant, envmap (rotated about +y only);
//   <default>, $name, <ref id>, and the transforms translate, rotate, scale, matrix, lookat.
// Everything else is an error naming the file, the line, the element and the attribute:
//   cornell.xml:12: <bsdf type="plastic">: unknown plugin 'plastic' (zraka reads: ...)
// Refused because zraka's model differs: a bare diffuse or conductor (Mitsuba's are black from
// behind, zraka's reflect on both sides: wrap them in twosided), Beckmann roughness, a bitmap or
// checkerboard on other shapes than rectangles or anywhere but a diffuse reflectance, Mitsuba's
// gaussian pixel filter
// (zraka's is a box), a mirroring or shearing to_world where zraka's shape cannot follow it.
// Limits as for YAML scenes (limits.hpp): file_bytes, and yaml_nodes for the XML's elements.
// Needs pugixml (libpugixml-dev) and yaml-cpp; compiled once into zraka::compiled when zraka is
// built with both (ZRAKA_COMPILED_MITSUBA_XML).
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/io/scene_file.hpp>

#include <filesystem>
#include <string>

#if defined(ZRAKA_COMPILED_MITSUBA_XML)
#define ZRAKA_MITSUBA_XML_FN
#else
#define ZRAKA_MITSUBA_XML_FN inline
#endif
#if !defined(ZRAKA_COMPILED_MITSUBA_XML) || defined(ZRAKA_COMPILING)
#define ZRAKA_MITSUBA_XML_DEFINITIONS 1
#else
#define ZRAKA_MITSUBA_XML_DEFINITIONS 0
#endif

#if ZRAKA_MITSUBA_XML_DEFINITIONS && __has_include(<pugixml.hpp>)
#include <zraka/core/affine.hpp>
#include <zraka/core/limits.hpp>
// PLY through mesh_file.hpp where scene_file.hpp reads it (assimp: ZRAKA_SCENE_MESH_FILES).
#if ZRAKA_SCENE_MESH_FILES
#include <zraka/io/mesh_file.hpp>
#else
#include <zraka/io/obj_file.hpp>
#endif

#include <pugixml.hpp>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <set>
#include <utility>
#include <vector>
#define ZRAKA_MITSUBA_XML_READER 1
#endif

namespace zraka {

// The zraka YAML of a Mitsuba XML text; `name` names the file in errors, `dir` is where the
// files it names (obj, envmap) are looked for, as Mitsuba does: next to the XML file.
// `registry`: the program's own types (scene_registry.hpp). zraka has no disk of its own (it is
// book 2.3's example of a shape from outside): a Mitsuba disk is read as `type: disk` with center,
// normal and radius when the program registered a disk shape that takes those keys.
ZRAKA_MITSUBA_XML_FN std::string mitsuba_xml_to_yaml(const std::string& text, const std::string& name,
                                                     const std::filesystem::path& dir,
                                                     const scene_registry& registry = {});

inline bool is_mitsuba_xml_path(const std::filesystem::path& p) { return p.extension() == ".xml"; }

namespace detail {
// load_mitsuba_xml with the resource root given (for load_scene_argument, compiled.hpp).
inline loaded_scene load_mitsuba_xml_in(const std::filesystem::path& path, const std::filesystem::path& root,
                                       const scene_registry& registry = {}) {
  const std::filesystem::path p = resource_path_in(path.string(), root);
  const std::string yaml = mitsuba_xml_to_yaml(read_input_file(p), path.string(), p.parent_path(), registry);
  // What the XML reader checked does not fail here; what it leaves to the YAML reader (a
  // malformed OBJ or sky file) is named by its place in the converted scene.
  return parse_scene_in(yaml, path.string() + " (as zraka YAML)", p.parent_path(), registry, root);
}
}  // namespace detail

// Reads a Mitsuba XML file (a path as given, or relative to the resource root); `registry` as for
// mitsuba_xml_to_yaml.
inline loaded_scene load_mitsuba_xml(const std::filesystem::path& path, const scene_registry& registry = {}) {
  return detail::load_mitsuba_xml_in(path, resource_root(), registry);
}

#if ZRAKA_MITSUBA_XML_DEFINITIONS && !defined(ZRAKA_MITSUBA_XML_READER)
ZRAKA_MITSUBA_XML_FN std::string mitsuba_xml_to_yaml(const std::string&, const std::string& name,
                                                     const std::filesystem::path&, const scene_registry&) {
  throw error(name + ": reading Mitsuba XML needs pugixml (libpugixml-dev), which this build of zraka lacks");
}
#elif ZRAKA_MITSUBA_XML_DEFINITIONS
namespace detail {

class mitsuba_reader {
 public:
  mitsuba_reader(std::string name, std::filesystem::path dir, const scene_registry& registry)
      : name_(std::move(name)), dir_(std::move(dir)) {
    if (const auto* d = registry.shape("disk"))
      disk_ = std::ranges::all_of(std::array{"center", "normal", "radius"},
                                  [&](const char* k) { return std::ranges::find(d->keys, k) != d->keys.end(); });
  }

  std::string read(const std::string& text) {
    for (std::size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') newlines_.push_back(i);
    pugi::xml_document doc;
    // parse_default: no DTD, so no entity of the file's own can expand (no "billion laughs").
    const pugi::xml_parse_result res = doc.load_buffer(text.data(), text.size(), pugi::parse_default, pugi::encoding_utf8);
    if (!res) throw error(name_ + ":" + std::to_string(line_of(res.offset)) + ": XML syntax: " + res.description());
    check_size(doc);
    pugi::xml_node root;
    for (pugi::xml_node c : doc.children())
      if (c.type() == pugi::node_element) {
        if (root) fail(c, "a second root element (the file holds one <scene>)");
        root = c;
      } else if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) {
        fail_at(line_of(std::size_t(c.offset_debug())), "text outside the <scene> element");
      }
    if (!root) throw error(name_ + ": no <scene> element");
    if (std::string(root.name()) != "scene") fail(root, "expected <scene version=\"3.x\">");
    attributes(root, {"version"});
    const std::string version = attr(root, "version");
    if (version.rfind("3.", 0) != 0) fail(root, "version '" + version + "': only Mitsuba 3 scenes (version 3.x) are read");

    for (pugi::xml_node c : elements(root))  // <default> first: Mitsuba substitutes in the whole file
      if (std::string(c.name()) == "default") {
        attributes(c, {"name", "value"});
        const std::string n = raw(c, "name");
        if (defaults_.count(n)) fail(c, "duplicate default '" + n + "'");
        defaults_[n] = raw(c, "value");
      }
    for (pugi::xml_node c : elements(root)) {  // named BSDFs, for <ref id>
      if (std::string(c.name()) != "bsdf") continue;
      attributes(c, {"type", "id", "name"});
      if (!c.attribute("id")) fail(c, "a BSDF at the top level needs an id (shapes refer to it with <ref id=\"...\"/>)");
      const std::string id = attr(c, "id");
      if (bsdf_nodes_.count(id)) fail(c, "duplicate id '" + id + "'");
      bsdf_nodes_[id] = c;
      taken_.insert(id);
    }
    for (pugi::xml_node c : elements(root)) {
      const std::string tag = c.name();
      if (tag == "default") continue;
      if (tag == "bsdf") (void)bsdf_by_id(attr(c, "id"), c);  // checked even if unused, as Mitsuba does
      else if (tag == "sensor") sensor(c);
      else if (tag == "integrator") integrator(c);
      else if (tag == "shape") shape(c);
      else if (tag == "emitter") emitter(c);
      else fail(c, "unknown element <" + tag + "> (zraka reads in <scene>: default, integrator, sensor, bsdf, shape, emitter)");
    }
    if (!have_sensor_) fail(root, "the scene has no <sensor>");
    if (!have_integrator_) fail(root, "the scene has no <integrator type=\"path\"> (zraka needs its max_depth)");
    if (objects_.size() == 0) fail(root, "the scene has no shapes");
    YAML::Node out;
    out["settings"] = settings_;
    out["camera"] = camera_;
    if (materials_.size()) out["materials"] = materials_;
    if (lights_.size()) out["lights"] = lights_;
    if (environment_.size()) out["environment"] = environment_;
    out["objects"] = objects_;
    YAML::Emitter em;
    em << out;
    return em.c_str();
  }

 private:
  std::string name_;
  bool disk_ = false;  // the program registered a disk (center, normal, radius)
  std::filesystem::path dir_;
  std::vector<std::size_t> newlines_;
  std::map<std::string, std::string> defaults_;
  std::map<std::string, pugi::xml_node> bsdf_nodes_;
  struct bsdf_t {
    YAML::Node material;  // the zraka material
    std::string name;     // its name in materials
    bool black = false;   // reflects nothing: may carry an area emitter
    bool one_sided = false;  // a bare diffuse or conductor
    pugi::xml_node textured;  // its bitmap or checkerboard, if any: on rectangles only
    bool emitted = false;
  };
  std::map<std::string, bsdf_t> bsdfs_;  // by id
  YAML::Node settings_, camera_, materials_, lights_, environment_, objects_;
  bool have_sensor_ = false, have_integrator_ = false;
  std::set<std::string> taken_;  // material names

  // ---------------------------------------------------------------- errors
  std::size_t line_of(std::size_t offset) const {
    return std::size_t(std::upper_bound(newlines_.begin(), newlines_.end(), offset) - newlines_.begin()) + 1;
  }
  std::size_t line_of(const pugi::xml_node& n) const {
    const std::ptrdiff_t off = n.offset_debug();
    return off < 0 ? 0 : line_of(std::size_t(off));
  }
  // <tag type="..." name="..." id="...">: the element as the file names it.
  static std::string describe(const pugi::xml_node& n) {
    std::string s = "<" + std::string(n.name());
    for (const char* a : {"type", "name", "id"})
      if (n.attribute(a)) s += " " + std::string(a) + "=\"" + clip(n.attribute(a).value()) + "\"";
    return s + ">";
  }
  static std::string clip(const std::string& s) { return s.size() > 60 ? s.substr(0, 60) + "..." : s; }
  [[noreturn]] void fail_at(std::size_t line, const std::string& what) const {
    throw error(name_ + ":" + std::to_string(line) + ": " + what);
  }
  [[noreturn]] void fail(const pugi::xml_node& n, const std::string& what) const {
    fail_at(line_of(n), describe(n) + ": " + what);
  }
  [[noreturn]] void fail(const pugi::xml_node& n, const char* attribute, const std::string& what) const {
    fail_at(line_of(n), describe(n) + ": " + attribute + "=\"" + clip(n.attribute(attribute).value()) + "\": " + what);
  }

  // ---------------------------------------------------------------- limits
  // Elements count against limits().yaml_nodes, as a YAML scene's nodes do.
  void check_size(const pugi::xml_document& doc) const {
    const std::uint64_t limit = limits().yaml_nodes;
    std::uint64_t count = 0;
    std::vector<pugi::xml_node> todo{doc};  // no recursion: a deeply nested file is a long list here
    while (!todo.empty()) {
      const pugi::xml_node n = todo.back();
      todo.pop_back();
      if (++count > limit)
        fail_at(line_of(n), "the file has more than " + std::to_string(limit) + " XML nodes " + raise_hint("yaml_nodes"));
      for (pugi::xml_node c : n.children()) todo.push_back(c);
    }
  }

  // ---------------------------------------------------------------- elements and attributes
  // The element children of n; text inside a zraka element is an error, comments are not.
  std::vector<pugi::xml_node> elements(const pugi::xml_node& n) const {
    std::vector<pugi::xml_node> out;
    for (pugi::xml_node c : n.children()) {
      if (c.type() == pugi::node_element) out.push_back(c);
      else if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) fail(n, "unexpected text inside the element");
    }
    return out;
  }
  void attributes(const pugi::xml_node& n, std::initializer_list<const char*> allowed) const {
    for (pugi::xml_attribute a : n.attributes()) {
      bool ok = false;
      std::string list;
      for (const char* x : allowed) {
        ok = ok || std::string(a.name()) == x;
        list += (list.empty() ? "" : ", ") + std::string(x);
      }
      if (!ok) fail_at(line_of(n), describe(n) + ": unknown attribute '" + clip(a.name()) + "' (expected " + list + ")");
    }
  }
  std::string raw(const pugi::xml_node& n, const char* a) const {
    if (!n.attribute(a)) fail(n, std::string("attribute '") + a + "' is missing");
    return n.attribute(a).value();
  }
  // An attribute's value with every $name replaced by its <default>, once (a default's value is
  // not substituted again, so nothing can grow without end).
  std::string attr(const pugi::xml_node& n, const char* a) const {
    const std::string v = raw(n, a);
    std::string out;
    for (std::size_t i = 0; i < v.size();) {
      if (v[i] != '$') {
        out += v[i++];
        continue;
      }
      std::size_t j = i + 1;
      while (j < v.size() && (std::isalnum(static_cast<unsigned char>(v[j])) || v[j] == '_')) ++j;
      const std::string key = v.substr(i + 1, j - i - 1);
      const auto it = defaults_.find(key);
      if (it == defaults_.end()) fail(n, a, "no <default name=\"" + key + "\"> for $" + key);
      out += it->second;
      i = j;
    }
    return out;
  }

  // ---------------------------------------------------------------- values
  double number_text(const pugi::xml_node& n, const char* a, const std::string& s) const {
    double x = 0;
    const char* b = s.data();
    while (b < s.data() + s.size() && *b == ' ') ++b;
    const char* e = s.data() + s.size();
    while (e > b && e[-1] == ' ') --e;
    const auto r = std::from_chars(b, e, x);
    if (b == e || r.ec != std::errc() || r.ptr != e) fail(n, a, "'" + clip(s) + "' is not a number");
    if (!std::isfinite(x)) fail(n, a, "must be finite");
    if (std::abs(x) > max_coordinate) fail(n, a, "must be within +-1e18 (its square would overflow)");
    return x;
  }
  std::vector<double> numbers(const pugi::xml_node& n, const char* a) const {
    std::string s = attr(n, a);
    std::replace(s.begin(), s.end(), ',', ' ');
    std::replace(s.begin(), s.end(), '\t', ' ');
    std::replace(s.begin(), s.end(), '\n', ' ');
    std::vector<double> out;
    std::size_t i = 0;
    while (i < s.size()) {
      while (i < s.size() && s[i] == ' ') ++i;
      std::size_t j = i;
      while (j < s.size() && s[j] != ' ') ++j;
      if (j > i) out.push_back(number_text(n, a, s.substr(i, j - i)));
      if (out.size() > 16) fail(n, a, "too many numbers");
      i = j;
    }
    return out;
  }
  double number(const pugi::xml_node& n, const char* a = "value") const {
    const std::vector<double> v = numbers(n, a);
    if (v.size() != 1) fail(n, a, "expected one number");
    return v[0];
  }
  vec3 triple(const pugi::xml_node& n, const char* a) const {
    const std::vector<double> v = numbers(n, a);
    if (v.size() != 3) fail(n, a, "expected three numbers \"x, y, z\"");
    return {v[0], v[1], v[2]};
  }
  // <point/vector name=".." value="x, y, z"/> or x=".." y=".." z="..".
  vec3 xyz(const pugi::xml_node& n, double fallback) const {
    if (n.attribute("value")) {
      if (n.attribute("x") || n.attribute("y") || n.attribute("z")) fail(n, "give value or x, y, z, not both");
      return triple(n, "value");
    }
    vec3 v(fallback);
    if (n.attribute("x")) v.x = number(n, "x");
    if (n.attribute("y")) v.y = number(n, "y");
    if (n.attribute("z")) v.z = number(n, "z");
    return v;
  }

  // The parameters of a plugin element: its children by name; nested plugins (bsdf, emitter,
  // film, ...) and refs apart. Each name once.
  struct params {
    std::map<std::string, pugi::xml_node> by_name;
    std::vector<pugi::xml_node> nested;
  };
  params parameters(const pugi::xml_node& n, std::initializer_list<const char*> allowed) const {
    static const std::set<std::string> value_tags = {"float", "integer", "boolean", "string", "rgb",
                                                     "spectrum", "point", "vector", "transform", "texture"};
    params p;
    for (pugi::xml_node c : elements(n)) {
      const std::string tag = c.name();
      if (!value_tags.count(tag) || (tag == "texture" && !c.attribute("name"))) {
        p.nested.push_back(c);
        continue;
      }
      const std::string key = raw(c, "name");
      bool ok = false;
      std::string list;
      for (const char* x : allowed) {
        ok = ok || key == x;
        list += (list.empty() ? "" : ", ") + std::string(x);
      }
      if (!ok)
        fail(c, "parameter '" + key + "' is outside zraka's subset for " + describe(n) +
                    (list.empty() ? " (it takes none)" : " (it reads: " + list + ")"));
      if (p.by_name.count(key)) fail(c, "duplicate parameter '" + key + "'");
      p.by_name[key] = c;
    }
    return p;
  }
  void no_nested(const params& p, const pugi::xml_node& parent) const {
    for (pugi::xml_node c : p.nested) fail(c, "unexpected inside " + describe(parent));
  }
  std::string unique_name(const std::string& base) {
    std::string name = base;
    for (int i = 2; !taken_.insert(name).second; ++i) name = base + "-" + std::to_string(i);
    return name;
  }
  pugi::xml_node param(const params& p, const char* key) const {
    const auto it = p.by_name.find(key);
    return it == p.by_name.end() ? pugi::xml_node() : it->second;
  }  // The plugin's filename as written and where it is: next to the scene file, as Mitsuba looks.
  // Only whether it is there: a FIFO or a device is named as such by read_input_file later.
  std::pair<std::string, std::filesystem::path> file_param(const pugi::xml_node& n, const params& p) const {
    const pugi::xml_node fn = param(p, "filename");
    if (!fn) fail(n, "needs <string name=\"filename\" value=\"...\"/>");
    const std::string file = string_param(p, "filename", "");
    const std::filesystem::path full = std::filesystem::path(file).is_absolute() ? std::filesystem::path(file) : dir_ / file;
    std::error_code ec;
    if (!std::filesystem::exists(full, ec)) fail(fn, "value", "file not found next to the scene file: " + full.string());
    return {file, full};
  }

  void expect_tag(const pugi::xml_node& c, std::initializer_list<const char*> tags) const {
    std::string list;
    for (const char* t : tags) {
      if (std::string(c.name()) == t) return;
      list += (list.empty() ? "<" : ", <") + std::string(t) + ">";
    }
    if (std::string(c.name()) == "texture")
      fail(c, "a texture here is outside zraka's subset (zraka reads a bitmap as a diffuse reflectance only)");
    fail(c, "expected " + list);
  }
  double float_param(const params& p, const char* key, double fallback) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return fallback;
    expect_tag(c, {"float", "integer"});
    attributes(c, {"name", "value"});
    return number(c);
  }
  long long integer_param(const params& p, const char* key, long long fallback, long long lo, long long hi) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return fallback;
    expect_tag(c, {"integer"});
    attributes(c, {"name", "value"});
    const double x = number(c);
    if (x != std::floor(x)) fail(c, "value", "expected an integer");
    if (x < double(lo) || x > double(hi))
      fail(c, "value", "must be in " + std::to_string(lo) + ".." + std::to_string(hi));
    return (long long)x;
  }
  bool bool_param(const params& p, const char* key, bool fallback) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return fallback;
    expect_tag(c, {"boolean"});
    attributes(c, {"name", "value"});
    const std::string v = attr(c, "value");
    if (v == "true") return true;
    if (v == "false") return false;
    fail(c, "value", "expected true or false");
  }
  std::string string_param(const params& p, const char* key, const std::string& fallback) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return fallback;
    expect_tag(c, {"string"});
    attributes(c, {"name", "value"});
    return attr(c, "value");
  }
  // A colour: <rgb value="r, g, b"/> or one number, <float>, or a <spectrum> of one value
  // (grey in scalar_rgb). Not negative.
  rgb colour_param(const params& p, const char* key, double fallback) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return rgb(float(fallback));
    expect_tag(c, {"rgb", "float", "spectrum"});
    attributes(c, {"name", "value"});
    const std::vector<double> v = numbers(c, "value");
    if (std::string(c.name()) == "rgb" ? (v.size() != 1 && v.size() != 3) : v.size() != 1)
      fail(c, "value", std::string(c.name()) == "rgb" ? "expected \"r, g, b\" or one number"
                                                      : "expected one number (a spectrum of wavelength:value pairs is outside the subset)");
    const vec3 col = v.size() == 3 ? vec3(v[0], v[1], v[2]) : vec3(v[0]);
    if (col.x < 0 || col.y < 0 || col.z < 0) fail(c, "value", "a colour must not be negative");
    return rgb(col);
  }
  vec3 point_param(const params& p, const char* key, const vec3& fallback) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return fallback;
    expect_tag(c, {"point", "vector"});
    attributes(c, {"name", "value", "x", "y", "z"});
    return xyz(c, 0);
  }

  // <transform name="to_world"> with translate, rotate, scale, matrix and lookat in order: each
  // applies after the ones before it (left-multiplies), as in Mitsuba.
  affine transform_param(const params& p, const char* key) const {
    const pugi::xml_node t = param(p, key);
    if (!t) return affine{};
    expect_tag(t, {"transform"});
    attributes(t, {"name"});
    affine a;
    for (pugi::xml_node op : elements(t)) {
      const std::string tag = op.name();
      affine m;
      if (tag == "translate") {
        attributes(op, {"value", "x", "y", "z"});
        m = affine::translate(xyz(op, 0));
      } else if (tag == "scale") {
        attributes(op, {"value", "x", "y", "z"});
        vec3 s = op.attribute("value") && numbers(op, "value").size() == 1 ? vec3(number(op)) : xyz(op, 1);
        if (s.x == 0 || s.y == 0 || s.z == 0) fail(op, "a scale must not be zero");
        m = affine::scale(s);
      } else if (tag == "rotate") {
        attributes(op, {"value", "x", "y", "z", "angle"});
        const vec3 axis = op.attribute("value") ? triple(op, "value") : xyz(op, 0);
        // Mitsuba uses the axis as given: one not of unit length makes a matrix that also scales.
        if (std::abs(glm::length(axis) - 1) > 1e-6)
          fail(op, "the axis must have length 1 (Mitsuba does not normalise it; its matrix would also scale)");
        m = affine::rotate(glm::normalize(axis), number(op, "angle") * pi<double> / 180);
      } else if (tag == "matrix") {
        attributes(op, {"value"});
        const std::vector<double> v = numbers(op, "value");
        if (v.size() != 16) fail(op, "value", "expected 16 numbers, a 4x4 matrix row by row");
        if (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)
          fail(op, "value", "the last row must be 0 0 0 1 (an affine map)");
        for (int r = 0; r < 3; ++r) {
          for (int c = 0; c < 3; ++c) m.linear[c][r] = v[std::size_t(4 * r + c)];  // glm: [column][row]
          m.translation[r] = v[std::size_t(4 * r + 3)];
        }
      } else if (tag == "lookat") {
        attributes(op, {"origin", "target", "up"});
        const vec3 o = triple(op, "origin"), target = triple(op, "target");
        const vec3 up = op.attribute("up") ? triple(op, "up") : vec3(0, 1, 0);
        const vec3 dir = normalize_or_zero(target - o);
        if (dir == vec3(0)) fail(op, "origin and target are the same point");
        const vec3 left = normalize_or_zero(glm::cross(up, dir));
        if (left == vec3(0)) fail(op, "up is parallel to the view direction (or zero)");
        m.linear = mat3(left, glm::cross(dir, left), dir);  // columns: camera x, y, z
        m.translation = o;
      } else {
        fail(op, "unknown transform '" + tag + "' (expected translate, rotate, scale, matrix, lookat)");
      }
      a = m * a;
    }
    return a;
  }

  // ---------------------------------------------------------------- YAML output
  // The shortest text that reads back as the same double (to_chars): the YAML is the XML's
  // scene to the last bit, and 0.35 stays 0.35.
  static YAML::Node num(double x) {
    char buf[32];
    return YAML::Node(std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr));
  }
  static YAML::Node flow(const vec3& v) {
    YAML::Node s(YAML::NodeType::Sequence);
    for (int i = 0; i < 3; ++i) s.push_back(num(v[i]));
    s.SetStyle(YAML::EmitterStyle::Flow);
    return s;
  }
  static YAML::Node flow(const rgb& c) { return flow(vec3(c)); }
  void check_placed(const pugi::xml_node& at, const vec3& v) const {
    for (int i = 0; i < 3; ++i)
      if (!(std::abs(v[i]) <= max_coordinate)) fail(at, "after to_world a coordinate is beyond +-1e18");
  }

  // ---------------------------------------------------------------- sensor, film, sampler, integrator
  // A plugin the scene has once, of the one type zraka reads.
  void single(const pugi::xml_node& n, bool& seen, const std::string& what, const std::string& type) const {
    attributes(n, {"type", "id", "name"});
    if (seen) fail(n, "a second " + what + " (zraka reads one)");
    seen = true;
    const std::string t = attr(n, "type");
    if (t != type) fail(n, "type", "unknown " + what + " plugin '" + t + "' (zraka reads: " + type + ")");
  }
  void sensor(const pugi::xml_node& n) {
    single(n, have_sensor_, "sensor", "perspective");
    // near_clip and far_clip are not read: zraka's camera has no clip planes (Mitsuba's default
    // near_clip 0.01 cuts nothing in the scenes of scenes/mitsuba/).
    const params p = parameters(n, {"fov", "fov_axis", "to_world"});
    pugi::xml_node film, sampler;
    for (pugi::xml_node c : p.nested) {
      const std::string tag = c.name();
      if (tag == "film" && !film) film = c;
      else if (tag == "sampler" && !sampler) sampler = c;
      else fail(c, "unexpected in a sensor (zraka reads one <film> and one <sampler>)");
    }
    int width = 768, height = 576;  // Mitsuba's hdrfilm defaults
    if (!film) fail(n, "zraka needs a <film type=\"hdrfilm\"> with <rfilter type=\"box\"/> (Mitsuba's default filter is a gaussian)");
    film_element(film, width, height);
    settings_["width"] = width;
    settings_["height"] = height;
    settings_["spp"] = 4;  // Mitsuba's sampler default
    settings_["seed"] = 0;
    if (sampler) sampler_element(sampler);

    double fov = 45;
    if (!param(p, "fov")) fail(n, "zraka needs the fov (focal_length is outside the subset)");
    fov = float_param(p, "fov", fov);
    if (!(fov > 0 && fov < 180)) fail(param(p, "fov"), "value", "must be in (0, 180) degrees");
    const std::string axis = string_param(p, "fov_axis", "x");
    // zraka's vfov is the vertical angle; Mitsuba's fov is along fov_axis (x by default).
    const double t = std::tan(fov * pi<double> / 360), w = width, h = height;
    double tan_half_v = 0;
    if (axis == "y") tan_half_v = t;
    else if (axis == "x") tan_half_v = t * h / w;
    else if (axis == "diagonal") tan_half_v = t * h / std::sqrt(w * w + h * h);
    else if (axis == "smaller") tan_half_v = w < h ? t * h / w : t;
    else if (axis == "larger") tan_half_v = w > h ? t * h / w : t;
    else fail(param(p, "fov_axis"), "value", "expected x, y, diagonal, smaller or larger");
    const double vfov = 2 * std::atan(tan_half_v) * 180 / pi<double>;

    // [listing mitsuba-camera]
    // Mitsuba's camera looks along +z of to_world with +y up, and its +x points to the image's
    // left (lookat makes x = up x dir). zraka's camera (position, look_at, up) is never mirrored
    // or scaled, so to_world must be a rotation and a translation.
    const affine m = transform_param(p, "to_world");
    const vec3 x = m.linear[0], y = m.linear[1], z = m.linear[2];
    const double tol = 1e-6;
    if (std::abs(glm::length(x) - 1) > tol || std::abs(glm::length(y) - 1) > tol || std::abs(glm::length(z) - 1) > tol ||
        std::abs(glm::dot(x, y)) > tol || std::abs(glm::dot(y, z)) > tol || std::abs(glm::dot(x, z)) > tol)
      fail(param(p, "to_world"), "a sensor's to_world must be a rotation and a translation (no scale or shear)");
    if (glm::determinant(m.linear) < 0)
      fail(param(p, "to_world"), "this to_world mirrors the image (e.g. scale x=\"-1\"); zraka's camera is never mirrored");
    check_placed(param(p, "to_world") ? param(p, "to_world") : n, m.translation);
    camera_["position"] = flow(m.translation);
    camera_["look_at"] = flow(m.translation + z);
    camera_["up"] = flow(y);
    camera_["vfov"] = num(vfov);
    // [end]
  }
  void film_element(const pugi::xml_node& f, int& width, int& height) {
    attributes(f, {"type", "id", "name"});
    if (attr(f, "type") != "hdrfilm") fail(f, "type", "unknown film plugin (zraka reads: hdrfilm)");
    const params p = parameters(f, {"width", "height", "pixel_format", "component_format"});
    width = int(integer_param(p, "width", width, 1, image::max_side));
    height = int(integer_param(p, "height", height, 1, image::max_side));
    const std::string pf = string_param(p, "pixel_format", "rgb");
    if (pf != "rgb" && pf != "rgba") fail(param(p, "pixel_format"), "value", "zraka writes rgb (or rgba)");
    (void)string_param(p, "component_format", "float16");  // the file's precision, not the image
    pugi::xml_node filter;
    for (pugi::xml_node c : p.nested) {
      if (std::string(c.name()) != "rfilter" || filter) fail(c, "unexpected in a film (zraka reads one <rfilter type=\"box\"/>)");
      filter = c;
    }
    if (!filter) fail(f, "Mitsuba's default pixel filter is a gaussian, zraka's a box: add <rfilter type=\"box\"/>");
    attributes(filter, {"type"});
    if (attr(filter, "type") != "box")
      fail(filter, "type", "zraka's pixel filter is a box (pixel_sampling.hpp): only <rfilter type=\"box\"/>");
    (void)parameters(filter, {});
    for (pugi::xml_node c : elements(filter)) fail(c, "a box filter takes no parameters");
  }
  void sampler_element(const pugi::xml_node& s) {
    attributes(s, {"type", "id", "name"});
    // Another sampler changes the noise, not the image's expectation; zraka has one kind.
    if (attr(s, "type") != "independent") fail(s, "type", "unknown sampler plugin (zraka reads: independent)");
    const params p = parameters(s, {"sample_count", "seed"});
    for (pugi::xml_node c : p.nested) fail(c, "unexpected in a sampler");
    settings_["spp"] = integer_param(p, "sample_count", 4, 1, scene_file_defaults::max_spp);
    settings_["seed"] = integer_param(p, "seed", 0, 0, 1LL << 40);
  }
  void integrator(const pugi::xml_node& n) {
    single(n, have_integrator_, "integrator", "path");
    // rr_depth: Russian roulette is unbiased, it changes the noise and not the image.
    const params p = parameters(n, {"max_depth", "rr_depth", "hide_emitters"});
    for (pugi::xml_node c : p.nested) fail(c, "unexpected in an integrator");
    if (!param(p, "max_depth")) fail(n, "zraka needs max_depth (Mitsuba's default -1 is unbounded; zraka's paths are)");
    // [listing mitsuba-depth]
    // Mitsuba counts a path's segments (max_depth 2: direct light), zraka its bounces.
    const long long depth = integer_param(p, "max_depth", 2, 2, scene_file_defaults::max_depth + 1);
    settings_["max_depth"] = depth - 1;
    // [end]
    (void)integer_param(p, "rr_depth", 5, 1, 1 << 20);
    if (bool_param(p, "hide_emitters", false)) fail(param(p, "hide_emitters"), "value", "hidden emitters are outside zraka's subset");
  }

  // ---------------------------------------------------------------- BSDFs
  static double named_ior(const std::string& s) {
    // Mitsuba's table of named indices (its dielectric plugin's documentation), those most used.
    static const std::map<std::string, double> t = {
        {"vacuum", 1.0},   {"helium", 1.000036}, {"hydrogen", 1.000132}, {"air", 1.000277},  {"water", 1.333},
        {"water ice", 1.31}, {"fused quartz", 1.458}, {"pyrex", 1.47}, {"acrylic glass", 1.49},
        {"polypropylene", 1.49}, {"bk7", 1.5046},   {"sodium chloride", 1.544}, {"amber", 1.55},
        {"pet", 1.575},    {"diamond", 2.419}};
    const auto it = t.find(s);
    return it == t.end() ? -1 : it->second;
  }
  double ior_param(const params& p, const char* key, double fallback) const {
    const pugi::xml_node c = param(p, key);
    if (!c) return fallback;
    expect_tag(c, {"float", "string"});
    attributes(c, {"name", "value"});
    double x;
    if (std::string(c.name()) == "string") {
      x = named_ior(attr(c, "value"));
      if (x < 0) fail(c, "value", "unknown index name (zraka knows Mitsuba's vacuum, air, water, bk7, diamond, ...)");
    } else {
      x = number(c);
    }
    if (!(x >= 1 && x <= 10)) fail(c, "value", "an index of refraction in [1, 10]");
    return x;
  }
  // GGX only: Mitsuba's default distribution is beckmann, which zraka does not have.
  double alpha_param(const pugi::xml_node& n, const params& p) const {
    if (!param(p, "distribution")) fail(n, "Mitsuba's default distribution is beckmann; zraka's microfacets are GGX: add <string name=\"distribution\" value=\"ggx\"/>");
    if (string_param(p, "distribution", "") != "ggx") fail(param(p, "distribution"), "value", "zraka's microfacets are GGX only");
    const double a = float_param(p, "alpha", 0.1);
    if (!(a > 0 && a <= 1)) fail(param(p, "alpha"), "value", "alpha must be in (0, 1]");
    return a;
  }
  bsdf_t convert_bsdf(const pugi::xml_node& n, bool in_twosided) {
    attributes(n, {"type", "id", "name"});
    const std::string type = attr(n, "type");
    bsdf_t b;
    YAML::Node& m = b.material;
    if (type == "twosided") {
      if (in_twosided) fail(n, "a twosided inside a twosided");
      const params p = parameters(n, {});
      if (p.nested.size() != 1) fail(n, "zraka reads a twosided around one BSDF (two BSDFs, front and back, are outside the subset)");
      const pugi::xml_node inner = p.nested[0];
      if (std::string(inner.name()) != "bsdf") fail(inner, "expected a <bsdf>");
      const std::string it = attr(inner, "type");
      if (it != "diffuse" && it != "conductor" && it != "roughconductor")
        fail(inner, "type", "zraka reads twosided around diffuse, conductor or roughconductor");
      b = convert_bsdf(inner, true);
      b.one_sided = false;
      return b;
    }
    if (type == "diffuse") {
      const params p = parameters(n, {"reflectance"});
      no_nested(p, n);
      m["type"] = "lambertian";
      const pugi::xml_node tex = param(p, "reflectance");
      if (tex && std::string(tex.name()) == "texture") {
        m["albedo"] = attr(tex, "type") == "checkerboard" ? checkerboard(tex) : bitmap(tex);
        b.textured = tex;
      } else {
        const rgb r = colour_param(p, "reflectance", 0.5);
        if (max_component(r) > 1) fail(param(p, "reflectance"), "value", "a reflectance must be at most 1");
        m["albedo"] = flow(r);
        b.black = max_component(r) == 0;
      }
    } else if (type == "conductor") {
      const params p = parameters(n, {"material", "specular_reflectance"});
      no_nested(p, n);
      if (string_param(p, "material", "none") != "none")
        fail(param(p, "material"), "value", "a smooth conductor of a named metal is outside the subset (zraka's smooth metal is a mirror times a colour: material 'none')");
      const rgb r = colour_param(p, "specular_reflectance", 1);
      if (max_component(r) > 1) fail(param(p, "specular_reflectance"), "value", "a reflectance must be at most 1");
      m["type"] = "metal";
      m["albedo"] = flow(r);
      m["fuzz"] = 0;
    } else if (type == "roughconductor") {
      const params p = parameters(n, {"distribution", "alpha", "material", "eta", "k", "sample_visible"});
      no_nested(p, n);
      m["type"] = "rough_conductor";
      m["roughness"] = num(alpha_param(n, p));
      (void)bool_param(p, "sample_visible", true);  // a sampling choice, not the BSDF
      const std::string mat = string_param(p, "material", "none");
      if (param(p, "eta") || param(p, "k")) {
        if (param(p, "material")) fail(param(p, "material"), "give material or eta and k, not both");
        if (!param(p, "eta") || !param(p, "k")) fail(n, "give both eta and k");
        const rgb eta = colour_param(p, "eta", 0);
        if (!(eta.x > 0 && eta.y > 0 && eta.z > 0)) fail(param(p, "eta"), "value", "must be positive");
        m["eta"] = flow(eta);
        m["k"] = flow(colour_param(p, "k", 0));
      } else if (mat == "none") {
        m["f0"] = flow(rgb(1));  // Mitsuba's 'none': a perfect reflector; Schlick at F0 = 1 is 1 too
      } else {
        fail(param(p, "material"), "value", "named metals are outside the subset (Mitsuba's spectral data differs from zraka's presets): give eta and k as rgb");
      }
    } else if (type == "dielectric" || type == "roughdielectric") {
      if (in_twosided) fail(n, "a dielectric inside a twosided");
      const params p = type == "dielectric" ? parameters(n, {"int_ior", "ext_ior"})
                                            : parameters(n, {"int_ior", "ext_ior", "distribution", "alpha", "sample_visible"});
      for (pugi::xml_node c : p.nested) fail(c, "unexpected in a dielectric");
      // Mitsuba's defaults: bk7 glass in air; zraka's ior is the ratio (outside is 1).
      const double ior = ior_param(p, "int_ior", 1.5046) / ior_param(p, "ext_ior", 1.000277);
      m["ior"] = num(ior);
      if (type == "dielectric") {
        m["type"] = "dielectric";
      } else {
        if (ior == 1) fail(n, "int_ior equals ext_ior: no interface to be rough");
        m["type"] = "rough_dielectric";
        m["roughness"] = num(alpha_param(n, p));
        (void)bool_param(p, "sample_visible", true);
      }
    } else {
      fail(n, "type", "unknown plugin '" + type +
                          "' (zraka reads the BSDFs diffuse, conductor, roughconductor, dielectric, roughdielectric, twosided)");
    }
    b.one_sided = type == "diffuse" || type == "conductor" || type == "roughconductor";
    m.SetStyle(YAML::EmitterStyle::Flow);
    return b;
  }
  // A bitmap reflectance: zraka's image texture (bilinear, sRGB unless raw). Its uv are checked
  // against Mitsuba's on rectangles only (book 4.1), so other shapes refuse it.
  YAML::Node bitmap(const pugi::xml_node& t) {
    attributes(t, {"type", "name", "id"});
    if (attr(t, "type") != "bitmap")
      fail(t, "type", "unknown texture plugin (zraka reads: bitmap, checkerboard)");
    const params p = parameters(t, {"filename", "filter_type", "wrap_mode", "raw"});
    no_nested(p, t);
    const std::string file = file_param(t, p).first;
    if (string_param(p, "filter_type", "bilinear") != "bilinear")
      fail(param(p, "filter_type"), "value", "zraka's image textures are bilinear");
    const std::string wrap = string_param(p, "wrap_mode", "repeat");
    if (wrap != "repeat" && wrap != "clamp") fail(param(p, "wrap_mode"), "value", "zraka wraps by repeat or clamp");
    YAML::Node img, a;
    img["file"] = file;
    img["srgb"] = !bool_param(p, "raw", false);
    img["wrap"] = wrap;
    a["image"] = img;
    a.SetStyle(YAML::EmitterStyle::Flow);
    return a;
  }
  // A checkerboard reflectance: zraka's checker in uv space. Mitsuba's takes color0 where the
  // fractional parts of u and v are on the same side of 1/2: cells of 1/2, even ones color0.
  YAML::Node checkerboard(const pugi::xml_node& t) {
    attributes(t, {"type", "name", "id"});
    const params p = parameters(t, {"color0", "color1", "to_uv"});
    no_nested(p, t);
    const rgb c0 = colour_param(p, "color0", 0.4), c1 = colour_param(p, "color1", 0.2);
    for (const char* k : {"color0", "color1"})
      if (max_component(colour_param(p, k, 0)) > 1) fail(param(p, k), "value", "a reflectance must be at most 1");
    double s = 1;
    if (param(p, "to_uv")) {  // uv' = to_uv (u, v, 0): a uniform scale of the plane only
      const affine a = transform_param(p, "to_uv");
      s = a.linear[0][0];
      if (!(s > 0) || a.linear[1][1] != s || a.linear[0][1] != 0 || a.linear[1][0] != 0 || a.translation != vec3(0))
        fail(param(p, "to_uv"), "zraka's uv checker takes a to_uv that scales u and v alike, nothing else");
    }
    YAML::Node c, a;
    c["even"] = flow(c0);
    c["odd"] = flow(c1);
    c["scale"] = num(0.5 / s);
    c["space"] = "uv";
    a["checker"] = c;
    a.SetStyle(YAML::EmitterStyle::Flow);
    return a;
  }
  bsdf_t& bsdf_by_id(const std::string& id, const pugi::xml_node& at) {
    if (const auto it = bsdfs_.find(id); it != bsdfs_.end()) return it->second;
    const auto n = bsdf_nodes_.find(id);
    if (n == bsdf_nodes_.end()) fail(at, "no <bsdf id=\"" + id + "\"> at the top level of the scene");
    bsdf_t b = convert_bsdf(n->second, false);
    b.name = id;
    return bsdfs_[id] = b;
  }
  // The material name of a non-emitting shape's BSDF, entered into materials when first used.
  std::string use(bsdf_t& b, const pugi::xml_node& shape_node, const pugi::xml_node& bsdf_node) {
    if (b.one_sided && !b.black)
      fail(bsdf_node, "Mitsuba's bare " + std::string(b.material["type"].Scalar() == "lambertian" ? "diffuse" : "conductor") +
                          " is black from behind, zraka's reflects on both sides: wrap it in <bsdf type=\"twosided\">");
    (void)shape_node;
    if (!b.emitted) {
      materials_[b.name] = b.material;  // names are unique: ids once, the others by unique_name
      b.emitted = true;
    }
    return b.name;
  }

  // ---------------------------------------------------------------- shapes
  // L must be s R (R a rotation, s > 0): for spheres (equal s) and meshes (s per axis).
  static bool orthogonal_columns(const mat3& l) {
    const double tol = 1e-9;
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j)
        if (std::abs(glm::dot(l[i], l[j])) > tol * glm::length(l[i]) * glm::length(l[j])) return false;
    return true;
  }
  void shape(const pugi::xml_node& n) {
    attributes(n, {"type", "id", "name"});
    const std::string type = attr(n, "type");
    params p;
    if (type == "sphere") p = parameters(n, {"center", "radius", "to_world"});
    else if (type == "rectangle" || type == "cube") p = parameters(n, {"to_world"});
    else if (type == "obj") p = parameters(n, {"filename", "to_world", "face_normals", "flip_tex_coords"});
    else if (type == "ply") p = parameters(n, {"filename", "to_world", "face_normals"});
    else if (type == "disk" && disk_) p = parameters(n, {"to_world"});
    else if (type == "disk")
      fail(n, "type", "zraka has no disk of its own: register a disk shape taking center, normal and radius "
                      "(book 2.3, 'Extending zraka') and read the file with that registry");
    else fail(n, "type", "unknown plugin '" + type + "' (zraka reads the shapes sphere, rectangle, cube, obj, ply)");

    const affine a = transform_param(p, "to_world");
    const pugi::xml_node tw = param(p, "to_world") ? param(p, "to_world") : n;
    if (glm::determinant(a.linear) <= 0)
      fail(tw, "a to_world that mirrors or flattens the shape is outside the subset (Mitsuba turns faces, zraka does not)");
    std::vector<YAML::Node> made;  // the geometry first, so its errors come in the file's order
    auto add = [&](YAML::Node o) { made.push_back(o); };
    // A sphere's or a disk's to_world: a rotation, a translation and a uniform scale s.
    auto uniform_scale = [&] {
      const mat3& l = a.linear;
      const double s = glm::length(l[0]);
      if (!orthogonal_columns(l) || std::abs(glm::length(l[1]) - s) > 1e-9 * s || std::abs(glm::length(l[2]) - s) > 1e-9 * s)
        fail(tw, "a " + type + "'s to_world may rotate, translate and scale uniformly only");
      return s;
    };
    if (type == "disk") {  // Mitsuba's: the unit disk at the origin in the xy plane, facing +z
      const double s = uniform_scale();
      const vec3 c = a.point(vec3(0));
      const vec3 nn = a.linear[2] / s;
      check_placed(tw, c);
      check_placed(tw, vec3(s));
      YAML::Node o;
      o["type"] = "disk";
      o["center"] = flow(c);
      o["normal"] = flow(nn);
      o["radius"] = num(s);
      add(o);
    } else if (type == "sphere") {
      const double s = uniform_scale();
      const double r = float_param(p, "radius", 1.0);
      if (!(r > 0)) fail(param(p, "radius"), "value", "must be positive");
      const vec3 c = a.point(point_param(p, "center", vec3(0)));
      check_placed(tw, c);
      check_placed(tw, vec3(r * s));
      YAML::Node o;
      o["type"] = "sphere";
      o["center"] = flow(c);
      o["radius"] = num(r * s);
      add(o);
    } else if (type == "rectangle" || type == "cube") {
      // [listing mitsuba-rectangle]
      // Mitsuba's rectangle is [-1, 1]^2 at z = 0 facing +z; its cube [-1, 1]^3 facing out. Under
      // an affine map a face stays a parallelogram: a zraka quad, facing u x v.
      std::vector<std::array<vec3, 3>> faces;  // corner, u, v in the shape's own space
      if (type == "rectangle") faces.push_back({vec3(-1, -1, 0), vec3(2, 0, 0), vec3(0, 2, 0)});
      else
        for (int ax = 0; ax < 3; ++ax)
          for (int side : {-1, 1}) {
            vec3 e(0), u(0), v(0);
            e[ax] = side;
            u[(ax + 1) % 3] = 2;
            v[(ax + 2) % 3] = 2;
            if (side < 0) std::swap(u, v);  // u x v along the outward normal
            faces.push_back({e - 0.5 * u - 0.5 * v, u, v});
          }
      for (const auto& f : faces) {
        YAML::Node o;
        o["type"] = "quad";
        o["corner"] = flow(a.point(f[0]));
        o["u"] = flow(a.vector(f[1]));
        o["v"] = flow(a.vector(f[2]));
        for (const vec3& q : {a.point(f[0]), a.vector(f[1]), a.vector(f[2]), a.point(f[0] + f[1] + f[2])}) check_placed(tw, q);
        add(o);
      }
      // [end]
    } else {  // obj or ply (mesh_file.hpp reads both)
      const pugi::xml_node fn = param(p, "filename");
      const auto [file, full] = file_param(n, p);
      if (type == "obj") (void)bool_param(p, "flip_tex_coords", true);  // uv only matter to textures, which a mesh does not take here
      // Mitsuba shades a mesh with the file's vn (or smooth normals it makes) unless face_normals
      // is set; zraka's path tracers shade every triangle with its own normal: flat.
      if (!bool_param(p, "face_normals", false))
        fail(param(p, "face_normals") ? param(p, "face_normals") : n,
             "zraka's path tracers shade meshes flat (Mitsuba smooths them by default): add <boolean name=\"face_normals\" value=\"true\"/>");
#if !ZRAKA_SCENE_MESH_FILES
      if (type == "ply") fail(n, "type", "this zraka reads no PLY: it was built without assimp (Debian's libassimp-dev)");
#endif
      try {  // the file's errors at this line, before the YAML reader loads it again
#if ZRAKA_SCENE_MESH_FILES
        (void)read_mesh_file(full);
#else
        (void)load_obj(full);
#endif
      } catch (const error& e) {
        fail(fn, "value", e.what());
      }
      YAML::Node o;
      o["type"] = "mesh";
      o["file"] = file;  // the YAML reader looks next to the scene file first, where it is
      if (param(p, "to_world")) o["transform"] = mesh_transform(a, tw);
      add(o);
    }

    // The BSDF (nested or <ref id>) and an area emitter.
    pugi::xml_node bsdf_node, emitter_node;
    bsdf_t inline_bsdf;
    bsdf_t* b = nullptr;
    for (pugi::xml_node c : p.nested) {
      const std::string tag = c.name();
      if (tag == "bsdf" || tag == "ref") {
        if (bsdf_node) fail(c, "a second BSDF for one shape");
        bsdf_node = c;
        if (tag == "ref") {
          attributes(c, {"id", "name"});
          if (c.attribute("name") && attr(c, "name") != "bsdf") fail(c, "name", "zraka reads a reference to a BSDF only");
          b = &bsdf_by_id(attr(c, "id"), c);
        } else {
          if (c.attribute("id")) fail(c, "id", "give a shape's own BSDF no id, or define it at the top level and use <ref id>");
          inline_bsdf = convert_bsdf(c, false);
          inline_bsdf.name = unique_name(type + "-line" + std::to_string(line_of(c)));
          b = &inline_bsdf;
        }
      } else if (tag == "emitter") {
        if (emitter_node) fail(c, "a second emitter for one shape");
        emitter_node = c;
      } else {
        fail(c, "unexpected in a shape (zraka reads a <bsdf>, a <ref id> and an <emitter type=\"area\">)");
      }
    }
    YAML::Node mat_name;
    if (emitter_node) {
      attributes(emitter_node, {"type", "id", "name"});
      if (attr(emitter_node, "type") != "area") fail(emitter_node, "type", "a shape's emitter must be area");
      const params ep = parameters(emitter_node, {"radiance"});
      no_nested(ep, emitter_node);
      const rgb radiance = colour_param(ep, "radiance", 1);
      // zraka's emitter reflects nothing; Mitsuba's shape reflects by its BSDF (diffuse 0.5 if none).
      if (!b || !b->black)
        fail(bsdf_node ? bsdf_node : n, "zraka's area lights reflect nothing: give the emitting shape a black BSDF "
                                        "(<bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0\"/></bsdf>)");
      YAML::Node m;
      m["type"] = "emitter";
      m["radiance"] = flow(radiance);
      m.SetStyle(YAML::EmitterStyle::Flow);
      const std::string name = unique_name("emitter-line" + std::to_string(line_of(emitter_node)));
      materials_[name] = m;
      mat_name = name;
    } else {
      if (!b) fail(n, "zraka needs the shape's BSDF (Mitsuba's default is a one-sided diffuse 0.5)");
      if (b->textured && type != "rectangle")
        fail(b->textured, "a " + attr(b->textured, "type") + " is read on a rectangle only (zraka's uv on a " + type +
                              " is not checked against Mitsuba's)");
      // Mitsuba's bitmap has v = 0 at the image's top row, zraka's at the bottom (texture.hpp):
      // the quad runs its v edge downwards instead. It then faces -z, which a two-sided
      // diffuse surface does not see.
      if (b->textured && attr(b->textured, "type") == "bitmap") {
        made[0]["corner"] = flow(a.point(vec3(-1, 1, 0)));
        made[0]["v"] = flow(a.vector(vec3(0, -2, 0)));
      }
      mat_name = use(*b, n, bsdf_node);
    }

    for (YAML::Node& o : made) {
      o["material"] = mat_name;
      o.SetStyle(YAML::EmitterStyle::Flow);
      objects_.push_back(o);
    }
  }
  // zraka's mesh transform is scale, then rotate about one axis, then translate.
  YAML::Node mesh_transform(const affine& a, const pugi::xml_node& at) const {
    const mat3& l = a.linear;
    if (!orthogonal_columns(l)) fail(at, "an obj's to_world may scale along the object's own axes, rotate and translate only (no shear)");
    const vec3 s(glm::length(l[0]), glm::length(l[1]), glm::length(l[2]));
    const mat3 r(l[0] / s.x, l[1] / s.y, l[2] / s.z);  // det > 0 was checked: a rotation
    YAML::Node t;
    t["scale"] = flow(s);
    // R = cos I + sin [a]x + (1 - cos) a a^T: the angle from both parts (atan2 keeps its digits
    // near 0 and a half turn, where acos would lose half of them); the axis from the skew part,
    // or past a quarter turn from the symmetric part, signed by the skew part.
    const vec3 skew(r[1][2] - r[2][1], r[2][0] - r[0][2], r[0][1] - r[1][0]);  // 2 sin(angle) a
    const double c = (r[0][0] + r[1][1] + r[2][2] - 1) / 2, angle = std::atan2(glm::length(skew) / 2, c);
    vec3 axis = skew;
    if (angle > pi<double> / 2) {
      int k = 0;
      for (int i = 1; i < 3; ++i)
        if (r[i][i] > r[k][k]) k = i;
      axis = vec3(0);
      axis[k] = std::sqrt(std::max(0.0, (r[k][k] - c) / (1 - c)));
      for (int i = 0; i < 3; ++i)
        if (i != k) axis[i] = (r[k][i] + r[i][k]) / (2 * (1 - c) * axis[k]);
      if (glm::dot(axis, skew) < 0) axis = -axis;
    }
    if (angle > 1e-12 && normalize_or_zero(axis) != vec3(0)) {
      YAML::Node rot;
      rot["axis"] = flow(normalize_or_zero(axis));
      rot["degrees"] = num(angle * 180 / pi<double>);
      t["rotate"] = rot;
    }
    t["translate"] = flow(a.translation);
    t.SetStyle(YAML::EmitterStyle::Flow);
    return t;
  }

  // ---------------------------------------------------------------- emitters
  void emitter(const pugi::xml_node& n) {
    attributes(n, {"type", "id", "name"});
    const std::string type = attr(n, "type");
    if (type == "point") {
      const params p = parameters(n, {"position", "intensity", "to_world"});
      no_nested(p, n);
      if (param(p, "position") && param(p, "to_world")) fail(n, "give position or to_world, not both");
      const vec3 pos = param(p, "to_world") ? transform_param(p, "to_world").point(vec3(0)) : point_param(p, "position", vec3(0));
      check_placed(n, pos);
      YAML::Node l;
      l["type"] = "point";
      l["position"] = flow(pos);
      l["intensity"] = flow(colour_param(p, "intensity", 1));
      l.SetStyle(YAML::EmitterStyle::Flow);
      lights_.push_back(l);
    } else if (type == "constant" || type == "envmap") {
      if (environment_.size()) fail(n, "a second environment emitter (zraka has one environment)");
      if (type == "constant") {
        const params p = parameters(n, {"radiance"});
        no_nested(p, n);
        environment_["color"] = flow(colour_param(p, "radiance", 1));
      } else {
        const params p = parameters(n, {"filename", "scale", "to_world"});
        for (pugi::xml_node c : p.nested) fail(c, "unexpected in an envmap");
        const std::string file = file_param(n, p).first;
        const double scale = float_param(p, "scale", 1);
        if (!(scale >= 0)) fail(param(p, "scale"), "value", "must not be negative");
        // environment.hpp uses Mitsuba's latitude-longitude map; zraka turns it about +y only.
        const affine a = transform_param(p, "to_world");
        const mat3& l = a.linear;
        const double tol = 1e-9;
        if (a.translation != vec3(0) || std::abs(l[1][1] - 1) > tol || std::abs(l[0][1]) > tol || std::abs(l[2][1]) > tol ||
            std::abs(l[1][0]) > tol || std::abs(l[1][2]) > tol || std::abs(l[0][0] - l[2][2]) > tol ||
            std::abs(l[2][0] + l[0][2]) > tol || std::abs(l[0][0] * l[0][0] + l[2][0] * l[2][0] - 1) > tol)
          fail(param(p, "to_world"), "an envmap's to_world may only rotate about +y in zraka");
        environment_["file"] = file;
        environment_["scale"] = num(scale);
        environment_["rotate"] = num(std::atan2(l[2][0], l[0][0]) * 180 / pi<double>);
      }
    } else if (type == "area") {
      fail(n, "an area emitter belongs inside a <shape>");
    } else {
      fail(n, "type", "unknown plugin '" + type + "' (zraka reads the emitters area, point, constant, envmap)");
    }
  }
};

}  // namespace detail

ZRAKA_MITSUBA_XML_FN std::string mitsuba_xml_to_yaml(const std::string& text, const std::string& name,
                                                     const std::filesystem::path& dir, const scene_registry& registry) {
  return detail::mitsuba_reader(name, dir, registry).read(text);
}
#endif

}  // namespace zraka

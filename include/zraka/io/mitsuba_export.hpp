#pragma once
// The scene as JSON for tools/mitsuba_reference.py, which builds the same scene in Mitsuba 3 to
// render a reference (book 2.3): size, depth, camera, materials, spheres, quads, triangles (every
// mesh's too, flat), point lights, homogeneous media (book 6.1), and what book 5.4 and 5.3 add:
// rough_conductor and rough_dielectric (GGX alpha; a conductor by its complex index per channel,
// presets included), image textures on lambertian quads (the linear texels, as read), and the
// environment (a constant sky or a map's scaled texels with its rotation). Numbers are written
// with 17 digits, texels with 9 (a float's round trip), so the values survive the trip.
// What the converter cannot express exactly is refused by name (zraka::error): an infinite plane,
// a user shape, a density grid, a custom BSDF, a conductor given by an RGB F0 (Schlick: Mitsuba's
// roughconductor has none), a roughness texture, a noise texture, an image texture on anything
// but a lambertian quad (a sphere's or a triangle's (u, v) is not Mitsuba's), a kind it does not
// know. The converter refuses more (checker, fuzzy metal, phong): see tools/mitsuba_reference.py.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image.hpp>
#include <zraka/lights/environment.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/textures/texture.hpp>

#include <cstddef>
#include <sstream>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace zraka {

namespace detail {
// A file name inside a JSON string: quotes, backslashes and control characters escaped.
inline std::string json_escape(const std::string& s) {
  std::string r;
  for (const char ch : s) {
    if (ch == '"' || ch == '\\') r += '\\', r += ch;
    else if (static_cast<unsigned char>(ch) < 0x20) {
      static const char* hex = "0123456789abcdef";
      r += "\\u00";
      r += hex[(ch >> 4) & 0xf];
      r += hex[ch & 0xf];
    } else r += ch;
  }
  return r;
}
// A material as JSON fields, from its kind's write() (materials/): what the converter reads
// (albedo and checker, fuzz, ior, alpha, eta and k, an image texture) and the refusals of what
// it cannot express. Fields are kept in order; a kind's value replaces a default.
struct mitsuba_material_writer {
  std::string label, kind;  // "--export: material 'red'", "metal"
  std::vector<std::pair<std::string, std::string>> fields;
  const zraka::texture* image = nullptr;  // written after the other fields, with its texels

  static std::string num(double x) {
    std::ostringstream o;
    o.precision(17);
    o << x;
    return o.str();
  }
  static std::string v3(const rgb& c) { return "[" + num(c.x) + ", " + num(c.y) + ", " + num(c.z) + "]"; }
  void set(const std::string& key, const std::string& json) {
    for (auto& [k, v] : fields)
      if (k == key) return void(v = json);
    fields.emplace_back(key, json);
  }
  void number(const char* key, double x) { set(key == std::string("roughness") ? "alpha" : key, num(x)); }
  void colour(const char* key, const rgb& c) {
    if (key == std::string("f0"))
      throw error(label + " is a rough_conductor given by an RGB f0 (Schlick's approximation), which Mitsuba's "
                  "roughconductor does not have; give a metal preset or eta and k");
    set(key, v3(c));
  }
  void texture(const char* key, const zraka::texture& t) {
    if (key != std::string("albedo"))
      throw error(label + " has a " + key + " texture (" + describe(t) + "), which Mitsuba cannot match exactly");
    if (t.type == zraka::texture::kind::noise) throw error(label + " has " + describe(t) + ", which Mitsuba does not have");
    if (t.type == zraka::texture::kind::image && kind != "lambertian")
      throw error(label + " is a " + kind + " with " + describe(t) + "; only lambertian image textures are exported");
    set("albedo", v3(t.a));
    set("checker", t.type == zraka::texture::kind::checker ? "true" : "false");
    if (t.type == zraka::texture::kind::image) image = &t;
  }
  void medium(const char*, int) {}  // the interior, written for every material
};

}  // namespace detail

// Throws zraka::error for what the converter cannot express (see the top).
ZRAKA_COMPILED_FN std::string mitsuba_scene_json(const scene& sc, int width, int height, int depth);

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN std::string mitsuba_scene_json(const scene& sc, int width, int height, int depth) {
  if (!sc.planes.empty()) throw error("--export: Mitsuba has no infinite plane; use a large quad");
  if (!sc.user_shapes.empty())
    throw error("--export: a user shape ('" + sc.user_shapes[0].shape->name() + "') cannot be exported");
  for (std::size_t i = 0; i < sc.lights.size(); ++i)  // the converter knows point lights (lights/point.hpp)
    if (!sc.lights[i].is<light_kinds::point>())
      throw error("--export: light " + std::to_string(i) + " is of type '" + light_type(sc.lights[i]) +
                  "', which the converter does not know; only point lights are exported");
  for (const medium& md : sc.media)
    if (!md.homogeneous()) throw error("--export: medium '" + md.name + "' is a density grid; only homogeneous media are exported");
  // Every material's fields first: what cannot be exported is refused before anything is written.
  std::vector<detail::mitsuba_material_writer> mats;
  for (std::size_t i = 0; i < sc.materials.size(); ++i) {
    const material& m = sc.materials[i];
    detail::mitsuba_material_writer w{"--export: " + sc.material_label(int(i)), kind_name(m.kind), {}, nullptr};
    if (const auto* c = m.get<material_kinds::custom>())
      throw error(w.label + " is a custom BSDF ('" + c->bsdf->name() + "'), which cannot be exported");
    w.set("type", "\"" + w.kind + "\"");
    w.texture("albedo", material_kinds::lambertian{}.albedo);  // the kinds without one: a default's
    w.number("fuzz", 0);
    w.number("ior", material_kinds::dielectric{}.ior);
    if (m.is<material_kinds::emitter>()) w.texture("albedo", texture::solid(rgb(0)));  // black
    const bool known = std::visit([&](const auto& k) {
      if constexpr (requires { k.write(w, m); }) return k.write(w, m), true;
      else return false;
    }, m.kind);
    if (!known) throw error(w.label + " is of a kind the converter does not know");
    w.set("radiance", w.v3(m.radiance));
    w.set("two_sided", m.two_sided ? "true" : "false");
    w.set("interior", std::to_string(m.interior));
    mats.push_back(std::move(w));
  }
  auto albedo_image = [&](int mat) { return mats[std::size_t(mat)].image; };
  // An image texture is looked up by the hit's (u, v): a quad's is Mitsuba's rectangle's, a
  // sphere's and a triangle's (barycentric) are not.
  auto image_on = [&](int mat, const char* shape) {
    if (const texture* t = albedo_image(mat))
      throw error("--export: " + sc.material_label(mat) + " has " + describe(*t) +
                  " on a " + shape + ", whose (u, v) differ from Mitsuba's; image textures are exported on quads only");
  };
  for (const auto& s : sc.spheres) image_on(s.material, "sphere");
  for (const auto& t : sc.triangles) image_on(t.material, "triangle");
  for (const auto& m : sc.meshes) image_on(m.material, "mesh");
  std::ostringstream o;
  o.precision(17);
  auto v3 = [&](const auto& v) { o << '[' << double(v.x) << ", " << double(v.y) << ", " << double(v.z) << ']'; };
  // An image's linear texels, row 0 at the top, as a flat list r, g, b, r, ... (9 digits: floats).
  auto texels = [&](const image& img) {
    o << "\"width\": " << img.width << ", \"height\": " << img.height << ", \"texels\": [";
    o.precision(9);
    for (std::size_t k = 0; k < img.pixels.size(); ++k)
      for (int c = 0; c < 3; ++c) o << (k + std::size_t(c) ? ", " : "") << double(img.pixels[k][c]);
    o.precision(17);
    o << "]";
  };
  o << "{\n  \"width\": " << width << ", \"height\": " << height << ", \"max_depth\": " << depth
    << ",\n  \"background\": ";
  v3(sc.background);
  o << ",\n  \"environment\": ";  // book 5.3: replaces the background
  if (!sc.environment) o << "null";
  else if (sc.environment->is_constant()) {
    o << "{\"type\": \"constant\", \"radiance\": ";
    v3(sc.environment->radiance(vec3(0, 1, 0)));
    o << "}";
  } else {
    o << "{\"type\": \"map\", \"source\": \"" << detail::json_escape(sc.environment->name()) << "\", \"rotate\": "
      << sc.environment->rotate_degrees() << ", ";
    texels(sc.environment->map());
    o << "}";
  }
  o << ",\n  \"camera\": {\"position\": ";
  v3(sc.camera.position);
  o << ", \"look_at\": ";
  v3(sc.camera.look_at);
  o << ", \"up\": ";
  v3(sc.camera.up);
  o << ", \"vfov\": " << sc.camera.vfov_degrees << "},\n  \"materials\": [";
  for (std::size_t i = 0; i < mats.size(); ++i) {
    o << (i ? ",\n    " : "\n    ") << "{";
    for (std::size_t f = 0; f < mats[i].fields.size(); ++f)
      o << (f ? ", " : "") << "\"" << mats[i].fields[f].first << "\": " << mats[i].fields[f].second;
    if (const texture* t = mats[i].image) {
      o << ", \"texture\": {\"source\": \"" << detail::json_escape(t->source) << "\", \"repeat\": " << (t->repeat ? "true" : "false")
        << ", ";
      texels(*t->map);
      o << "}";
    }
    o << "}";
  }
  o << "],\n  \"global_medium\": " << sc.global_medium << ",\n  \"media\": [";  // book 6.1
  for (std::size_t i = 0; i < sc.media.size(); ++i) {
    const medium& md = sc.media[i];
    o << (i ? ",\n    " : "\n    ") << "{\"name\": \"" << md.name << "\", \"sigma_a\": ";
    v3(md.sigma_a);
    o << ", \"sigma_s\": ";
    v3(md.sigma_s);
    o << ", \"g\": " << md.g << "}";
  }
  o << "],\n  \"spheres\": [";
  for (std::size_t i = 0; i < sc.spheres.size(); ++i) {
    o << (i ? ",\n    " : "\n    ") << "{\"center\": ";
    v3(sc.spheres[i].shape.center);
    o << ", \"radius\": " << sc.spheres[i].shape.radius << ", \"material\": " << sc.spheres[i].material << "}";
  }
  o << "],\n  \"quads\": [";
  for (std::size_t i = 0; i < sc.quads.size(); ++i) {
    const auto& q = sc.quads[i].shape;
    o << (i ? ",\n    " : "\n    ") << "{\"corner\": ";
    v3(q.corner);
    o << ", \"u\": ";
    v3(q.u);
    o << ", \"v\": ";
    v3(q.v);
    o << ", \"material\": " << sc.quads[i].material << "}";
  }
  o << "],\n  \"triangles\": [";  // loose triangles and every mesh's triangles, flat-shaded
  bool first = true;
  auto tri = [&](const auto& a, const auto& b, const auto& c, int mat) {
    o << (first ? "\n    " : ",\n    ") << "{\"a\": ";
    v3(a), o << ", \"b\": ", v3(b), o << ", \"c\": ", v3(c);
    o << ", \"material\": " << mat << "}";
    first = false;
  };
  for (const auto& t : sc.triangles) tri(t.shape.a, t.shape.b, t.shape.c, t.material);
  for (const auto& m : sc.meshes)
    for (std::size_t i = 0; i < m.shape.triangle_count(); ++i) {
      const auto t = m.shape.triangle(i);
      tri(t.a, t.b, t.c, m.material);
    }
  o << "],\n  \"point_lights\": [";
  // A point light's own writer (lights/point.hpp) fills {"position": [...], "intensity": [...]}.
  struct json_writer {
    std::ostringstream& o;
    decltype(v3)& vector;
    bool first = true;
    void key(const char* k) { o << (first ? "{\"" : ", \"") << k << "\": ", first = false; }
    void point(const char* k, const vec3& p) { key(k), vector(p); }
    void colour(const char* k, const rgb& c) { key(k), vector(c); }
  };
  for (std::size_t i = 0; i < sc.lights.size(); ++i) {
    o << (i ? ",\n    " : "\n    ");
    json_writer w{o, v3};
    sc.lights[i].get<light_kinds::point>()->write(w);
    o << "}";
  }
  o << "]\n}\n";
  return o.str();
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

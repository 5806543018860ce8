#pragma once
// The fuzzy metal (book 1.7; the thesis's "diffuse", RTIOW's fuzzy metal): the mirror direction
// plus fuzz times a point in the unit ball, weighted by the albedo; fuzz 0 is a mirror. Not a
// BRDF one can evaluate, so it is specular: lights are not sampled at it. A rough conductor
// (rough_conductor.hpp) is the physically based metal. "metal" in scene files.
#include <zraka/core/hit.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/materials/scatter.hpp>
#include <zraka/sampling/sampling.hpp>
#include <zraka/textures/texture.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct fuzzy_metal {
  static constexpr const char* name = "metal";
  static constexpr bool has_density = false;
  static constexpr bool is_specular = true;  // a narrow lobe light sampling cannot hit by chance
  texture albedo = texture::solid(rgb(0.8f));
  double fuzz = 0;  // 0 = mirror

  // d: the incoming ray's direction. Three numbers for the point in the ball.
  template <class T> std::optional<scatter_t<T>> scatter(const vec3_t<T>& d, const hit_t<T>& h, rng& g) const {
    const vec3_t<T> n = h.facing_normal();
    // One full-expression per draw: a constructor's arguments are evaluated in no fixed order.
    const T u0 = T(g.uniform()), u1 = T(g.uniform()), u2 = T(g.uniform());
    const vec3_t<T> ball = sample_unit_ball(vec3_t<T>(u0, u1, u2));
    const auto wi = fuzzy_mirror(d, n, T(fuzz), ball);
    if (!wi) return std::nullopt;  // pushed below the surface: absorbed
    return scatter_t<T>{*wi, evaluate(albedo, h.p, n, h.uv), T(0), true};
  }

  // [listing whitted-metal]
  // Whitted (whitted.hpp): one ray, about the shading normal; one that would cross the
  // geometric surface (where the two normals differ) is drawn again about the geometric one.
  template <class W> rgb whitted(W& w) const {
    auto s = scatter(w.d, w.shading_hit(), w.g);
    if (s && !w.outside(s->direction)) s = scatter(w.d, w.h, w.g);
    return s ? w.trace(s->direction, s->weight) : rgb(0);
  }
  // [end]

  static constexpr int gpu_kind = 1;  // KIND_METAL
  template <class Packer> void pack(Packer& p) const {
    p.albedo(albedo);
    p.record.fuzz = float(fuzz);
  }

  static std::vector<std::string> keys() { return {"albedo", "fuzz"}; }
  template <class Node> static fuzzy_metal read(const Node& n, material_common&) {
    fuzzy_metal k;
    if (n.has("albedo")) k.albedo = n.texture("albedo");
    if (n.has("fuzz")) {
      k.fuzz = n.number("fuzz");
      if (k.fuzz < 0 || k.fuzz > 1) n.fail("fuzz", "must be in [0, 1], got " + n.scalar("fuzz"));
    }
    return k;
  }
  template <class Writer> void write(Writer& w, const material_common&) const {
    w.texture("albedo", albedo);
    w.number("fuzz", fuzz);
  }
};

}  // namespace zraka::material_kinds

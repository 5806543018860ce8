#pragma once
// A smooth metal (Mitsuba's `conductor`): the mirror direction, weighted by the metal's Fresnel
// reflectance at the angle of incidence (microfacet.hpp's conductor_fresnel: a complex index per
// channel, a preset by name, or an RGB F0 with Schlick). The limit of rough_conductor.hpp as the
// roughness goes to 0; unlike metal.hpp's mirror, its colour whitens towards grazing angles.
// Specular: lights are not sampled at it. The OpenCL kernel does not render it (no pack()), so
// realtime refuses it by name.
#include <zraka/core/hit.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/microfacet.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/materials/rough_conductor.hpp>
#include <zraka/materials/scatter.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct conductor {
  static constexpr const char* name = "conductor";
  static constexpr bool has_density = false;
  static constexpr bool is_specular = true;  // one direction
  conductor_fresnel fresnel;  // silver by default

  // Draws no number: the direction is certain, the colour is the weight.
  template <class T> std::optional<scatter_t<T>> scatter(const vec3_t<T>& d, const hit_t<T>& h, rng&) const {
    const vec3_t<T> n = h.facing_normal();
    const T cos_i = -glm::dot(d, n);
    if (!(cos_i > T(0))) return std::nullopt;  // along the surface: nothing reflected
    return scatter_t<T>{reflect(d, n), fresnel.eval(cos_i), T(0), true};
  }
  // Whitted (whitted.hpp): the mirror ray about the shading normal (the geometric one if it
  // would cross the surface), weighted by F.
  template <class W> rgb whitted(W& w) const {
    using T = typename W::scalar;
    vec3_t<T> n = w.ns;
    if (!w.outside(reflect(w.d, n))) n = w.ng;
    return w.trace(reflect(w.d, n), fresnel.eval(-glm::dot(w.d, n)));
  }

  // {type: conductor, metal | eta and k | f0} as for rough_conductor, without a roughness.
  static std::vector<std::string> keys() { return {"metal", "eta", "k", "f0"}; }
  template <class Node> static conductor read(const Node& n, material_common&) {
    return {rough_conductor::read_fresnel(n, "conductor")};
  }
  template <class Writer> void write(Writer& w, const material_common&) const { rough_conductor::write_fresnel(w, fresnel); }
};

}  // namespace zraka::material_kinds

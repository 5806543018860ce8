#pragma once
// An area light's surface (book 2.3): black, it scatters nothing; it gives off
// material_common::radiance from its front face (from both with two_sided). Any other kind may
// glow too; an emitter only glows.
#include <zraka/core/hit.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/scatter.hpp>
#include <zraka/textures/texture.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct emitter {
  static constexpr const char* name = "emitter";
  static constexpr bool has_density = false;
  static constexpr bool is_specular = false;
  static constexpr float default_radiance = 4.0f;  // a scene file's emitter and area lights

  template <class T> std::optional<scatter_t<T>> scatter(const vec3_t<T>&, const hit_t<T>&, rng&) const {
    return std::nullopt;  // absorbed: draws no number
  }

  // Whitted (whitted.hpp) sees its light only; the kernel (KIND_EMITTER) packs it black.
  template <class W> rgb whitted(W& w) const { return w.emitted(); }
  static constexpr int gpu_kind = 3;
  template <class Packer> void pack(Packer& p) const { p.albedo(texture::solid(rgb(0))); }

  static std::vector<std::string> keys() { return {"radiance"}; }
  template <class Node> static emitter read(const Node& n, material_common& c) {
    c.radiance = n.has("radiance") ? n.colour("radiance") : rgb(default_radiance);
    return {};
  }
  template <class Writer> void write(Writer& w, const material_common& c) const { w.colour("radiance", c.radiance); }
};

}  // namespace zraka::material_kinds

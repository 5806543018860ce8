#pragma once
// Lights that are not shapes (book 2.2, 2.3): this file closes the family, the list of kinds,
// each one file of this folder (README.md), and the few things the light set
// (scene/lights.hpp) asks of a light, each dispatched to the kind:
//   sample_light(l, h)                  the light arriving at hit h: direction, Le, pdf, delta,
//                                       shadow segment;
//   light_power(l)                      its flux, for choosing lights in proportion to it;
//   sample_light_emission(l, u)         light leaving it (BDPT, photon mapping), and
//   light_pdf_emission_direction(l, w), light_intensity_towards(l, w);
//   light_type(l), pack_light(l, k)     its name; its numbers for the OpenCL kernel, if it runs it.
// A light is a kind (a std::variant of the kinds' structs, each holding its own parameters). A
// course's light is the kind custom (custom.hpp); the OpenCL kernel refuses it by name. Area
// lights are shapes with a glowing material, and the environment is the scene's sky
// (environment.hpp): scene/lights.hpp samples those itself.
#include <zraka/core/error.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/lights/custom.hpp>
#include <zraka/lights/kernel_light.hpp>
#include <zraka/lights/light_sample.hpp>
#include <zraka/lights/point.hpp>

#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace zraka {

// [listing light-kinds]
// The kinds, closed here: a new built-in kind is one file, one line here and one in builtin.hpp.
using light_kind = std::variant<light_kinds::point, light_kinds::custom>;

struct light {
  light_kind kind;  // a point light of intensity 20 by default

  light() = default;
  template <class K>
    requires std::is_constructible_v<light_kind, K>
  light(K k) : kind(std::move(k)) {  // NOLINT: a kind is a light
    if (const auto* c = get<light_kinds::custom>(); c && !c->light) throw error("custom light: the light must not be null");
  }
  template <class K> bool is() const { return std::holds_alternative<K>(kind); }
  template <class K> const K* get() const { return std::get_if<K>(&kind); }  // null: another kind
};
// [end]

// The kind's name in scene files and messages: "point", or a course's own ("spot").
inline std::string light_type(const light& l) {
  if (const auto* c = l.get<light_kinds::custom>()) return c->light->name();
  return std::visit([](const auto& k) -> std::string { return k.name; }, l.kind);
}
template <class T> std::optional<light_sample_t<T>> sample_light(const light& l, const hit_t<T>& h) {
  return std::visit([&](const auto& k) { return k.sample(h); }, l.kind);
}
inline double light_power(const light& l) {
  return std::visit([](const auto& k) { return k.power(); }, l.kind);
}
template <class T> emission_sample_t<T> sample_light_emission(const light& l, const vec2_t<T>& u_dir) {
  return std::visit([&](const auto& k) { return k.template sample_emission<T>(u_dir); }, l.kind);
}
template <class T> T light_pdf_emission_direction(const light& l, const vec3_t<T>& w) {
  return std::visit([&](const auto& k) { return k.pdf_emission_direction(w); }, l.kind);
}
template <class T> rgb light_intensity_towards(const light& l, const vec3_t<T>& w) {
  return std::visit([&](const auto& k) { return k.intensity_towards(w); }, l.kind);
}
// Does the OpenCL kernel render it? Then pack_light fills k and returns true.
inline bool pack_light(const light& l, kernel_light& k) {
  return std::visit([&](const auto& x) {
    if constexpr (requires { x.pack(k); }) {
      x.pack(k);
      return true;
    } else {
      return false;
    }
  }, l.kind);
}

}  // namespace zraka

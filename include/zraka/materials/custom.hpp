#pragma once
// A course's own BSDF as a material kind (book 2.3, custom_bsdf.hpp): the one kind whose
// physics is behind a virtual interface, so that a course adds a material without editing the
// library. A registered material type (scene_registry.hpp) makes one with material::custom().
#include <zraka/core/hit.hpp>
#include <zraka/materials/custom_bsdf.hpp>
#include <zraka/materials/scatter.hpp>

#include <memory>
#include <optional>

namespace zraka {

// What a custom BSDF sees of a hit: the point, uv and a frame around the facing normal.
template <class T> bsdf_frame frame_at(const hit_t<T>& h) {
  return bsdf_frame::around(vec3(h.p), vec2(h.uv), vec3(h.facing_normal()), h.front_face);
}

namespace material_kinds {

struct custom {
  static constexpr const char* name = "custom";
  static constexpr bool has_density = true;  // custom_bsdf.hpp: eval and pdf
  static constexpr bool is_specular = false;
  std::shared_ptr<const custom_bsdf> bsdf;  // never null (material::custom checks)

  template <class T>
  std::optional<scatter_t<T>> sample(const vec3_t<T>& d, const hit_t<T>& h, const vec2& u, double u_lobe) const {
    const auto sm = bsdf->sample(frame_at(h), vec3(-d), vec3(u, u_lobe));
    if (!sm || !(sm->pdf > 0)) return std::nullopt;  // lost below the surface: absorbed
    return scatter_t<T>{vec3_t<T>(sm->wi), rgb(sm->weight), T(sm->pdf), false};
  }
  template <class T> rgb f_cos(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const vec3_t<T> n = h.facing_normal();
    return rgb(vec3_t<T>(bsdf->eval(frame_at(h), vec3(wo), vec3(wi))) * std::max(T(0), glm::dot(n, wi)));
  }
  template <class T> T pdf(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    return T(bsdf->pdf(frame_at(h), vec3(wo), vec3(wi)));
  }
};

}  // namespace material_kinds
}  // namespace zraka

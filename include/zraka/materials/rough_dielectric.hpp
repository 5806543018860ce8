#pragma once
// Rough glass (book 5.4; Walter et al. 2007): GGX microfacets (microfacet.hpp) between two
// indices, ior = n_inside / n_outside as for dielectric.hpp, but not 1 (no interface to be rough:
// the light would pass straight on, a direction without a density).
#include <zraka/core/hit.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/materials/microfacet.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/materials/roughness.hpp>
#include <zraka/materials/scatter.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct rough_dielectric {
  static constexpr const char* name = "rough_dielectric";
  static constexpr bool has_density = true;
  static constexpr bool is_specular = false;
  static constexpr bool is_microfacet = true;
  ggx_roughness roughness;
  double ior = 1.5;

  // In the local frame of the facing normal; eta = eta_t / eta_i is the index across the
  // surface over the one on wo's side.
  template <class T> rough_dielectric_t<T> bsdf(const hit_t<T>& h) const {
    return {ggx_t<T>(roughness.at(h)), T(1) / relative_ior(h.front_face, T(ior))};
  }
  // A visible GGX normal from u; the lobe (reflect or refract) from u_lobe.
  template <class T>
  std::optional<scatter_t<T>> sample(const vec3_t<T>& d, const hit_t<T>& h, const vec2& u, double u_lobe) const {
    const onb_t<T> b(h.facing_normal());
    const auto sm = bsdf(h).sample(b.to_local(-d), vec2_t<T>(u), T(u_lobe));
    if (!sm) return std::nullopt;  // sent below the surface by a facet: absorbed
    return scatter_t<T>{b.to_world(sm->wi), sm->weight, sm->pdf, false};
  }
  template <class T> rgb f_cos(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const onb_t<T> b(h.facing_normal());
    const vec3_t<T> lo = b.to_local(wo), li = b.to_local(wi);  // wi may be below: refraction
    return rgb(float(bsdf(h).f(lo, li) * std::abs(li.z)));
  }
  template <class T> T pdf(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const onb_t<T> b(h.facing_normal());
    return bsdf(h).pdf(b.to_local(wo), b.to_local(wi));
  }

  static constexpr int gpu_kind = 6;  // KIND_ROUGH_DIELECTRIC
  template <class Packer> void pack(Packer& p) const {
    roughness.pack(p);
    p.record.ior = float(ior);
  }

  static std::vector<std::string> keys() { return {"roughness", "ior"}; }
  template <class Node> static rough_dielectric read(const Node& n, material_common&) {
    rough_dielectric k;
    k.roughness = ggx_roughness::read(n);
    if (n.has("ior")) {
      k.ior = n.number("ior");
      if (!(k.ior > 0) || k.ior == 1)
        n.fail("ior", "must be positive and not 1 (no interface to be rough), got " + n.scalar("ior"));
    }
    return k;
  }
  template <class Writer> void write(Writer& w, const material_common&) const {
    roughness.write(w);
    w.number("ior", ior);
  }
};

}  // namespace zraka::material_kinds

#pragma once
// A rough metal (book 5.4): GGX microfacets (microfacet.hpp) over a conductor given by its
// complex index per channel, a preset by name, or an RGB F0 with Schlick's approximation.
// It has a density: lights are sampled at it.
#include <zraka/core/hit.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/materials/microfacet.hpp>
#include <zraka/materials/roughness.hpp>
#include <zraka/materials/scatter.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct rough_conductor {
  static constexpr const char* name = "rough_conductor";
  static constexpr bool has_density = true;
  static constexpr bool is_specular = false;
  static constexpr bool is_microfacet = true;  // a glossy lobe: Whitted cannot shade it
  ggx_roughness roughness;
  conductor_fresnel conductor;  // eta + i k per channel (silver by default), or F0

  // The BSDF at a hit, in the local frame of its facing normal.
  template <class T> rough_conductor_t<T> bsdf(const hit_t<T>& h) const {
    return {ggx_t<T>(roughness.at(h)), conductor};
  }
  // A visible GGX normal from u; the third number is not used.
  template <class T>
  std::optional<scatter_t<T>> sample(const vec3_t<T>& d, const hit_t<T>& h, const vec2& u, double) const {
    const onb_t<T> b(h.facing_normal());
    const auto sm = bsdf(h).sample(b.to_local(-d), vec2_t<T>(u));
    if (!sm) return std::nullopt;  // sent below the surface by a facet: absorbed
    return scatter_t<T>{b.to_world(sm->wi), sm->weight, sm->pdf, false};
  }
  template <class T> rgb f_cos(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const onb_t<T> b(h.facing_normal());
    const vec3_t<T> lo = b.to_local(wo), li = b.to_local(wi);
    return bsdf(h).f(lo, li) * float(std::abs(li.z));
  }
  template <class T> T pdf(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const onb_t<T> b(h.facing_normal());
    return bsdf(h).pdf(b.to_local(wo), b.to_local(wi));
  }

  static constexpr int gpu_kind = 5;  // KIND_ROUGH_CONDUCTOR
  template <class Packer> void pack(Packer& p) const {
    roughness.pack(p);
    p.record.schlick = conductor.schlick ? 1 : 0;  // Schlick's F0 travels in eta
    p.record.eta = p.colour(conductor.schlick ? conductor.f0 : conductor.eta);
    p.record.k = p.colour(conductor.k);
  }

  static std::vector<std::string> keys() { return {"roughness", "metal", "eta", "k", "f0"}; }
  // [listing scene-rough-conductor]
  // At most one of: metal (a preset of microfacet.hpp), eta and k (the complex index per
  // channel), or f0 (the colour at normal incidence, Schlick); none: silver.
  template <class Node> static rough_conductor read(const Node& n, material_common&) {
    rough_conductor k;
    k.roughness = ggx_roughness::read(n);
    k.conductor = read_fresnel(n, "rough_conductor");
    return k;
  }
  template <class Node> static conductor_fresnel read_fresnel(const Node& n, const std::string& kind) {
    const int given = (n.has("metal") ? 1 : 0) + (n.has("eta") || n.has("k") ? 1 : 0) + (n.has("f0") ? 1 : 0);
    if (given > 1) n.fail("a " + kind + " takes one of: metal, eta and k, f0");
    if (!given) return *find_metal("silver");
    if (n.has("metal")) {
      const std::string metal = n.text("metal", "");
      const auto f = find_metal(metal);
      if (!f) n.fail("metal", "unknown metal '" + metal + "' (expected " + metal_names() + ")");
      return *f;
    }
    if (n.has("f0")) {
      const rgb f0 = n.colour("f0");
      if (max_component(f0) > 1) n.fail("f0", "a reflectance must be at most 1");
      return conductor_fresnel::from_f0(f0);
    }
    const rgb eta = n.colour("eta"), k = n.colour("k");
    if (!(eta.x > 0 && eta.y > 0 && eta.z > 0)) n.fail("eta", "must be positive");
    return conductor_fresnel::complex_ior(eta, k);
  }
  // [end]
  template <class Writer> void write(Writer& w, const material_common&) const {
    roughness.write(w);
    write_fresnel(w, conductor);
  }
  // A preset is written as its numbers.
  template <class Writer> static void write_fresnel(Writer& w, const conductor_fresnel& f) {
    if (f.schlick) {
      w.colour("f0", f.f0);
    } else {
      w.colour("eta", f.eta);
      w.colour("k", f.k);
    }
  }
};

}  // namespace zraka::material_kinds

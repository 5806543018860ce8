#pragma once
// Materials (book 1.7-1.9, 2.3, 5.4): what a surface does with light. This file closes the
// family: the list of kinds, each one file of this folder (README.md), and the few functions a
// renderer asks of a material, each dispatched to the kind:
//   emitted(m, h)                 light the surface gives off towards the ray;
//   scatter(m, d, h, g)           a new direction and the path weight f cos / pdf, or none when
//                                 the light is absorbed;
//   brdf_cos(m, h, wo, wi)        f(wo, wi) |cos theta_i| for light sampling (next-event
//                                 estimation); zero for the kinds without a density (a mirror
//                                 reflects one direction only);
//   scatter_pdf(m, h, wo, wi)     the density scatter() samples wi with, for multiple importance
//                                 sampling; zero without a density;
//   is_specular(m), has_density(m), is_index_matched(m), kind_name(m.kind).
// Directions: d is the incoming ray direction (towards the surface), wo = -d, wi points away.
// A material is a kind (a std::variant of the kinds' structs, each holding its own parameters)
// plus what every material has (material_common: it may glow, from the front face or from both
// faces when two_sided is set, and it may enclose a medium). A course's BSDF is the kind custom
// (custom.hpp); renderers that cannot run it (whitted.hpp, the OpenCL kernel) refuse it by name.
// Scene files find the kinds by name through scene_registry.hpp; builtin.hpp registers them.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/conductor.hpp>
#include <zraka/materials/custom.hpp>
#include <zraka/materials/dielectric.hpp>
#include <zraka/materials/emitter.hpp>
#include <zraka/materials/lambertian.hpp>
#include <zraka/materials/metal.hpp>
#include <zraka/materials/phong.hpp>
#include <zraka/materials/rough_conductor.hpp>
#include <zraka/materials/rough_dielectric.hpp>
#include <zraka/materials/scatter.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>

namespace zraka {

// [listing material-kinds]
// The kinds, closed here: a new built-in kind is one file, one line here and one in builtin.hpp.
using material_kind = std::variant<material_kinds::lambertian, material_kinds::fuzzy_metal,
                                   material_kinds::dielectric, material_kinds::emitter, material_kinds::phong,
                                   material_kinds::rough_conductor, material_kinds::rough_dielectric,
                                   material_kinds::conductor, material_kinds::custom>;

struct material : material_common {
  material_kind kind;  // lambertian of albedo 0.8 by default

  template <class K> bool is() const { return std::holds_alternative<K>(kind); }
  template <class K> const K* get() const { return std::get_if<K>(&kind); }  // null: another kind
  template <class K> K* get() { return std::get_if<K>(&kind); }
  // [end]

  static material lambertian(rgb albedo) { return lambertian(texture::solid(albedo)); }
  static material lambertian(texture albedo) { return of(material_kinds::lambertian{albedo}); }
  static material fuzzy_metal(rgb albedo, double fuzz) {
    return of(material_kinds::fuzzy_metal{texture::solid(albedo), fuzz});
  }
  static material mirror(rgb albedo = rgb(1)) { return fuzzy_metal(albedo, 0.0); }
  // ior = n_inside / n_outside: 1.5 a glass ball in air, 1/1.5 an air bubble in glass.
  static material dielectric(double ior) {
    if (!(ior > 0) || !std::isfinite(ior))
      throw error("dielectric: the index of refraction must be positive, got " + std::to_string(ior));
    return of(material_kinds::dielectric{ior});
  }
  static material emitter(rgb radiance, bool two_sided = false) {
    if (!is_finite(radiance) || radiance.x < 0 || radiance.y < 0 || radiance.z < 0)
      throw error("emitter: radiance must be finite and not negative");
    material m = of(material_kinds::emitter{});
    m.radiance = radiance;
    m.two_sided = two_sided;
    return m;
  }
  static material custom(std::shared_ptr<const custom_bsdf> f) {
    if (!f) throw error("custom: the BSDF must not be null");
    return of(material_kinds::custom{std::move(f)});
  }
  // Rough metal; roughness is the GGX alpha in (0, 1] (microfacet.hpp). A preset by name:
  // rough_conductor(0.2, *find_metal("gold")); an RGB F0: conductor_fresnel::from_f0(...).
  static material rough_conductor(double roughness, const conductor_fresnel& f) {
    check_roughness(roughness, "rough_conductor");
    return of(material_kinds::rough_conductor{{roughness, {}}, f});
  }
  // Rough glass; ior = n_inside / n_outside as for dielectric(), but not 1 (no interface to be
  // rough: the light would pass straight on, a direction without a density).
  static material rough_dielectric(double roughness, double ior) {
    check_roughness(roughness, "rough_dielectric");
    if (!(ior > 0) || !std::isfinite(ior) || ior == 1)
      throw error("rough_dielectric: the index of refraction must be positive and not 1, got " + std::to_string(ior));
    return of(material_kinds::rough_dielectric{{roughness, {}}, ior});
  }
  static void check_roughness(double r, const char* kind) {
    if (!(r > 0 && r <= 1))
      throw error(std::string(kind) + ": roughness (the GGX alpha) must be in (0, 1], got " + std::to_string(r));
  }
  // A boundary only (book 6.1): an index-matched interface (a dielectric of ior 1) that rays
  // cross unchanged; it marks where a medium begins (interior) without refracting.
  static material boundary(int interior_medium) {
    material m = dielectric(1.0);
    m.interior = interior_medium;
    return m;
  }
  static material phong(rgb kd, rgb ks, double shininess) { return of(material_kinds::phong{kd, ks, shininess}); }
  // A material of kind k that does not glow.
  template <class K> static material of(K k) {
    material m;
    m.kind = std::move(k);
    return m;
  }
};

// Mirror, fuzzy metal and glass scatter into a direction (or a narrow lobe) that light sampling
// cannot hit by chance: renderers skip next-event estimation there and follow the scattered ray.
inline bool is_specular(const material& m) {
  return std::visit([](const auto& k) { return k.is_specular; }, m.kind);
}
// Does brdf_cos() give anything to sample lights with? (Lambert, Phong, microfacets, custom.)
inline bool has_density(const material& m) {
  return std::visit([](const auto& k) { return k.has_density; }, m.kind);
}
// A glossy microfacet lobe (book 5.4): neither a mirror nor a local model.
inline bool is_microfacet(const material& m) {
  return std::visit([](const auto& k) { return requires { k.is_microfacet; }; }, m.kind);
}
// The kind's name in scene files and messages: "rough_conductor", "metal", "custom".
inline const char* kind_name(const material_kind& k) {
  return std::visit([](const auto& x) { return x.name; }, k);
}
inline bool is_custom(const material& m) { return m.is<material_kinds::custom>(); }

// One-sided emitters shine from their front face only (a quad light faces along its normal).
template <class T> rgb emitted(const material& m, const hit_t<T>& h) {
  return h.front_face || m.two_sided ? m.radiance : rgb(0);
}
inline bool emits(const material& m) { return m.radiance != rgb(0); }
// Index-matched: light crosses it unchanged (media.hpp lets paths and shadow rays through).
inline bool is_index_matched(const material& m) {
  const auto* d = m.get<material_kinds::dielectric>();
  return d && d->index_matched() && !emits(m);
}

// [listing brdf-cos]
template <class T>
rgb brdf_cos(const material& m, const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) {
  return std::visit([&](const auto& k) {
    if constexpr (std::decay_t<decltype(k)>::has_density) return k.f_cos(h, wo, wi);  // glass: wi may be below
    else return rgb(0);
  }, m.kind);
}
// [end]

template <class T>
T scatter_pdf(const material& m, const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) {
  return std::visit([&](const auto& k) {
    if constexpr (std::decay_t<decltype(k)>::has_density) return k.pdf(h, wo, wi);
    else return T(0);
  }, m.kind);
}

// [listing scatter]
template <class T>
std::optional<scatter_t<T>> scatter(const material& m, const vec3_t<T>& d, const hit_t<T>& h, rng& g) {
  return std::visit([&](const auto& k) -> std::optional<scatter_t<T>> {
    if constexpr (std::decay_t<decltype(k)>::has_density) {
      // Every surface with a density draws three numbers, two for the direction and one for a
      // lobe, whether it uses the third or not: the path's later numbers then do not depend on
      // which material it met (a custom Lambert gives the built-in one's paths bit for bit).
      const vec2 u = g.uniform2();
      const double u_lobe = g.uniform();
      return k.sample(d, h, u, u_lobe);
    } else {
      return k.scatter(d, h, g);  // a mirror, glass or an emitter: draws what it needs
    }
  }, m.kind);
}
// [end]

// Compiled once at double (compiled.hpp).
ZRAKA_INSTANCE(std::optional<scatter_t<double>> scatter(const material&, const vec3_t<double>&,
                                                        const hit_t<double>&, rng&))
ZRAKA_INSTANCE(rgb brdf_cos(const material&, const hit_t<double>&, const vec3_t<double>&,
                            const vec3_t<double>&))
ZRAKA_INSTANCE(double scatter_pdf(const material&, const hit_t<double>&, const vec3_t<double>&,
                                  const vec3_t<double>&))

}  // namespace zraka

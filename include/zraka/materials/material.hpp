#pragma once
// Materials (book 1.7-1.9, 2.3): plain data saying what a surface does with light, plus the few
// functions a renderer asks of it:
//   emitted(m, h)                 light the surface gives off towards the ray (emitters only);
//   scatter(m, d, h, g)           a new direction and the path weight f cos / pdf, or none when
//                                 the light is absorbed;
//   brdf_cos(m, h, wo, wi)        f(wo, wi) |cos theta_i| for light sampling (next-event
//                                 estimation); zero for the specular materials, which have no
//                                 density to evaluate (a mirror reflects one direction only);
//   scatter_pdf(m, h, wo, wi)     the density scatter() samples wi with, for multiple importance
//                                 sampling; zero for the specular materials.
// Directions: d is the incoming ray direction (towards the surface), wo = -d, wi points away.
// The kinds follow the book: lambertian (cosine-weighted, erratum C1), fuzzy_metal (the thesis's
// "diffuse", RTIOW's fuzzy metal; a mirror is fuzz 0), dielectric (glass, exact Fresnel and
// total internal reflection; an IOR below 1 is a hollow, e.g. an air bubble in glass at
// 1/1.5), emitter (an area light, black) and phong (kd, ks, shininess: the local model of book
// 1.9 for the Whitted tracer, and its energy-normalised BRDF for path tracing).
// Book 5.4 adds two microfacet kinds (microfacet.hpp; GGX, `roughness` is the GGX alpha as
// Mitsuba's): rough_conductor (a metal by its complex index per channel, a preset, or an RGB F0
// with Schlick) and rough_dielectric (rough glass, Walter et al. 2007). They have densities:
// lights are sampled at them. fuzzy_metal stays as RTIOW's model, which is not a BRDF one can
// evaluate; a rough conductor is the physically based metal.
// Any material may also glow: `radiance` is emitted from the front face, or from both faces
// when `two_sided` is set (book 2.3's furnace: a Lambertian sphere that glows inwards).
// A material is data, so a scene file can describe it field by field; the one exception is
// `bsdf`, a user-defined BSDF (custom_bsdf.hpp) that, when set, replaces the kind's reflection in
// scatter(), brdf_cos() and scatter_pdf() (material::custom). Renderers that cannot run one
// (whitted.hpp, the OpenCL kernel) refuse it by name: is_custom().
#include <zraka/materials/bxdf.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/materials/custom_bsdf.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/materials/microfacet.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/sampling.hpp>
#include <zraka/textures/texture.hpp>

#include <cmath>
#include <memory>
#include <optional>
#include <string>

namespace zraka {

enum class material_kind { lambertian, fuzzy_metal, dielectric, emitter, phong, rough_conductor, rough_dielectric };

struct material {
  material_kind kind = material_kind::lambertian;
  texture albedo = texture::solid(rgb(0.8f));  // lambertian, fuzzy_metal
  double fuzz = 0;                             // fuzzy_metal: 0 = mirror
  double ior = 1.5;                            // dielectric: index inside (outside is 1)
  rgb radiance{0};                             // emitted (emitter, or any glowing surface)
  bool two_sided = false;                      // emit from the back face too
  rgb kd{0.8f}, ks{0.2f};                      // phong
  double shininess = 32;                       // phong exponent p
  std::shared_ptr<const custom_bsdf> bsdf;     // set: a user-defined BSDF (custom_bsdf.hpp)
  double roughness = 0.1;                      // rough_*: the GGX alpha (microfacet.hpp), (0, 1]
  std::optional<texture> roughness_map;        // rough_*: set, alpha varies over the surface (alpha_at)
  conductor_fresnel conductor;                 // rough_conductor: eta + i k per channel, or F0
  int interior = -1;  // media (book 6.1): scene.media index inside this closed shape; -1 no change

  static material lambertian(rgb albedo) { return lambertian(texture::solid(albedo)); }
  static material lambertian(texture albedo) {
    material m;
    m.albedo = albedo;
    return m;
  }
  static material fuzzy_metal(rgb albedo, double fuzz) {
    material m;
    m.kind = material_kind::fuzzy_metal;
    m.albedo = texture::solid(albedo);
    m.fuzz = fuzz;
    return m;
  }
  static material mirror(rgb albedo = rgb(1)) { return fuzzy_metal(albedo, 0.0); }
  // ior = n_inside / n_outside: 1.5 a glass ball in air, 1/1.5 an air bubble in glass.
  static material dielectric(double ior) {
    if (!(ior > 0) || !std::isfinite(ior))
      throw error("dielectric: the index of refraction must be positive, got " + std::to_string(ior));
    material m;
    m.kind = material_kind::dielectric;
    m.ior = ior;
    return m;
  }
  static material emitter(rgb radiance, bool two_sided = false) {
    if (!is_finite(radiance) || radiance.x < 0 || radiance.y < 0 || radiance.z < 0)
      throw error("emitter: radiance must be finite and not negative");
    material m;
    m.kind = material_kind::emitter;
    m.radiance = radiance;
    m.two_sided = two_sided;
    m.albedo = texture::solid(rgb(0));
    return m;
  }
  static material custom(std::shared_ptr<const custom_bsdf> f) {
    if (!f) throw error("custom: the BSDF must not be null");
    material m;
    m.bsdf = std::move(f);
    return m;
  }
  // Rough metal; roughness is the GGX alpha in (0, 1] (microfacet.hpp). A preset by name:
  // rough_conductor(0.2, *find_metal("gold")); an RGB F0: conductor_fresnel::from_f0(...).
  static material rough_conductor(double roughness, const conductor_fresnel& f) {
    check_roughness(roughness, "rough_conductor");
    material m;
    m.kind = material_kind::rough_conductor;
    m.roughness = roughness;
    m.conductor = f;
    return m;
  }
  // Rough glass; ior = n_inside / n_outside as for dielectric(), but not 1 (no interface to be
  // rough: the light would pass straight on, a direction without a density).
  static material rough_dielectric(double roughness, double ior) {
    check_roughness(roughness, "rough_dielectric");
    if (!(ior > 0) || !std::isfinite(ior) || ior == 1)
      throw error("rough_dielectric: the index of refraction must be positive and not 1, got " + std::to_string(ior));
    material m;
    m.kind = material_kind::rough_dielectric;
    m.roughness = roughness;
    m.ior = ior;
    return m;
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
  static material phong(rgb kd, rgb ks, double shininess) {
    material m;
    m.kind = material_kind::phong;
    m.kd = kd;
    m.ks = ks;
    m.shininess = shininess;
    return m;
  }
};

// Mirror, fuzzy metal and glass scatter into a direction (or a narrow lobe) that light sampling
// cannot hit by chance: renderers skip next-event estimation there and follow the scattered ray.
inline bool is_specular(const material& m) {
  if (m.bsdf) return false;  // a custom BSDF has a density (custom_bsdf.hpp)
  return m.kind == material_kind::fuzzy_metal || m.kind == material_kind::dielectric;
}
inline bool is_microfacet(const material& m) {
  return !m.bsdf && (m.kind == material_kind::rough_conductor || m.kind == material_kind::rough_dielectric);
}
// Does brdf_cos() give anything to sample lights with? (Lambert, Phong, microfacets, custom.)
inline bool has_density(const material& m) {
  return m.bsdf || m.kind == material_kind::lambertian || m.kind == material_kind::phong || is_microfacet(m);
}
// The material's name in messages: "rough_conductor".
inline const char* kind_name(material_kind k) {
  switch (k) {
    case material_kind::lambertian: return "lambertian";
    case material_kind::fuzzy_metal: return "metal";
    case material_kind::dielectric: return "dielectric";
    case material_kind::emitter: return "emitter";
    case material_kind::phong: return "phong";
    case material_kind::rough_conductor: return "rough_conductor";
    case material_kind::rough_dielectric: return "rough_dielectric";
  }
  return "?";
}
inline bool is_custom(const material& m) { return bool(m.bsdf); }

// What a custom BSDF sees of a hit: the point, uv and a frame around the facing normal.
template <class T> bsdf_frame frame_at(const hit_t<T>& h) {
  return bsdf_frame::around(vec3(h.p), vec2(h.uv), vec3(h.facing_normal()), h.front_face);
}

// One-sided emitters shine from their front face only (a quad light faces along its normal).
template <class T> rgb emitted(const material& m, const hit_t<T>& h) {
  return h.front_face || m.two_sided ? m.radiance : rgb(0);
}
inline bool emits(const material& m) { return m.radiance != rgb(0); }
// Index-matched: light crosses it unchanged (media.hpp lets paths and shadow rays through).
inline bool is_index_matched(const material& m) {
  return !m.bsdf && m.kind == material_kind::dielectric && m.ior == 1.0 && !emits(m);
}

template <class T> struct scatter_t {
  vec3_t<T> direction;  // unit, away from the surface
  rgb weight;           // f |cos| / pdf, what the path throughput is multiplied by
  T pdf = T(0);         // density of direction; 0 for specular (a delta, not evaluable)
  bool specular = false;
};

// The BRDF of a non-specular material at a hit: Lambert (rho/pi, with the texture's albedo
// there) or, for phong, Lambert plus the energy-normalised Phong lobe (bxdf.hpp). The local
// model's (V.R)^p is not a BRDF; a path tracer uses this normalised form of the same lobe.
template <class T> lambert_phong_brdf_t<T> brdf_at(const material& m, const hit_t<T>& h) {
  lambert_phong_brdf_t<T> f;
  if (m.kind == material_kind::lambertian) {
    f.diffuse.rho = vec3_t<T>(evaluate(m.albedo, h.p, h.facing_normal(), h.uv));
    f.glossy.rho_s = vec3_t<T>(0);
  } else {
    f.diffuse.rho = vec3_t<T>(m.kd);
    f.glossy.rho_s = vec3_t<T>(m.ks);
    f.glossy.s = T(m.shininess);
  }
  return f;
}

// [listing roughness-texture]
// The GGX alpha at a hit: the material's number, or its roughness texture there (the mean of the
// texture's three channels). A texel of 0 would be a mirror that the microfacet samplers cannot
// evaluate, so alpha is kept at 0.001 or more, the sharpest the chi-square tests cover.
template <class T> T alpha_at(const material& m, const hit_t<T>& h) {
  if (!m.roughness_map) return T(m.roughness);
  const rgb c = evaluate(*m.roughness_map, h.p, h.facing_normal(), h.uv);
  return T(std::clamp((double(c.x) + double(c.y) + double(c.z)) / 3, 1e-3, 1.0));
}
// [end]

// The microfacet BSDFs of a hit work in the local frame of its facing normal (microfacet.hpp);
// the glass's eta = eta_t / eta_i is the index across the surface over the one on wo's side.
template <class T> rough_dielectric_t<T> rough_glass_at(const material& m, const hit_t<T>& h) {
  return {ggx_t<T>(alpha_at(m, h)), T(1) / relative_ior(h.front_face, T(m.ior))};
}
template <class T> rough_conductor_t<T> rough_metal_at(const material& m, const hit_t<T>& h) {
  return {ggx_t<T>(alpha_at(m, h)), m.conductor};
}
template <class T>
rgb microfacet_f_cos(const material& m, const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) {
  const onb_t<T> b(h.facing_normal());
  const vec3_t<T> lo = b.to_local(wo), li = b.to_local(wi);
  if (m.kind == material_kind::rough_conductor)
    return rough_metal_at(m, h).f(lo, li) * float(std::abs(li.z));
  return rgb(float(rough_glass_at(m, h).f(lo, li) * std::abs(li.z)));
}
template <class T>
T microfacet_pdf(const material& m, const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) {
  const onb_t<T> b(h.facing_normal());
  const vec3_t<T> lo = b.to_local(wo), li = b.to_local(wi);
  if (m.kind == material_kind::rough_conductor)
    return rough_metal_at(m, h).pdf(lo, li);
  return rough_glass_at(m, h).pdf(lo, li);
}

// [listing brdf-cos]
template <class T>
rgb brdf_cos(const material& m, const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) {
  if (m.bsdf) {
    const vec3_t<T> n = h.facing_normal();
    return rgb(vec3_t<T>(m.bsdf->eval(frame_at(h), vec3(wo), vec3(wi))) * std::max(T(0), glm::dot(n, wi)));
  }
  if (is_microfacet(m)) return microfacet_f_cos(m, h, wo, wi);  // glass: wi may be below
  if (m.kind != material_kind::lambertian && m.kind != material_kind::phong) return rgb(0);
  const vec3_t<T> n = h.facing_normal();
  return rgb(brdf_at(m, h).eval(wi, wo, n) * std::max(T(0), glm::dot(n, wi)));
}
// [end]

template <class T>
T scatter_pdf(const material& m, const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) {
  if (m.bsdf) return T(m.bsdf->pdf(frame_at(h), vec3(wo), vec3(wi)));
  if (is_microfacet(m)) return microfacet_pdf(m, h, wo, wi);
  if (m.kind != material_kind::lambertian && m.kind != material_kind::phong) return T(0);
  return brdf_at(m, h).pdf(wi, wo, h.facing_normal());
}

// [listing scatter]
template <class T>
std::optional<scatter_t<T>> scatter(const material& m, const vec3_t<T>& d, const hit_t<T>& h, rng& g) {
  const vec3_t<T> n = h.facing_normal();  // on the side the ray came from
  if (m.kind == material_kind::emitter && !m.bsdf) return std::nullopt;
  if (has_density(m)) {
    // Every surface with a density draws three numbers, two for the direction and one for a
    // lobe, whether it uses the third or not: the path's later numbers then do not depend on
    // which material it met (a custom Lambert gives the built-in one's paths bit for bit).
    const vec2 u = g.uniform2();
    const double u_lobe = g.uniform();
    if (m.bsdf) {  // user-defined (custom_bsdf.hpp)
      const auto sm = m.bsdf->sample(frame_at(h), vec3(-d), vec3(u, u_lobe));
      if (!sm || !(sm->pdf > 0)) return std::nullopt;  // lost below the surface: absorbed
      return scatter_t<T>{vec3_t<T>(sm->wi), rgb(sm->weight), T(sm->pdf), false};
    }
    if (m.kind == material_kind::lambertian) {  // cosine-weighted: f cos / pdf = albedo exactly
      const lambert_brdf_t<T> f{vec3_t<T>(evaluate(m.albedo, h.p, n, h.uv))};
      const auto sm = f.sample(-d, n, vec2_t<T>(u));
      if (!sm) return std::nullopt;  // grazing: d along the surface, or rounding on the horizon
      return scatter_t<T>{sm->wi, rgb(sm->weight), sm->pdf, false};
    }
    if (is_microfacet(m)) {  // a visible GGX normal (u); the glass picks its lobe with u_lobe
      const onb_t<T> b(n);
      const vec3_t<T> wo = b.to_local(-d);
      const auto sm = m.kind == material_kind::rough_conductor
                          ? rough_metal_at(m, h).sample(wo, vec2_t<T>(u))
                          : rough_glass_at(m, h).sample(wo, vec2_t<T>(u), T(u_lobe));
      if (!sm) return std::nullopt;  // sent below the surface by a facet: absorbed
      return scatter_t<T>{b.to_world(sm->wi), sm->weight, sm->pdf, false};
    }
    // phong: Lambert + normalised Phong, sampled as their mixture (bxdf.hpp reuses u for the lobe)
    const auto sm = brdf_at(m, h).sample(-d, n, vec2_t<T>(u));
    if (!sm) return std::nullopt;  // sampled below the surface: absorbed
    return scatter_t<T>{sm->wi, rgb(sm->weight), sm->pdf, false};
  }
  switch (m.kind) {
    case material_kind::fuzzy_metal: {  // mirror direction + fuzz * point in the unit ball
      // One full-expression per draw: a constructor's arguments are evaluated in no fixed order.
      const T u0 = T(g.uniform()), u1 = T(g.uniform()), u2 = T(g.uniform());
      const vec3_t<T> ball = sample_unit_ball(vec3_t<T>(u0, u1, u2));
      const auto wi = fuzzy_mirror(d, n, T(m.fuzz), ball);
      if (!wi) return std::nullopt;  // pushed below the surface: absorbed
      return scatter_t<T>{*wi, evaluate(m.albedo, h.p, n, h.uv), T(0), true};
    }
    // Glass: reflect with probability R (exact Fresnel), else refract; the weight is 1 either way.
    // The eta^2 change of radiance across the boundary is left out: it cancels for every path
    // that leaves the glass again, which is all of them in the course's scenes.
    case material_kind::dielectric: {
      const T eta = relative_ior(h.front_face, T(m.ior));
      const T cos_i = -glm::dot(d, n);
      const auto t = refract(d, n, eta);  // none on total internal reflection
      if (t && T(g.uniform()) >= fresnel_dielectric(cos_i, eta))
        return scatter_t<T>{*t, rgb(1), T(0), true};
      return scatter_t<T>{reflect(d, n), rgb(1), T(0), true};
    }
    case material_kind::lambertian:
    case material_kind::phong:
    case material_kind::emitter:
    case material_kind::rough_conductor:
    case material_kind::rough_dielectric:
      break;
  }
  return std::nullopt;
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

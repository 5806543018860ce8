#pragma once
// Local illumination (Phong, Blinn-Phong) and BRDFs (book 1.9).
//
// Directions: n is the unit normal on the viewer's side (hit.facing_normal()); l and wi point
// from the surface towards the light, v and wo from the surface towards the viewer; all unit.
//
// Whitted-style shading of one light (book 2.2):
//     const auto k = zraka::phong_terms(n, l, v, m.p);          // or blinn_phong_terms
//     colour += zraka::phong_shade(m, k, light_colour, ambient_colour);
//
// A BRDF f(wi, wo) in a path tracer (book 2.3, 5.3):
//     const zraka::lambert_brdf f{albedo};
//     if (auto s = f.sample(wo, n, g.uniform2())) { throughput *= s->weight; dir = s->wi; }
//     // s->weight = f cos(theta_i) / pdf, here exactly the albedo
// f.eval(wi, wo, n) and f.pdf(wi, wo, n) serve light sampling and MIS.
#include <zraka/materials/optics.hpp>
#include <zraka/sampling/sampling.hpp>

#include <optional>

namespace zraka {

// ---------------------------------------------------------------- Phong and Blinn-Phong (Whitted)
// The two geometric factors of I = I_a rho_a + I (rho_d diffuse + rho_s specular).
template <class T> struct shading_terms_t {
  T diffuse = T(0);   // max(0, N.L)
  T specular = T(0);  // max(0, V.R)^p, or max(0, N.H)^p; 0 when the light is behind
};

// Clamped as erratum A6 asks: a light behind the surface (N.L <= 0) adds nothing, and neither
// does a mirror direction pointing away from the viewer. R = reflect(-L, N) mirrors the
// direction *to* the light.
// [listing phong-terms]
template <class T>
shading_terms_t<T> phong_terms(const vec3_t<T>& n, const vec3_t<T>& l, const vec3_t<T>& v, T p) {
  const T n_l = glm::dot(n, l);
  if (!(n_l > T(0))) return {};
  const vec3_t<T> r = reflect(-l, n);
  return {n_l, std::pow(std::max(T(0), glm::dot(v, r)), p)};
}
// [end]

// Blinn-Phong: the half vector H = (L + V)/|L + V| against N. Its lobe is wider than Phong's
// for the same p (roughly p_Blinn = 4 p_Phong matches the highlight).
// [listing blinn-phong-terms]
template <class T>
shading_terms_t<T> blinn_phong_terms(const vec3_t<T>& n, const vec3_t<T>& l, const vec3_t<T>& v,
                                     T p) {
  const T n_l = glm::dot(n, l);
  if (!(n_l > T(0))) return {};
  const vec3_t<T> h = normalize_or_zero(l + v);  // zero when V = -L: no highlight
  return {n_l, std::pow(std::max(T(0), glm::dot(n, h)), p)};
}
// [end]

// Coefficients of the Phong model; C is a colour (vec3) or a scalar.
template <class T, class C = vec3_t<T>> struct phong_material_t {
  C rho_a{T(0.1)};  // ambient
  C rho_d{T(0.6)};  // diffuse
  C rho_s{T(0.3)};  // specular
  T p = T(32);      // shininess
};
using phong_material = phong_material_t<double>;

template <class T, class C>
C phong_shade(const phong_material_t<T, C>& m, const shading_terms_t<T>& k, const C& light,
              const C& ambient) {
  return ambient * m.rho_a + light * (m.rho_d * k.diffuse + m.rho_s * k.specular);
}

// ---------------------------------------------------------------- BRDFs
// What sample() returns: the direction to follow, f and pdf there, and the path weight
// f cos(theta_i) / pdf (computed in closed form where it simplifies, so it is exact).
template <class T> struct brdf_sample_t {
  vec3_t<T> wi;
  vec3_t<T> f;
  T pdf;
  vec3_t<T> weight;
};

// Both directions above the surface: a BRDF reflects, it does not transmit.
template <class T>
bool same_hemisphere(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) {
  return glm::dot(wi, n) > T(0) && glm::dot(wo, n) > T(0);
}

// Lambert: f = rho / pi. The 1/pi makes the albedo int f cos dw equal rho (book 5.3, A8).
// Cosine-weighted sampling makes the weight f cos / pdf = (rho/pi) cos / (cos/pi) = rho.
// [listing lambert]
template <class T> struct lambert_brdf_t {
  vec3_t<T> rho{T(0.5)};

  vec3_t<T> eval(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) const {
    return same_hemisphere(wi, wo, n) ? rho / pi<T> : vec3_t<T>(0);
  }
  T pdf(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) const {
    return glm::dot(wo, n) > T(0) ? std::max(T(0), glm::dot(wi, n)) / pi<T> : T(0);
  }
  std::optional<brdf_sample_t<T>> sample(const vec3_t<T>& wo, const vec3_t<T>& n,
                                         const vec2_t<T>& u) const {
    if (!(glm::dot(wo, n) > T(0))) return std::nullopt;
    const vec3_t<T> wi = onb_t<T>(n).to_world(sample_cosine_hemisphere(u));
    const T p = pdf(wi, wo, n);
    if (!(p > T(0))) return std::nullopt;  // rounding put wi on the horizon
    return brdf_sample_t<T>{wi, rho / pi<T>, p, rho};
  }
};
// [end]

// The normalised Phong lobe (Lewis 1994; Lafortune and Willems 1994):
//   f = rho_s (s+2)/(2 pi) cos^s(alpha),  alpha = angle between wi and the mirror of wo.
// The (s+2)/(2 pi) makes the albedo exactly rho_s at normal incidence and less elsewhere (part
// of the lobe falls below the horizon), so rho_s <= 1 conserves energy for every s. The
// Whitted-style rho_s (V.R)^p above has albedo 2 pi rho_s/(p+2) at normal incidence instead:
// above rho_s for p < 2 pi - 2, and vanishing for shiny surfaces.
// Sampling follows the lobe, p = (s+1)/(2 pi) cos^s(alpha); directions below the surface are
// rejected (none), so the weight is rho_s (s+2)/(s+1) cos(theta_i).
// [listing phong-brdf]
template <class T> struct phong_brdf_t {
  vec3_t<T> rho_s{T(0.5)};
  T s = T(32);  // shininess

  static vec3_t<T> mirror(const vec3_t<T>& wo, const vec3_t<T>& n) { return reflect(-wo, n); }

  vec3_t<T> eval(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) const {
    if (!same_hemisphere(wi, wo, n)) return vec3_t<T>(0);
    const T c = std::clamp(glm::dot(wi, mirror(wo, n)), T(0), T(1));
    return rho_s * ((s + T(2)) / (T(2) * pi<T>) * std::pow(c, s));
  }
  T pdf(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) const {
    if (!same_hemisphere(wi, wo, n)) return T(0);
    return phong_lobe_t<T>(mirror(wo, n), s).pdf(wi);
  }
  std::optional<brdf_sample_t<T>> sample(const vec3_t<T>& wo, const vec3_t<T>& n,
                                         const vec2_t<T>& u) const {
    if (!(glm::dot(wo, n) > T(0))) return std::nullopt;
    const vec3_t<T> wi = phong_lobe_t<T>(mirror(wo, n), s).sample(u);
    const T cos_i = glm::dot(wi, n);
    const T p = pdf(wi, wo, n);
    if (!(cos_i > T(0)) || !(p > T(0))) return std::nullopt;  // below the surface: absorbed
    return brdf_sample_t<T>{wi, eval(wi, wo, n), p, rho_s * ((s + T(2)) / (s + T(1)) * cos_i)};
  }
};
// [end]

// A plastic-like surface: Lambert plus a normalised Phong lobe, f = rho_d/pi + phong. Energy is
// conserved when rho_d + rho_s <= 1 per channel. Sampled as the mixture of the two densities,
// choosing the lobe in proportion to the mean reflectances (mixture_t in sampling.hpp).
template <class T> struct lambert_phong_brdf_t {
  lambert_brdf_t<T> diffuse;
  phong_brdf_t<T> glossy;

  T glossy_probability() const {
    const T d = glm::dot(diffuse.rho, vec3_t<T>(1)), g = glm::dot(glossy.rho_s, vec3_t<T>(1));
    return d + g > T(0) ? g / (d + g) : T(0);
  }
  mixture_t<phong_lobe_t<T>, cosine_hemisphere_t<T>, T> density(const vec3_t<T>& wo,
                                                                const vec3_t<T>& n) const {
    return {phong_lobe_t<T>(glossy.mirror(wo, n), glossy.s), cosine_hemisphere_t<T>(n),
            glossy_probability()};
  }
  // Without a glossy part (a Lambertian material) the lobe is not evaluated: its term is 0, and
  // the sum and the mixture are then the diffuse term's bits exactly (path tracers call these per
  // bounce, and the lobe's cos^s is a pow).
  vec3_t<T> eval(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) const {
    if (glossy.rho_s == vec3_t<T>(0)) return diffuse.eval(wi, wo, n);
    return diffuse.eval(wi, wo, n) + glossy.eval(wi, wo, n);
  }
  T pdf(const vec3_t<T>& wi, const vec3_t<T>& wo, const vec3_t<T>& n) const {
    if (!same_hemisphere(wi, wo, n)) return T(0);
    // Lambert's own density: both directions are above, so it is the mixture's cos / pi (whose
    // frame's z axis is n) without building that frame.
    if (glossy.rho_s == vec3_t<T>(0)) return diffuse.pdf(wi, wo, n);
    return density(wo, n).pdf(wi);
  }
  std::optional<brdf_sample_t<T>> sample(const vec3_t<T>& wo, const vec3_t<T>& n,
                                         const vec2_t<T>& u) const {
    if (!(glm::dot(wo, n) > T(0))) return std::nullopt;
    const vec3_t<T> wi = density(wo, n).sample(u);
    const T cos_i = glm::dot(wi, n), p = pdf(wi, wo, n);
    if (!(cos_i > T(0)) || !(p > T(0))) return std::nullopt;
    const vec3_t<T> f = eval(wi, wo, n);
    return brdf_sample_t<T>{wi, f, p, f * (cos_i / p)};
  }
};

using lambert_brdf = lambert_brdf_t<double>;
using phong_brdf = phong_brdf_t<double>;
using lambert_phong_brdf = lambert_phong_brdf_t<double>;

}  // namespace zraka

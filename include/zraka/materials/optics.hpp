#pragma once
// Mirror reflection, refraction and Fresnel reflectance (book 1.7 and 1.8).
//
// Conventions. `d` is the unit direction the light travels in (a ray direction: towards the
// surface). `n` is the unit normal on the side d comes from (dot(d, n) <= 0): for a hit use
// hit.facing_normal(). `eta` is the ratio n_incident / n_transmitted of refractive indices, e.g.
// 1/1.5 from air into glass and 1.5 from glass into air; relative_ior() picks it from the face.
//
//     const auto n = h.facing_normal();
//     const double eta = zraka::relative_ior(h.front_face, 1.5);       // glass sphere in air
//     const double cos_i = -glm::dot(d, n);
//     if (auto t = zraka::refract(d, n, eta); t && u >= zraka::fresnel_dielectric(cos_i, eta))
//       next = *t;                                                      // transmitted
//     else
//       next = zraka::reflect(d, n);                                    // reflected (or TIR)
#include <zraka/core/vec.hpp>

#include <algorithm>
#include <optional>

namespace zraka {

// The component of d along n, d.n n, changes sign; the tangential part stays. (d.n is the
// signed length of that component, not an angle: book 1.7, erratum A4.) Works for either
// orientation of n and keeps |d|.
// [listing reflect]
template <class T> vec3_t<T> reflect(const vec3_t<T>& d, const vec3_t<T>& n) {
  return d - T(2) * glm::dot(d, n) * n;
}
// [end]

// RTIOW's "fuzzy metal", which the thesis calls diffuse reflection (erratum C1): the mirror
// direction pushed by fuzz times a point in the unit ball (sample_unit_ball, sampling.hpp). It
// is centred on the mirror direction and so depends on the view; it is not Lambertian for any
// fuzz. The result is normalised; a direction at or below the surface has no meaning for a
// reflection, so none is returned and the caller treats the light as absorbed (erratum B8).
// [listing fuzzy-mirror]
template <class T>
std::optional<vec3_t<T>> fuzzy_mirror(const vec3_t<T>& d, const vec3_t<T>& n, T fuzz,
                                      const vec3_t<T>& in_ball) {
  const vec3_t<T> w = normalize_or_zero(reflect(d, n) + fuzz * in_ball);
  if (!(glm::dot(w, n) > T(0))) return std::nullopt;  // below the surface, or zero length
  return w;
}
// [end]

// eta = n_i / n_t for a hit: entering (front face) the inside index is transmitted, leaving
// (back face) it is the incident one.
template <class T> T relative_ior(bool front_face, T n_inside, T n_outside = T(1)) {
  return front_face ? n_outside / n_inside : n_inside / n_outside;
}

// cos^2 of the transmitted angle: by Snell's law n_i sin(theta_i) = n_t sin(theta_t),
// cos^2(theta_t) = 1 - eta^2 sin^2(theta_i). Negative means there is no transmitted ray: total
// internal reflection. Each case takes the form without cancellation:
//  * eta <= 1 (into a denser medium): (1 - eta)(1 + eta) + (eta cos(theta_i))^2, a sum of two
//    non-negative terms; at grazing incidence 1 - eta^2 (1 - cos^2) would lose every digit, and
//    for eta = 1 this is exactly cos^2(theta_i), so the ray goes straight on;
//  * eta > 1: 1 - eta^2 (1 - c)(1 + c); the sum above would cancel for large eta (1e4).
// [listing cos2-transmitted]
template <class T> T cos2_transmitted(T cos_i, T eta) {
  const T c = std::clamp(cos_i, T(0), T(1));  // a rounding above 1 or below 0 is clamped
  if (eta <= T(1)) return (T(1) - eta) * (T(1) + eta) + (eta * c) * (eta * c);
  return T(1) - eta * eta * ((T(1) - c) * (T(1) + c));
}
// [end]

template <class T> bool total_internal_reflection(T cos_i, T eta) {
  return cos2_transmitted(cos_i, eta) < T(0);
}

// The refracted direction, or none on total internal reflection. With d = d_perp + d_par
// (tangential and normal parts), the transmitted t = eta d_perp - cos(theta_t) n: its tangential
// length is eta sin(theta_i) = sin(theta_t) (Snell) and it is unit. cos(theta_i) is clamped to
// [0,1] (a unit d can give a dot product a rounding above one), and the result is renormalised:
// for large eta the two large terms of t cancel, and a unit direction is part of the contract.
// [listing refract]
template <class T>
std::optional<vec3_t<T>> refract(const vec3_t<T>& d, const vec3_t<T>& n, T eta) {
  const T cos_i = std::clamp(-glm::dot(d, n), T(0), T(1));
  const vec3_t<T> d_perp = d + cos_i * n;  // tangential part, length sin(theta_i)
  // Leaving a denser medium, light gets through only near the normal, where cos_i holds few
  // digits of sin_i: there sin^2(theta_i) is taken from d_perp itself.
  const T cos2_t = eta > T(1) ? T(1) - eta * eta * length2(d_perp) : cos2_transmitted(cos_i, eta);
  if (cos2_t < T(0)) return std::nullopt;  // total internal reflection
  const T cos_t = std::sqrt(cos2_t);
  return normalize_or_zero(eta * d_perp - cos_t * n);
}
// [end]

// Fraction of unpolarised light reflected by a smooth dielectric interface (Fresnel), from the
// amplitude ratios of the two polarisations (s: perpendicular, p: parallel to the plane of
// incidence), R = (r_s^2 + r_p^2)/2. One on total internal reflection; zero for matching media
// (no interface). The transmitted fraction is T = 1 - R (no absorption at the interface).
// [listing fresnel]
template <class T> T fresnel_dielectric(T cos_i, T eta) {
  if (eta == T(1)) return T(0);
  const T ci = std::clamp(cos_i, T(0), T(1));
  const T cos2_t = cos2_transmitted(ci, eta);
  if (cos2_t <= T(0)) return T(1);  // TIR (and its limit, theta_t = 90 deg)
  const T ct = std::sqrt(cos2_t);
  const T r_s = (eta * ci - ct) / (eta * ci + ct);
  const T r_p = (ci - eta * ct) / (ci + eta * ct);
  return std::clamp((r_s * r_s + r_p * r_p) / T(2), T(0), T(1));
}
// [end]

// Schlick's approximation R0 + (1 - R0)(1 - cos)^5 with R0 = ((1 - eta)/(1 + eta))^2. The cosine
// must be that of the angle on the optically thinner side: when leaving the denser medium
// (eta > 1) that is the transmitted angle, and under TIR the reflectance is 1. Using cos_i there,
// as many renderers do, misses TIR entirely (see the table in test_optics.cpp).
// [listing schlick]
template <class T> T fresnel_schlick(T cos_i, T eta) {
  const T ci = std::clamp(cos_i, T(0), T(1));
  T c = ci;
  if (eta > T(1)) {
    const T cos2_t = cos2_transmitted(ci, eta);
    if (cos2_t <= T(0)) return T(1);
    c = std::sqrt(cos2_t);
  }
  const T r0 = ((T(1) - eta) / (T(1) + eta)) * ((T(1) - eta) / (T(1) + eta));
  const T m = T(1) - c, m2 = m * m;
  return r0 + (T(1) - r0) * m2 * m2 * m;
}
// [end]

// The critical angle asin(1/eta) for eta > 1 (leaving the denser medium); none for eta <= 1.
template <class T> std::optional<T> critical_angle(T eta) {
  if (!(eta > T(1))) return std::nullopt;
  return std::asin(T(1) / eta);
}

}  // namespace zraka

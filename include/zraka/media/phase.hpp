#pragma once
// Phase functions (book 6.1): where light goes when a particle of a medium scatters it. A phase
// function p(wo, wi) is a density over the sphere of directions (it integrates to 1), so it is
// its own sampling density: sample() returns pdf = value and the path weight p / pdf = 1.
// Convention: wo points back along the path (away from the scattering point, towards where the
// light goes), wi is the new direction; the scattering angle theta is between the direction of
// travel -wo and wi, cos theta = -dot(wo, wi).
//   isotropic           p = 1 / (4 pi)
//   Henyey-Greenstein   p = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^(3/2)), g in (-1, 1) the
//                       mean cosine: g > 0 forward (fog, milk), g < 0 backward, g = 0 isotropic.
#include <zraka/core/onb.hpp>
#include <zraka/core/vec.hpp>
#include <zraka/sampling/sampling.hpp>

#include <cmath>

namespace zraka {

template <class T> struct phase_sample_t {
  vec3_t<T> wi;
  T pdf;  // = the phase function's value
};

// [listing hg]
template <class T> T henyey_greenstein(T cos_theta, T g) {
  const T denom = T(1) + g * g - T(2) * g * cos_theta;  // (1 - |g|)^2 at its smallest: never 0 for |g| < 1
  return (T(1) - g * g) / (T(4) * pi<T> * denom * std::sqrt(denom));
}

// cos theta by inverting the HG distribution of cos theta; near g = 0 the formula divides 0 by
// 0, and the isotropic inverse is used (the two agree to O(g)).
template <class T> T sample_hg_cos(T u, T g) {
  if (std::abs(g) < T(1e-3)) return T(1) - T(2) * u;
  const T s = (T(1) - g * g) / (T(1) - g + T(2) * g * u);
  return std::clamp((T(1) + g * g - s * s) / (T(2) * g), T(-1), T(1));
}
// [end]

// A phase function: g = 0 is isotropic (its own case, exactly 1 / (4 pi)).
template <class T> struct phase_t {
  T g = T(0);

  T eval(const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    if (g == T(0)) return T(1) / (T(4) * pi<T>);
    return henyey_greenstein(-glm::dot(wo, wi), g);
  }
  T pdf(const vec3_t<T>& wo, const vec3_t<T>& wi) const { return eval(wo, wi); }
  phase_sample_t<T> sample(const vec3_t<T>& wo, const vec2_t<T>& u) const {
    const T cos_t = g == T(0) ? T(1) - T(2) * clamp_unit(u.x) : sample_hg_cos(clamp_unit(u.x), g);
    const T sin_t = std::sqrt(std::max(T(0), T(1) - cos_t * cos_t));
    const T phi = T(2) * pi<T> * u.y;
    const onb_t<T> frame(-wo);  // around the direction of travel
    const vec3_t<T> wi = glm::normalize(frame.to_world({sin_t * std::cos(phi), sin_t * std::sin(phi), cos_t}));
    return {wi, eval(wo, wi)};
  }
};

}  // namespace zraka

#pragma once
// Assignment 02, reference solution: sampling microfacet normals from the GGX (Trowbridge-Reitz)
// distribution, in the local frame where +z is the macro-surface normal.
//
// D(h) = alpha^2 / (pi (alpha^2 cos^2 theta + sin^2 theta)^2), and a normal h is drawn with the
// density p(h) = D(h) cos theta per steradian, which integrates to 1 over the hemisphere. The
// CDF in theta inverts to tan^2 theta = alpha^2 u / (1 - u).
// Numerics: at alpha = 1e-4 the lobe is 1e-4 radians wide, and cos theta there is 1 - 5e-9,
// which float cannot tell from 1. So sin^2 theta comes from x^2 + y^2 (never from 1 - cos^2),
// and cos, sin come from tan theta as 1/sqrt(1 + tan^2), tan/sqrt(1 + tan^2).
#include <zraka/core/vec.hpp>
#include <zraka/sampling/sampling.hpp>

namespace course {

template <class T> struct ggx_t {
  static constexpr T min_alpha = T(1e-4);  // below: a mirror, which has no density
  T alpha = T(0.5);                        // roughness, in [min_alpha, 1]

  T a() const { return std::max(alpha, min_alpha); }

  // The distribution of normals D(h), per steradian of h (not normalised by cos).
  T D(const zraka::vec3_t<T>& h) const {
    if (!(h.z > T(0))) return T(0);
    const T a2 = a() * a();
    const T k = a2 * h.z * h.z + (h.x * h.x + h.y * h.y);  // alpha^2 cos^2 + sin^2 (for unit h)
    return a2 / (zraka::pi<T> * k * k);
  }

  // A unit normal h in the upper hemisphere with density pdf(h); u in [0,1)^2.
  zraka::vec3_t<T> sample(const zraka::vec2_t<T>& u) const {
    const T u0 = zraka::clamp_unit(u.x);
    const T tan_theta = a() * std::sqrt(u0 / (T(1) - u0));
    const T len = std::hypot(T(1), tan_theta);
    const T cos_theta = T(1) / len, sin_theta = tan_theta / len;
    const T phi = T(2) * zraka::pi<T> * zraka::clamp_unit(u.y);
    return {sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta};
  }

  // p(h) = D(h) cos theta, per steradian; 0 below the horizon.
  T pdf(const zraka::vec3_t<T>& h) const { return D(h) * std::max(h.z, T(0)); }
};
using ggx = ggx_t<double>;

}  // namespace course

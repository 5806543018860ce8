#pragma once
// Assignment 02: sample microfacet normals from the GGX (Trowbridge-Reitz) distribution, in the
// local frame where +z is the macro-surface normal. Fill in D(), sample() and pdf(); see
// book/assignments/02-ggx/README.md. Keep the names and signatures: the tests call them.
#include <zraka/core/vec.hpp>
#include <zraka/sampling/sampling.hpp>

namespace course {

template <class T> struct ggx_t {
  static constexpr T min_alpha = T(1e-4);  // below: a mirror, which has no density
  T alpha = T(0.5);                        // roughness, in [min_alpha, 1]

  T a() const { return std::max(alpha, min_alpha); }

  // The distribution of normals D(h), per steradian of h.
  T D(const zraka::vec3_t<T>& h) const {
    (void)h;
    return T(0);  // TODO
  }

  // A unit normal h in the upper hemisphere with density pdf(h); u in [0,1)^2.
  zraka::vec3_t<T> sample(const zraka::vec2_t<T>& u) const {
    (void)u;
    return {T(0), T(0), T(1)};  // TODO
  }

  // The density of sample(), per steradian; 0 below the horizon.
  T pdf(const zraka::vec3_t<T>& h) const {
    (void)h;
    return T(0);  // TODO
  }
};
using ggx = ggx_t<double>;

}  // namespace course

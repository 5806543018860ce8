#pragma once
// Vectors (book 1.0). GLM supplies the types and the dot, cross and length of Def 1.0.4-1.0.6;
// zraka adds only what the book needs beyond them. Every geometric type is a template on the
// scalar T (float or double) so the tests can check both; the short names use double.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

// Inlined by force where the compiler knows how: for the few small routines that run per ray
// and that GCC would rather call (triangle.hpp, quad.hpp, sphere.hpp say what each call cost).
#if defined(__GNUC__)
#define ZRAKA_FORCE_INLINE [[gnu::always_inline]] inline
#else
#define ZRAKA_FORCE_INLINE inline
#endif

namespace zraka {

template <class T> using vec2_t = glm::vec<2, T, glm::defaultp>;
template <class T> using vec3_t = glm::vec<3, T, glm::defaultp>;
template <class T> using mat3_t = glm::mat<3, 3, T, glm::defaultp>;

using vec2 = vec2_t<double>;
using vec3 = vec3_t<double>;
using mat3 = mat3_t<double>;
using vec3f = vec3_t<float>;

template <class T> constexpr T pi = T(3.141592653589793238462643383279502884L);
template <class T> constexpr T infinity = std::numeric_limits<T>::infinity();

// ||v||^2 without the square root.
template <class T> T length2(const vec3_t<T>& v) { return glm::dot(v, v); }

template <class T> bool is_finite(const vec3_t<T>& v) {  // & not &&: no branches
  return std::isfinite(v.x) & std::isfinite(v.y) & std::isfinite(v.z);
}

template <class T> T max_component(const vec3_t<T>& v) { return std::max({v.x, v.y, v.z}); }

// |v| component by component. (glm::abs is x >= 0 ? x : -x, which GCC compiles to a branch for
// each double component: a coin toss in the error bounds computed per ray, which cost a small
// mesh's BVH 8 % of its time, book 5.2. std::abs only clears the sign bit.)
template <class T> vec3_t<T> abs3(const vec3_t<T>& v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }

// [listing normalize]
// v / ||v||, or the zero vector when v is zero or has a NaN or infinite component. Scaling by
// the largest component first keeps ||v||^2 from overflowing (1e200) or underflowing (1e-200).
// That costs three divisions more, so it is done only where ||v||^2 leaves the range in which
// no square can overflow or lose digits that count (2^+-60 in float, 2^+-500 in double); a NaN
// or an infinity falls outside that range too. (The finiteness test comes before the scaling:
// max_component of (1, NaN, 1) is 1, not NaN.)
template <class T> vec3_t<T> normalize_or_zero(const vec3_t<T>& v) {
  constexpr T lo = sizeof(T) == 4 ? T(0x1p-60) : T(0x1p-500), hi = sizeof(T) == 4 ? T(0x1p60) : T(0x1p500);
  if (const T d = glm::dot(v, v); d >= lo && d <= hi) return v / std::sqrt(d);
  if (!is_finite(v)) return vec3_t<T>(0);
  const T m = max_component(abs3(v));
  if (!(m > T(0))) return vec3_t<T>(0);
  const vec3_t<T> s = v / m;
  return s / std::sqrt(glm::dot(s, s));
}
// [end]

}  // namespace zraka

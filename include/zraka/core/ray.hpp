#pragma once
// A ray R(t) = O + t D, t >= 0 (book 1.1).
// Convention: the stored direction is always unit length; the constructor normalises it, as the
// thesis's Remark 1.1.3 asks. So t is a distance. A zero, NaN or infinite direction becomes the
// zero vector, and every intersection routine reports "no hit" for such a ray.
#include <zraka/core/vec.hpp>

namespace zraka {

// [listing ray]
template <class T> struct ray_t {
  vec3_t<T> origin{T(0)};
  vec3_t<T> direction{T(0), T(0), T(1)};  // unit length, or zero for an invalid ray

  ray_t() = default;
  ray_t(const vec3_t<T>& o, const vec3_t<T>& d) : origin(o), direction(normalize_or_zero(d)) {}

  vec3_t<T> at(T t) const { return origin + t * direction; }
  bool valid() const { return direction != vec3_t<T>(0) && is_finite(origin); }
};
// [end]

using ray = ray_t<double>;
using rayf = ray_t<float>;

}  // namespace zraka

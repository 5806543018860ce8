#pragma once
// An orthonormal basis (t, b, n) around a unit normal n, used to turn directions sampled
// around +z into directions around n. This is the branch-free construction of Duff et al.,
// "Building an Orthonormal Basis, Revisited" (JCGT 2017): it has no singular direction, unlike
// the common cross(n, fixed axis) recipe, which fails when n is (anti)parallel to that axis.
#include <zraka/core/vec.hpp>

namespace zraka {

template <class T> struct onb_t {
  vec3_t<T> t, b, n;

  // [listing onb]
  explicit onb_t(const vec3_t<T>& unit_n) : n(unit_n) {
    const T sign = std::copysign(T(1), n.z);
    const T a = T(-1) / (sign + n.z);
    const T c = n.x * n.y * a;
    t = vec3_t<T>(T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x);
    b = vec3_t<T>(c, sign + n.y * n.y * a, -n.y);
  }
  // [end]
  vec3_t<T> to_world(const vec3_t<T>& v) const { return v.x * t + v.y * b + v.z * n; }
  vec3_t<T> to_local(const vec3_t<T>& v) const {
    return {glm::dot(v, t), glm::dot(v, b), glm::dot(v, n)};
  }
};

using onb = onb_t<double>;

}  // namespace zraka

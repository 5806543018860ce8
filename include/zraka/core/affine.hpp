#pragma once
// Affine maps A(x) = B x + u (book 1.0, Def 1.0.3): a linear part B and a translation u.
// Points get both; vectors only B; normals the inverse transpose of B, so they stay
// perpendicular to transformed surfaces.
#include <zraka/core/vec.hpp>

#include <glm/gtc/matrix_transform.hpp>

namespace zraka {

template <class T> struct affine_t {
  mat3_t<T> linear{T(1)};     // B
  vec3_t<T> translation{T(0)};  // u

  // [listing affine-apply]
  vec3_t<T> point(const vec3_t<T>& x) const { return linear * x + translation; }
  vec3_t<T> vector(const vec3_t<T>& v) const { return linear * v; }
  vec3_t<T> normal(const vec3_t<T>& n) const {
    return normalize_or_zero(glm::transpose(glm::inverse(linear)) * n);
  }
  // [end]
  // (this * other)(x) = this(other(x))
  affine_t operator*(const affine_t& other) const {
    return {linear * other.linear, linear * other.translation + translation};
  }
  bool is_linear() const { return translation == vec3_t<T>(0); }

  static affine_t translate(const vec3_t<T>& u) { return {mat3_t<T>(T(1)), u}; }
  static affine_t scale(const vec3_t<T>& s) {
    mat3_t<T> m(T(0));
    m[0][0] = s.x; m[1][1] = s.y; m[2][2] = s.z;
    return {m, vec3_t<T>(0)};
  }
  // Rotation by `radians` about `axis` (right-handed).
  static affine_t rotate(const vec3_t<T>& axis, T radians) {
    const auto m4 = glm::rotate(glm::mat<4, 4, T, glm::defaultp>(T(1)), radians, axis);
    return {mat3_t<T>(m4), vec3_t<T>(0)};
  }
};

using affine = affine_t<double>;

}  // namespace zraka

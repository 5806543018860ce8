#pragma once
// Cubic Bezier curves (book 1.3): P(t) = sum_i b_i^3(t) P_i, t in [0,1], eq. (1.3).
// Two ways to evaluate, which agree to rounding: the Bernstein sum (Listing 1.3) and de Casteljau's
// repeated linear interpolation (Listing 1.4). de Casteljau is not faster (errata A10), but it is
// exact at the ends and on collapsed rows, and its one pass also yields the derivative
// (Lemma 1.4.6).
//
// Every function takes the four control points as std::array<V, 4> with V any glm vector
// (vec2_t<T> for drawing, vec3_t<T> for patches), so T is float or double.
#include <zraka/core/vec.hpp>

#include <array>

namespace zraka {

template <class V> using cubic_t = std::array<V, 4>;  // control points P_0..P_3
template <class V> using scalar_of = typename V::value_type;

// [listing bernstein]
// b_0 = (1-t)^3, b_1 = 3(1-t)^2 t, b_2 = 3(1-t) t^2, b_3 = t^3.
template <class T> std::array<T, 4> bernstein3(T t) {
  const T s = T(1) - t;
  return {s * s * s, T(3) * s * s * t, T(3) * s * t * t, t * t * t};
}
// d/dt b_i^3 = 3 (b_{i-1}^2 - b_i^2): the weights of the derivative (book 1.4; see errata A3).
template <class T> std::array<T, 4> bernstein3_derivative(T t) {
  const T s = T(1) - t;
  return {T(-3) * s * s, T(3) * s * s - T(6) * s * t, T(6) * s * t - T(3) * t * t, T(3) * t * t};
}

template <class V> V bernstein_sum(const cubic_t<V>& P, const std::array<scalar_of<V>, 4>& w) {
  return w[0] * P[0] + w[1] * P[1] + w[2] * P[2] + w[3] * P[3];
}
template <class V> V eval_bernstein(const cubic_t<V>& P, scalar_of<V> t) {
  return bernstein_sum(P, bernstein3(t));
}
template <class V> V derivative_bernstein(const cubic_t<V>& P, scalar_of<V> t) {
  return bernstein_sum(P, bernstein3_derivative(t));
}
// [end]

// [listing lerp]
// The lerp of de Casteljau, written so that it is exact where exactness matters: it returns a at
// t = 0, b at t = 1, and a when a = b (a collapsed row stays one point, with derivative 0).
// So curves end exactly on their end control points, and two patches sharing an edge tessellate
// to bit-identical seam vertices (no cracks). 1 - t is exact for t >= 1/2 (Sterbenz).
template <class V> inline V lerp_point(const V& a, const V& b, scalar_of<V> t) {
  using T = scalar_of<V>;
  const V d = b - a;
  return t < T(0.5) ? a + t * d : b - (T(1) - t) * d;
}
// [end]

template <class V> struct curve_point_t {
  V point;       // P(t)
  V derivative;  // P'(t)
};

// [listing de-casteljau]
// de Casteljau: P_k^[s] is the lerp at t of P_{k-1}^[s-1] and P_k^[s-1]. Level 3 is the point;
// by Lemma 1.4.6 the derivative is 3 (P_3^[2] - P_2^[2]), the two points of level 2 (eq. 1.8).
template <class V> curve_point_t<V> de_casteljau(const cubic_t<V>& P, scalar_of<V> t) {
  using T = scalar_of<V>;
  const V p1_1 = lerp_point(P[0], P[1], t);
  const V p1_2 = lerp_point(P[1], P[2], t);
  const V p1_3 = lerp_point(P[2], P[3], t);
  const V p2_2 = lerp_point(p1_1, p1_2, t);
  const V p2_3 = lerp_point(p1_2, p1_3, t);
  return {lerp_point(p2_2, p2_3, t), T(3) * (p2_3 - p2_2)};  // B5: 3 * (...), not 3(...)
}
// [end]

template <class V> V eval_de_casteljau(const cubic_t<V>& P, scalar_of<V> t) {
  return de_casteljau(P, t).point;
}
template <class V> V derivative_de_casteljau(const cubic_t<V>& P, scalar_of<V> t) {
  return de_casteljau(P, t).derivative;
}

}  // namespace zraka

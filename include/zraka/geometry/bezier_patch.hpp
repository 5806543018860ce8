#pragma once
// Bicubic Bezier patches (book 1.3), P(u,v) = sum_i sum_j b_i^3(u) b_j^3(v) P_ij (eq. 1.4), and
// their partial derivatives and unit normal (book 1.4).
//
// Layout, as in the thesis's Listing 1.3 and the .bpt files: 16 control points stored row by
// row, P[4*row + col]; the column index runs in u and the row index in v. In the formulas,
// P_ij has i = column (u) and j = row (v), so P_ij = P[i + 4*j].
#include <zraka/geometry/bezier.hpp>

#include <cmath>
#include <limits>

namespace zraka {

template <class T> struct bezier_patch_t {
  std::array<vec3_t<T>, 16> P{};

  const vec3_t<T>& at(int i, int j) const { return P[i + 4 * j]; }  // P_ij
  // Row j is a curve in u; column i is a curve in v (the control points of Q_i, eq. 1.9).
  cubic_t<vec3_t<T>> row(int j) const { return {at(0, j), at(1, j), at(2, j), at(3, j)}; }
  cubic_t<vec3_t<T>> column(int i) const { return {at(i, 0), at(i, 1), at(i, 2), at(i, 3)}; }

  // The largest |coordinate| of a control point: evaluation errors are relative to it.
  T scale() const {
    T m = T(0);
    for (const auto& p : P) m = std::max(m, max_component(abs3(p)));
    return m;
  }
};

using bezier_patch = bezier_patch_t<double>;

// [listing patch-eval]
// Listing 1.3's order: each row is a curve in u, and the four row points a curve in v. We use
// de Casteljau for both: it is exact at the patch's edges and on collapsed rows (see lerp_point).
template <class T> vec3_t<T> evaluate(const bezier_patch_t<T>& patch, T u, T v) {
  cubic_t<vec3_t<T>> R;
  for (int j = 0; j < 4; ++j) R[j] = eval_de_casteljau(patch.row(j), u);
  return eval_de_casteljau(R, v);
}
// [end]

// [listing patch-explicit]
// The derivatives with explicit weights (book 1.4; the last u weight is 3u^2, errata A3):
// d/du = sum_j b_j(v) sum_i b_i'(u) P_ij,  d/dv = sum_j b_j'(v) sum_i b_i(u) P_ij.
template <class T> vec3_t<T> du_explicit(const bezier_patch_t<T>& patch, T u, T v) {
  const auto dbu = bernstein3_derivative(u);
  cubic_t<vec3_t<T>> R;
  for (int j = 0; j < 4; ++j) R[j] = bernstein_sum(patch.row(j), dbu);
  return bernstein_sum(R, bernstein3(v));
}
template <class T> vec3_t<T> dv_explicit(const bezier_patch_t<T>& patch, T u, T v) {
  const auto bu = bernstein3(u);
  cubic_t<vec3_t<T>> R;
  for (int j = 0; j < 4; ++j) R[j] = bernstein_sum(patch.row(j), bu);
  return bernstein_sum(R, bernstein3_derivative(v));
}
// [end]

// Point, both tangents and the mixed second derivative at (u, v).
template <class T> struct patch_derivatives_t { vec3_t<T> p, du, dv, duv; };

// [listing patch-fast]
// The faster scheme (eq. 1.9-1.11): one de Casteljau pass per column gives Q_i(v) and Q_i'(v)
// (gathered as P[i + 4*j], errata B6). Then the curve Q(u) gives P and dP/du (1.10), and the
// curve Q'(u) gives dP/dv (1.11) and, as its own derivative, d2P/dudv.
template <class T> patch_derivatives_t<T> differentiate(const bezier_patch_t<T>& patch, T u, T v) {
  cubic_t<vec3_t<T>> Q, dQ;
  for (int i = 0; i < 4; ++i) {
    const auto c = de_casteljau(patch.column(i), v);
    Q[i] = c.point;
    dQ[i] = c.derivative;
  }
  const auto along_u = de_casteljau(Q, u);
  const auto cross_u = de_casteljau(dQ, u);
  return {along_u.point, along_u.derivative, cross_u.point, cross_u.derivative};
}
// [end]

namespace detail {
// du x dv when it is trustworthy: both tangents well above the evaluation noise and not
// (anti)parallel; otherwise zero. `tiny` is the noise floor in absolute units.
template <class T> vec3_t<T> reliable_normal(const vec3_t<T>& du, const vec3_t<T>& dv, T tiny) {
  const T sqrt_eps = std::sqrt(std::numeric_limits<T>::epsilon());
  if (!(max_component(abs3(du)) > tiny && max_component(abs3(dv)) > tiny)) return {};
  const vec3_t<T> n = glm::cross(normalize_or_zero(du), normalize_or_zero(dv));  // |n| = sin
  return glm::length(n) > sqrt_eps ? normalize_or_zero(n) : vec3_t<T>(0);
}
}  // namespace detail

// [listing patch-normal]
// The unit normal (du x dv) / |du x dv| (eq. 1.7), defined everywhere. Where a row of control
// points collapses to one point (the teapot's lid knob and bottom centre), du vanishes along the
// whole edge and the naive normal is 0/0 = NaN (errata C8). There we take the limit from inside
// the patch: du(u, v+h) = h duv + O(h^2), so the normal tends to sign(h) duv x dv (and likewise
// du x duv when a column collapses). "Vanishes" means: shorter than sqrt(eps) times the patch's
// size, below which rounding (about eps times the size) would decide the direction.
template <class T> vec3_t<T> patch_normal(const bezier_patch_t<T>& patch, T u, T v) {
  const auto d = differentiate(patch, u, v);
  const T tiny = std::sqrt(std::numeric_limits<T>::epsilon()) * patch.scale();
  if (const vec3_t<T> n = detail::reliable_normal(d.du, d.dv, tiny); n != vec3_t<T>(0)) return n;

  const T inward_v = v < T(0.5) ? T(1) : T(-1), inward_u = u < T(0.5) ? T(1) : T(-1);
  vec3_t<T> n(0);
  if (max_component(abs3(d.dv)) > tiny)  // du vanished: a collapsed row
    n = inward_v * normalize_or_zero(glm::cross(normalize_or_zero(d.duv), normalize_or_zero(d.dv)));
  else if (max_component(abs3(d.du)) > tiny)  // dv vanished: a collapsed column
    n = inward_u * normalize_or_zero(glm::cross(normalize_or_zero(d.du), normalize_or_zero(d.duv)));
  if (n != vec3_t<T>(0)) return n;

  // Rarer degeneracies (a collapsed corner, parallel tangents): the normal a little inside.
  for (const T h : {T(1e-3), T(1e-2), T(1e-1)}) {
    const T ui = u + h * (T(0.5) - u), vi = v + h * (T(0.5) - v);
    const auto di = differentiate(patch, ui, vi);
    if (const vec3_t<T> m = detail::reliable_normal(di.du, di.dv, tiny); m != vec3_t<T>(0))
      return m;
  }
  return {T(0), T(0), T(1)};  // the patch is a point or a curve: no normal exists; never NaN
}
// [end]

}  // namespace zraka

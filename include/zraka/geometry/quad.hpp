#pragma once
// A quad: the parallelogram { Q + a u + b v : a, b in [0,1] } with corner Q and edges u, v.
// Its normal is N = u x v / ||u x v||, so the quad is counter-clockwise seen from the side N
// points to (the same rule as triangle.hpp). Quads make the floors, walls and area lights of the
// course's scenes; hits report (a, b) in uv.
//
// The intersection first finds the plane hit t = N.(Q - O) / N.D, then the plane coordinates
// (a, b) of the hit. Two rounding traps are closed explicitly instead of with an epsilon:
//  * a ray (nearly) parallel to the plane: N.D is within its own rounding error of zero, so its
//    sign, and the sign of t, mean nothing: no hit;
//  * a ray starting (nearly) on the plane, e.g. one spawned from this quad: the signed distance
//    N.(Q - O) is within its rounding error of zero, so we cannot tell which side the origin is
//    on: no hit. A ray leaving a planar surface can never meet it again, so this is exact.
// The hit point is rebuilt as Q + a u + b v, which lies on the plane up to the rounding of that
// one expression; p_error bounds it, and spawn.hpp moves new rays off by that much.
#include <zraka/core/hit.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>

#include <limits>
#include <optional>

namespace zraka {

// Named parallelogram_t, not quad_t: glibc's <sys/types.h> already has a global quad_t, which
// would make `using namespace zraka` ambiguous. The short names are quad and quadf.
template <class T> struct parallelogram_t {
  vec3_t<T> corner{T(0)};                      // Q
  vec3_t<T> u{T(1), T(0), T(0)}, v{T(0), T(1), T(0)};  // edges from Q

  vec3_t<T> normal() const { return normalize_or_zero(glm::cross(u, v)); }
  T area() const { return glm::length(glm::cross(u, v)); }
  vec3_t<T> point(T a, T b) const { return corner + a * u + b * v; }
  // Degenerate (u parallel to v), NaN or infinite quads are never hit.
  bool valid() const {
    return is_finite(corner) && is_finite(u) && is_finite(v) && normal() != vec3_t<T>(0);
  }
};

using quad = parallelogram_t<double>;
using quadf = parallelogram_t<float>;

// n / |n|^2 for the plane coordinates, given n = u x v and its unit N. Where |n|^2 leaves T's
// normal range (float: edges below ~1e-10 or above ~4e9; double: ~1e-77 and ~1e77) the quotient
// would be inf or 0, a quad never hit or one as wide as its plane; there w is N / |n|, with
// |n| = N.n, which never squares n (N is already normalize_or_zero's careful unit). Inside the
// range the plain quotient: the same bits as ever. A degenerate or non-finite n has N = 0, so
// 0 / 0: NaN, never hit, as before.
template <class T> vec3_t<T> plane_coordinate_vector(const vec3_t<T>& n, const vec3_t<T>& N) {
  const T d = glm::dot(n, n);
  if (d >= std::numeric_limits<T>::min() && d <= std::numeric_limits<T>::max()) return n / d;
  return N / glm::dot(N, n);
}

// What the intersection derives from the quad alone: its normal, unnormalised and unit, and
// n / |n|^2 for the plane coordinates. The object BVH keeps one per quad (scene.hpp), so that a
// ray does not normalise a cross product per quad it tests; the numbers are the same either way.
template <class T> struct quad_plane_t {
  vec3_t<T> n_raw, N, w;
  explicit quad_plane_t(const parallelogram_t<T>& q)
      : n_raw(glm::cross(q.u, q.v)), N(normalize_or_zero(n_raw)), w(plane_coordinate_vector(n_raw, N)) {}
};

// Where a ray meets the quad with t in (t_min, t_max): t and the plane coordinates (a, b), or
// none. pl is quad_plane_t(q). Inlined by force: GCC called it and passed the optional back
// through memory; inlined (with sphere_root), a path tracer's sample is 3-4 % cheaper
// (time_to_error, mis in float, one thread).
template <class T> struct quad_root_t {
  T t, a, b;
};

// [listing quad-intersect]
template <class T>
ZRAKA_FORCE_INLINE std::optional<quad_root_t<T>> quad_root(const parallelogram_t<T>& q, const quad_plane_t<T>& pl, const ray_t<T>& r,
                                        T t_min, T t_max) {
  const vec3_t<T>& N = pl.N;
  const vec3_t<T> D = r.direction;
  const T denom = glm::dot(N, D);
  const vec3_t<T> QO = q.corner - r.origin;
  const T s = glm::dot(N, QO);  // signed distance from the origin to the plane, along N
  const T t = s / denom;
  // First the test that rejects most: the plane behind the ray or beyond the nearest hit. (A
  // parallel ray's t is infinite or NaN, or whatever the rounding of N.D made it: the next test
  // decides, and the order changes no answer.)
  if (!(t > t_min && t < t_max)) return std::nullopt;
  // Parallel (or NaN): the sign of N.D is lost in its rounding error.
  if (!(std::abs(denom) > gamma<T>(3) * glm::dot(abs3(N), abs3(D)))) return std::nullopt;
  // The error of s: the subtraction and the dot product round (gamma(4) of the magnitudes), and
  // N is itself a few ulps off perpendicular to u and v (gamma(4) of the distance from Q).
  const T s_error = gamma<T>(4) * glm::dot(abs3(N), abs3(q.corner) + abs3(r.origin)) +
                    gamma<T>(4) * glm::length(QO);
  if (!(std::abs(s) > s_error)) return std::nullopt;  // origin on the plane: it cannot see this quad

  // Plane coordinates: with d = P - Q = a u + b v, a = (d x v).n / |n|^2, b = (u x d).n / |n|^2.
  const vec3_t<T> d = r.at(t) - q.corner;
  const vec3_t<T>& w = pl.w;
  const T a = glm::dot(w, glm::cross(d, q.v));
  const T b = glm::dot(w, glm::cross(q.u, d));
  if (!(a >= T(0) && a <= T(1) && b >= T(0) && b <= T(1))) return std::nullopt;
  return quad_root_t<T>{t, a, b};
}
// [end]

// The nearest hit with t in (t_min, t_max); fills `rec` only on a hit.
template <class T>
bool intersect(const parallelogram_t<T>& q, const quad_plane_t<T>& pl, const ray_t<T>& r, T t_min, T t_max,
               hit_t<T>& rec) {
  const auto root = quad_root(q, pl, r, t_min, t_max);
  if (!root) return false;
  const T a = root->a, b = root->b;
  rec.t = root->t;
  rec.p = q.point(a, b);
  // Q + a u + b v: one rounding per product and per sum, three terms (gamma(3), and one spare).
  rec.p_error = gamma<T>(4) * (abs3(q.corner) + abs3(a * q.u) + abs3(b * q.v));
  rec.normal = pl.N;
  rec.uv = {a, b};
  rec.set_face(r.direction);
  return true;
}

template <class T>
bool intersect(const parallelogram_t<T>& q, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec) {
  return intersect(q, quad_plane_t<T>(q), r, t_min, t_max, rec);
}

// Shadow rays only ask whether the quad is in the way: no hit point is built.
template <class T>
bool occludes(const parallelogram_t<T>& q, const quad_plane_t<T>& pl, const ray_t<T>& r, T t_min, T t_max) {
  return quad_root(q, pl, r, t_min, t_max).has_value();
}
template <class T> bool occludes(const parallelogram_t<T>& q, const ray_t<T>& r, T t_min, T t_max) {
  return occludes(q, quad_plane_t<T>(q), r, t_min, t_max);
}

}  // namespace zraka

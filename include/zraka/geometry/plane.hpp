#pragma once
// A plane (x - P0) . N = 0 (book 1.4, 1.5): by a point and a normal, by three points (normal by
// eq. 1.5) or by the equation ax + by + cz + d = 0 (Def 1.5.1), and its intersection with a ray.
//
// Two choices make the intersection safe to spawn rays from (book 1.5, errata B3):
//  * t is accepted only when its sign is certain: the numerator and the denominator of eq. 1.12
//    must each be larger than the bound on their own rounding error. A ray running parallel to
//    the plane to within rounding has no hit (never one "at infinity"), and neither has a ray
//    that starts on the plane to within rounding, which is what a spawned ray does;
//  * the hit point is reprojected onto the plane, so it lies within a few roundings of it, and
//    p_error = (e, e, e) bounds that distance. (It does not bound the distance along the plane
//    to the exact intersection; spawning only needs the distance across.)
#include <zraka/core/hit.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>

namespace zraka {

template <class T> struct plane_t {
  vec3_t<T> point{T(0)};                  // P0, any point of the plane
  vec3_t<T> normal{T(0), T(1), T(0)};     // N, unit (zero for an invalid plane)

  static plane_t from_point_normal(const vec3_t<T>& p0, const vec3_t<T>& n) {
    return {p0, normalize_or_zero(n)};
  }
  // Counter-clockwise a, b, c seen from the side N points to (eq. 1.5).
  static plane_t from_points(const vec3_t<T>& a, const vec3_t<T>& b, const vec3_t<T>& c) {
    return {a, normalize_or_zero(glm::cross(b - a, c - a))};
  }
  // ax + by + cz + d = 0: N = (a,b,c)/|(a,b,c)| and P0 = -d N/|(a,b,c)|, the point nearest 0.
  static plane_t from_equation(T a, T b, T c, T d) {
    const vec3_t<T> abc{a, b, c};
    const vec3_t<T> n = normalize_or_zero(abc);
    const T len = glm::dot(n, abc);  // |(a,b,c)| without squaring (no overflow for 1e200)
    if (!(len > T(0))) return {vec3_t<T>(T(0)), vec3_t<T>(T(0))};
    return {n * (-d / len), n};
  }

  // A zero, NaN or infinite normal or point makes a plane that is never hit.
  bool valid() const { return normal != vec3_t<T>(T(0)) && is_finite(normal) && is_finite(point); }
  T signed_distance(const vec3_t<T>& x) const { return glm::dot(x - point, normal); }
};

using plane = plane_t<double>;

// The hit with t in the open interval (t_min, t_max), t_min >= 0; fills `rec` only on a hit.
// uv: coordinates of the hit in the plane, along an orthonormal basis around N (onb.hpp),
// measured from P0 (a floor's checkerboard uses them).
// [listing plane-intersect]
template <class T>
bool intersect(const plane_t<T>& pl, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec) {
  if (!pl.valid() || !r.valid() || !is_finite(r.direction)) return false;
  const vec3_t<T>& N = pl.normal;
  const vec3_t<T>& D = r.direction;
  const vec3_t<T> to_plane = pl.point - r.origin;
  const T num = glm::dot(to_plane, N);  // eq. 1.12: t = (P0 - O).N / D.N
  const T den = glm::dot(D, N);
  // A 3-term dot product is off by at most gamma(3) sum |a_i b_i|; one more for P0 - O.
  if (!(std::abs(den) > gamma<T>(3) * glm::dot(abs3(D), abs3(N)))) return false;
  if (!(std::abs(num) > gamma<T>(5) * glm::dot(abs3(to_plane), abs3(N)))) return false;
  const T t = num / den;
  if (!(t > t_min && t < t_max)) return false;
  // [end]

  const vec3_t<T> x = r.at(t);
  if (!is_finite(x)) return false;  // t finite but O + tD overflowed
  // [listing plane-reproject]
  const vec3_t<T> p = x - pl.signed_distance(x) * N;
  // |(p - P0).N| <= gamma(13) S with S = (|x| + |P0|).|N|: gamma(4) for the distance, as much
  // again because |N| = 1 only to rounding, and 2 gamma(2) for the subtraction; S itself and
  // the second-order terms are covered by rounding up to gamma(16).
  const T e = gamma<T>(16) * glm::dot(abs3(x) + abs3(pl.point), abs3(N));
  // [end]
  rec.t = t;
  rec.p = p;
  rec.p_error = vec3_t<T>(e);
  rec.normal = N;
  rec.set_face(D);
  const onb_t<T> frame(N);
  rec.uv = {glm::dot(p - pl.point, frame.t), glm::dot(p - pl.point, frame.b)};
  return true;
}

template <class T> bool occludes(const plane_t<T>& pl, const ray_t<T>& r, T t_min, T t_max) {
  hit_t<T> ignored;
  return intersect(pl, r, t_min, t_max, ignored);
}

}  // namespace zraka

#pragma once
// Ray-triangle intersection (book 1.5). A triangle ABC, counter-clockwise seen from the side its
// normal N = (B-A) x (C-A) / ||...|| points to (book 1.4, eq. 1.5).
// Hits report barycentrics in uv: P = (1-u-v) A + u B + v C.
#include <zraka/hit.hpp>
#include <zraka/ray.hpp>
#include <zraka/spawn.hpp>

namespace zraka {

template <class T> struct triangle_t {
  vec3_t<T> a, b, c;

  vec3_t<T> normal() const { return normalize_or_zero(glm::cross(b - a, c - a)); }
  T area() const { return T(0.5) * glm::length(glm::cross(b - a, c - a)); }
};

using triangle = triangle_t<double>;

// Fills the hit record from barycentrics; the point is interpolated from the vertices (not
// O + tD), which bounds its error by gamma(7) times the weighted vertex magnitudes (pbrt 3.9.5).
template <class T>
void fill_triangle_hit(const triangle_t<T>& tri, const ray_t<T>& r, T t, T u, T v, hit_t<T>& rec) {
  const T w = T(1) - u - v;
  rec.t = t;
  rec.p = w * tri.a + u * tri.b + v * tri.c;
  rec.p_error = gamma<T>(7) * (glm::abs(w * tri.a) + glm::abs(u * tri.b) + glm::abs(v * tri.c));
  rec.normal = tri.normal();
  rec.uv = {u, v};
  rec.set_face(r.direction);
}

// Moller-Trumbore (1997): solve O + tD = (1-u-v)A + uB + vC by Cramer's rule, with no need for
// the plane equation. Nearest hit with t in (t_min, t_max).
// [listing moller-trumbore]
template <class T>
bool intersect(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec) {
  const vec3_t<T> e1 = tri.b - tri.a, e2 = tri.c - tri.a;
  const vec3_t<T> p = glm::cross(r.direction, e2);
  const T det = glm::dot(e1, p);
  if (!(det != T(0)) || !std::isfinite(det)) return false;  // parallel, degenerate, NaN
  const T inv_det = T(1) / det;
  const vec3_t<T> s = r.origin - tri.a;
  const T u = glm::dot(s, p) * inv_det;
  if (!(u >= T(0) && u <= T(1))) return false;
  const vec3_t<T> q = glm::cross(s, e1);
  const T v = glm::dot(r.direction, q) * inv_det;
  if (!(v >= T(0) && u + v <= T(1))) return false;
  const T t = glm::dot(e2, q) * inv_det;
  if (!(t > t_min && t < t_max)) return false;
  fill_triangle_hit(tri, r, t, u, v, rec);
  return true;
}
// [end]

}  // namespace zraka

#pragma once
// Axis-aligned bounding boxes (book 1.4 uses one per patch; the BVH of book 5.2 is built of them).
// A box is the set lo <= x <= hi (closed). The default box is empty (lo = +inf, hi = -inf), so
// growing it by the first point gives that point's box.
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>

#include <utility>

namespace zraka {

template <class T> struct aabb_t {
  vec3_t<T> lo{infinity<T>};
  vec3_t<T> hi{-infinity<T>};

  bool empty() const { return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z); }
  void grow(const vec3_t<T>& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const aabb_t& b) {
    if (b.empty()) return;
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool contains(const vec3_t<T>& p) const {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
  vec3_t<T> center() const { return T(0.5) * (lo + hi); }
  vec3_t<T> extent() const { return empty() ? vec3_t<T>(0) : hi - lo; }
  T surface_area() const {
    const vec3_t<T> e = extent();
    return T(2) * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
};

using aabb = aabb_t<double>;

template <class T> aabb_t<T> unite(aabb_t<T> a, const aabb_t<T>& b) {
  a.grow(b);
  return a;
}

// A ray prepared for many box tests: the reciprocal direction is computed once. A zero direction
// component gives an infinite reciprocal, which the slab test handles on its own.
template <class T> struct box_ray_t {
  vec3_t<T> origin, inv_direction;
  bool valid;
  explicit box_ray_t(const ray_t<T>& r)
      : origin(r.origin), inv_direction(T(1) / r.direction), valid(r.valid()) {}
};

// [listing slab]
// The slab test: on each axis the ray is inside the slab lo <= x <= hi for t between
// (lo - o)/d and (hi - o)/d; the box is hit where all three intervals and (t_min, t_max) overlap.
// * d = 0 on an axis: the ray is parallel to that slab; it is inside for all t or for none.
//   Tested directly, so 0 * inf = NaN never arises from a ray lying in a face's plane.
// * Any NaN left (a NaN box or origin) makes a comparison false and so reports a miss.
// * The far t is widened by 1 + 2 gamma(3) (Ize, "Robust BVH Ray Traversal", JCGT 2013): the
//   computed near and far t are each within gamma(3) of the true ones, so a ray that truly
//   grazes the box is never lost to rounding (a negative far t is behind the origin anyway).
template <class T> bool intersect(const aabb_t<T>& box, const box_ray_t<T>& r, T t_min, T t_max,
                                  T* t_enter = nullptr, T* t_exit = nullptr) {
  if (!r.valid) return false;
  T t0 = t_min, t1 = t_max;
  for (int a = 0; a < 3; ++a) {
    if (std::isinf(r.inv_direction[a])) {  // parallel to this slab
      if (!(box.lo[a] <= r.origin[a] && r.origin[a] <= box.hi[a])) return false;
      continue;
    }
    T t_near = (box.lo[a] - r.origin[a]) * r.inv_direction[a];
    T t_far = (box.hi[a] - r.origin[a]) * r.inv_direction[a];
    if (r.inv_direction[a] < T(0)) std::swap(t_near, t_far);  // by sign: an empty box stays empty
    t_far *= T(1) + T(2) * gamma<T>(3);
    if (!(t_near <= t_far)) return false;  // NaN, or an empty box
    if (t_near > t0) t0 = t_near;
    if (t_far < t1) t1 = t_far;
    if (!(t0 <= t1)) return false;
  }
  if (t_enter) *t_enter = t0;
  if (t_exit) *t_exit = t1;
  return true;
}
// [end]

template <class T> bool intersect(const aabb_t<T>& box, const ray_t<T>& r, T t_min, T t_max,
                                  T* t_enter = nullptr, T* t_exit = nullptr) {
  return intersect(box, box_ray_t<T>(r), t_min, t_max, t_enter, t_exit);
}

}  // namespace zraka

#pragma once
// Ray-triangle intersection (book 1.5). A triangle ABC, counter-clockwise seen from the side its
// normal N = (B-A) x (C-A) / ||...|| points to (book 1.4, eq. 1.5).
// Hits report barycentrics in uv: P = (1-u-v) A + u B + v C.
//
// Three methods with one interface, so that the book and chapter 1.5 can compare them:
//  * intersect_edge_tests: the thesis's geometric method (plane, then three edge tests), fixed;
//  * intersect_moller_trumbore: Moller & Trumbore (1997), Cramer's rule, no plane equation;
//  * intersect_watertight: Woop, Benthin & Wald, "Watertight Ray/Triangle Intersection" (JCGT
//    2013), with a t that is accepted only when its sign is certain: the origin's distance to
//    the plane and the direction's slope to it are both beyond their rounding errors.
// intersect() without a method is the watertight one: a ray through an edge or a vertex shared by
// two triangles hits at least one of them, and a spawned ray never hits its own triangle.
// Every method: a degenerate triangle (computed N = 0) and NaN/inf input are never hit; hits
// are in the open interval (t_min, t_max), t_min >= 0.
#include <zraka/core/enum_names.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/geometry/spawn.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <cmath>
#include <string_view>
#include <utility>

namespace zraka {

template <class T> struct triangle_t {
  vec3_t<T> a, b, c;

  vec3_t<T> normal() const { return normalize_or_zero(glm::cross(b - a, c - a)); }
  T area() const { return T(0.5) * glm::length(glm::cross(b - a, c - a)); }
};

using triangle = triangle_t<double>;
using trianglef = triangle_t<float>;

// Fills the hit record from barycentrics; the point is interpolated from the vertices (not
// O + tD), which bounds its error by gamma(7) times the weighted vertex magnitudes (pbrt 3.9.5).
template <class T>
void fill_triangle_hit(const triangle_t<T>& tri, const ray_t<T>& r, T t, T u, T v, hit_t<T>& rec) {
  const T w = T(1) - u - v;
  rec.t = t;
  rec.p = w * tri.a + u * tri.b + v * tri.c;
  rec.p_error = gamma<T>(7) * (abs3(w * tri.a) + abs3(u * tri.b) + abs3(v * tri.c));
  rec.normal = tri.normal();
  rec.uv = {u, v};
  rec.set_face(r.direction);
}

namespace detail {
// The guard every method starts with. n = (B-A) x (C-A) is zero for a degenerate triangle, and
// NaN or infinite when a vertex is (or when the coordinates are so large that n overflows).
template <class T> bool can_hit(const triangle_t<T>& tri, const ray_t<T>& r) {
  const vec3_t<T> n = glm::cross(tri.b - tri.a, tri.c - tri.a);
  return is_finite(n) && n != vec3_t<T>(T(0)) && r.valid() && is_finite(r.direction);
}
}  // namespace detail

// The thesis's geometric method (Example 1.5.3, Listing 1.12) with its errors fixed (errata B2):
// each edge's cross product has its own name, t < t_min is rejected, and the barycentrics are
// the area ratios of eq. 1.15, as signed areas: n . ((B-A) x (P-A)) = |n| 2 area(ABP).
// [listing edge-tests]
template <class T>
bool intersect_edge_tests(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max,
                          hit_t<T>& rec) {
  if (!detail::can_hit(tri, r)) return false;
  const vec3_t<T> n = glm::cross(tri.b - tri.a, tri.c - tri.a);  // eq. 1.5, not normalised
  const T n_dot_d = glm::dot(n, r.direction);
  if (n_dot_d == T(0)) return false;  // the ray runs parallel to the plane
  const T t = glm::dot(n, tri.a - r.origin) / n_dot_d;  // eq. 1.16
  if (!(t > t_min && t < t_max)) return false;
  const vec3_t<T> p = r.at(t);
  const vec3_t<T> c_ab = glm::cross(tri.b - tri.a, p - tri.a);  // eq. 1.17, edge AB
  const vec3_t<T> c_bc = glm::cross(tri.c - tri.b, p - tri.b);  // edge BC
  const vec3_t<T> c_ca = glm::cross(tri.a - tri.c, p - tri.c);  // edge CA
  const T area_abp = glm::dot(n, c_ab), area_bcp = glm::dot(n, c_bc), area_cap = glm::dot(n, c_ca);
  if (!(area_abp >= T(0) && area_bcp >= T(0) && area_cap >= T(0))) return false;  // outside
  const T area_abc = glm::dot(n, n);
  fill_triangle_hit(tri, r, t, area_cap / area_abc, area_abp / area_abc, rec);  // eq. 1.15
  return true;
}
// [end]

// Moller-Trumbore (1997): solve O + tD = (1-u-v)A + uB + vC by Cramer's rule, with no need for
// the plane equation. Nearest hit with t in (t_min, t_max).
// [listing moller-trumbore]
template <class T>
bool intersect_moller_trumbore(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max,
                               hit_t<T>& rec) {
  if (!detail::can_hit(tri, r)) return false;
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

namespace detail {
// a b - c d with its sign exact. Rounded the plain way, fl(fl(ab) - fl(cd)) never has the wrong
// sign (rounding is monotone), it can only lose it as 0, and the paper recomputes just that case.
// But a compiler may fuse a product and the subtraction into one FMA (GCC does on ARM, or with
// -march=native on x86), and fl(ab - fl(cd)) can have the wrong sign. So we filter instead: the
// error is at most gamma(2)(|ab| + |cd|) either way, and only within that bound (0 included) is
// the sign decided again, exactly. float: the products of floats are exact in double, and the
// one rounding of the difference keeps its sign. double: Kahan's difference of products with
// FMA, whose relative error is below 2 ulp (Jeannerod, Louvet, Muller 2013), so its sign is exact.
// [listing exact-edge]
inline float difference_of_products(float a, float b, float c, float d) {
  return float(double(a) * double(b) - double(c) * double(d));
}
inline double difference_of_products(double a, double b, double c, double d) {
  const double cd = c * d;
  const double cd_error = std::fma(-c, d, cd);  // cd - c*d, exactly
  return std::fma(a, b, -cd) + cd_error;
}
// x86 without FMA instructions (the default x86-64 target) cannot fuse, so there the paper's
// cheaper rule is exact: only a 0 is recomputed. Any other target, or an unknown compiler, filters.
#if (defined(__x86_64__) || defined(__i386__)) && !defined(__FMA__) && !defined(__FMA4__)
inline constexpr bool may_fuse = false;
#else
inline constexpr bool may_fuse = true;
#endif
template <class T> T edge_function(T a, T b, T c, T d) {
  const T e = a * b - c * d;
  if constexpr (may_fuse) {
    if (std::abs(e) > gamma<T>(3) * (std::abs(a * b) + std::abs(c * d))) return e;  // certain
  } else if (e != T(0)) {
    return e;  // fl(fl(ab) - fl(cd)): the right sign whenever not 0
  }
  return difference_of_products(a, b, c, d);
}
// [end]
}  // namespace detail

// Watertight (Woop, Benthin, Wald 2013). Move the ray to the origin, permute the axes so that
// its largest direction component is z, and shear so that it becomes the +z axis. Then the
// ray hits the triangle when the origin lies inside the projected triangle (x, y): three 2-D
// edge functions of one sign. An edge function depends only on its edge's two vertices, and
// its sign is computed exactly (see edge_function), so the two triangles sharing an
// edge always see the ray on opposite sides of it, or both exactly on it (edges are inclusive).
// The test is split in its per-ray half (watertight_ray: the permutation and the shear, which
// the mesh BVH prepares once per ray in bvh_ray) and its per-triangle half (watertight_test),
// so that triangle_bvh.hpp's scalar leaf calls the very same code and gives the same bits (its
// four-lane leaf, watertight4.hpp, repeats watertight_test's operations lane by lane).
namespace detail {
// [listing watertight-ray]
template <class T> struct watertight_ray {
  vec3_t<T> origin, direction;
  int kx, ky, kz;  // the axes that become x, y and z
  T sx, sy, sz;    // the shear that makes the direction (0, 0, 1)
  T ox, oy, oz;    // the origin's coordinates kx, ky, kz
  explicit watertight_ray(const ray_t<T>& r) : origin(r.origin), direction(r.direction) {
    // Coordinates are read through pointers (vec3's operator[] is a switch) and the axes are
    // chosen by arithmetic on the comparisons, not by branches: for incoherent rays each choice
    // is a coin toss, and GCC's branches for glm::abs and ?: cost a mesh BVH a tenth of its time.
    const T* d = glm::value_ptr(direction);
    const T* o = glm::value_ptr(origin);
    const int x_over_y = std::abs(d[0]) > std::abs(d[1]), x_over_z = std::abs(d[0]) > std::abs(d[2]),
              y_over_z = std::abs(d[1]) > std::abs(d[2]);
    const int z_if_x = 2 - 2 * x_over_z, z_if_y = 2 - y_over_z;  // kz when |x| > |y|, and when not
    kz = z_if_y + x_over_y * (z_if_x - z_if_y);
    constexpr int next_axis[5] = {1, 2, 0, 1, 2};  // (kz + 1) % 3 and (kz + 2) % 3 without a branch
    const int next = next_axis[kz], after = next_axis[kz + 1];
    const int flip = d[kz] < T(0);  // keep the winding: swap x and y
    kx = next + flip * (after - next);
    ky = after + flip * (next - after);
    sz = T(1) / d[kz];  // one division: the shear need not be correctly rounded, only one for all triangles
    sx = d[kx] * sz;
    sy = d[ky] * sz;
    ox = o[kx];
    oy = o[ky];
    oz = o[kz];
  }
};
// [end]

// The mesh BVH runs this once per triangle of a leaf: GCC would rather call it, which costs
// the BVH about a tenth of its speed, so it is inlined by force (ZRAKA_FORCE_INLINE, vec.hpp).

// [listing watertight]
// True when the ray passes inside the triangle ABC (edges inclusive) and does not see it
// edge-on; then t is the hit's distance and (u, v) the weights of B and C, not yet checked
// against any interval.
template <class T>
ZRAKA_FORCE_INLINE bool watertight_test(const watertight_ray<T>& r, const vec3_t<T>& A,
                                        const vec3_t<T>& B, const vec3_t<T>& C, T& t, T& u, T& v) {
  // q = p - O, permuted, then sheared: (x, y) and q[kz]; z = sz q[kz] only if t is wanted.
  auto to_ray_space = [&](const vec3_t<T>& p) {
    const T* v = glm::value_ptr(p);  // indexed in memory: vec3's operator[] is a switch
    const T qx = v[r.kx] - r.ox, qy = v[r.ky] - r.oy, qz = v[r.kz] - r.oz;
    return vec3_t<T>(qx - r.sx * qz, qy - r.sy * qz, qz);
  };
  const vec3_t<T> a = to_ray_space(A), b = to_ray_space(B), c = to_ray_space(C);

  // e_a is twice the signed area of (ray, B, C): the weight of A, and so on.
  const T e_a = edge_function(c.x, b.y, c.y, b.x);
  const T e_b = edge_function(a.x, c.y, a.y, c.x);
  if (std::min(e_a, e_b) < T(0) && std::max(e_a, e_b) > T(0)) return false;  // early out
  const T e_c = edge_function(b.x, a.y, b.y, a.x);
  if (std::min(e_c, std::min(e_a, e_b)) < T(0) && std::max(e_c, std::max(e_a, e_b)) > T(0))
    return false;  // the ray passes outside an edge: weights of both signs
  const T det = e_a + e_b + e_c;  // twice the projected area; 0: seen edge-on
  if (!(std::abs(det) > T(0))) return false;
  const T inv_det = T(1) / det;
  t = (e_a * (r.sz * a.z) + e_b * (r.sz * b.z) + e_c * (r.sz * c.z)) * inv_det;
  u = e_b * inv_det;
  v = e_c * inv_det;
  return true;
}
// [end]

// [listing watertight-conservative-t]
// Is the true t of the plane hit certainly positive? t = s / (n.D), with n = (B-A) x (C-A) and
// s = n.(A-O) the origin's signed distance to the plane times |n|: so t > 0 exactly when s and
// n.D have one sign, and we accept only when both signs are beyond their rounding errors. This
// is what stops a ray spawned from the triangle (it leaves the plane, so its t is negative,
// or its s is lost in rounding) without rejecting real hits: unlike a bound on the error of t
// through the shear and the edge functions, whose relative size grows like (distance / size)
// and 1/det, s and n.D stay well conditioned for slivers, tiny far triangles and grazing rays,
// computed in double (float's n of a sliver of aspect 1e-7 would have no correct digit).
// Error bounds, unit roundoff u of double: B-A and C-A round once each, a product of two and
// their difference once more, so |dn| <= gamma(4) n_abs (n_abs: the cross product's terms
// taken in absolute value); A-O rounds once and the dot product three times: |ds| <=
// gamma(8) n_abs.|A-O|, |d(n.D)| <= gamma(7) n_abs.|D|, taken with one spare rounding each.
template <class T>
bool t_certainly_positive_in_double(const vec3_t<T>& A, const vec3_t<T>& B, const vec3_t<T>& C,
                                    const vec3_t<T>& O, const vec3_t<T>& D) {
  const vec3 a(A), e1 = vec3(B) - a, e2 = vec3(C) - a, w = a - vec3(O), d(D);
  const vec3 n = glm::cross(e1, e2);
  const vec3 n_abs(std::abs(e1.y * e2.z) + std::abs(e1.z * e2.y),
                   std::abs(e1.z * e2.x) + std::abs(e1.x * e2.z),
                   std::abs(e1.x * e2.y) + std::abs(e1.y * e2.x));
  const double s = glm::dot(n, w), n_dot_d = glm::dot(n, d);
  return std::abs(s) > gamma<double>(9) * glm::dot(n_abs, abs3(w)) &&
         std::abs(n_dot_d) > gamma<double>(8) * glm::dot(n_abs, abs3(d)) &&
         (s > 0) == (n_dot_d > 0);
}
// The same question asked in float first, for float input, which answers most hits at half the
// cost (book 5.2): the same formulas with float's unit roundoff, two spare roundings for the
// bounds computed in float, a term for products that underflow (each may lose 2^-126 where the
// processor flushes subnormals to zero, and s multiplies n's error by |w|), and all of it twice
// over. When both signs clear their bounds, |s| and |n.D| exceed float's error by more than
// double's error and bound together, so the double test above would be certain of the same
// signs: the answer is its answer, bit for bit. Otherwise (near the plane, grazing, slivers,
// overflow, NaN) it says "don't know" (-1).
inline int t_positive_in_float(const vec3_t<float>& A, const vec3_t<float>& B, const vec3_t<float>& C,
                               const vec3_t<float>& O, const vec3_t<float>& D) {
  const vec3_t<float> e1 = B - A, e2 = C - A, w = A - O;
  const vec3_t<float> n = glm::cross(e1, e2);
  const vec3_t<float> n_abs(std::abs(e1.y * e2.z) + std::abs(e1.z * e2.y),
                            std::abs(e1.z * e2.x) + std::abs(e1.x * e2.z),
                            std::abs(e1.x * e2.y) + std::abs(e1.y * e2.x));
  const vec3_t<float> aw = abs3(w), ad = abs3(D);
  const float s = glm::dot(n, w), n_dot_d = glm::dot(n, D);
  // Compared at 2^32 times their size (exact: a power of two), so that the underflow term,
  // 2^-123 (twice 2^-124 (|w| + 1), what flushed products can lose), is a normal float even for
  // a bound near 0: arithmetic that makes a subnormal float takes the processor a slow path,
  // which cost the BVH a fifth of its speed. Beyond float's range at that scale: "don't know".
  constexpr float scale = 0x1p32f, underflow = 0x1p-91f;
  const float s_bound = (2 * gamma<float>(10) * scale) * glm::dot(n_abs, aw) + underflow * (aw.x + aw.y + aw.z + 1);
  const float d_bound = (2 * gamma<float>(9) * scale) * glm::dot(n_abs, ad) + underflow * (ad.x + ad.y + ad.z + 1);
  if (!(std::abs(s) * scale > s_bound && std::abs(n_dot_d) * scale > d_bound)) return -1;
  return (s > 0) == (n_dot_d > 0);
}

template <class T>
bool t_certainly_positive(const vec3_t<T>& A, const vec3_t<T>& B, const vec3_t<T>& C,
                          const vec3_t<T>& O, const vec3_t<T>& D) {
  if constexpr (std::is_same_v<T, float>)
    if (const int sure = t_positive_in_float(A, B, C, O, D); sure >= 0) return sure == 1;
  return t_certainly_positive_in_double(A, B, C, O, D);
}
// [end]
}  // namespace detail

// [listing watertight-intersect]
template <class T>
bool intersect_watertight(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max,
                          hit_t<T>& rec) {
  if (!detail::can_hit(tri, r)) return false;
  T t, u, v;
  if (!detail::watertight_test(detail::watertight_ray<T>(r), tri.a, tri.b, tri.c, t, u, v))
    return false;
  if (!(t > t_min && t < t_max)) return false;
  if (!detail::t_certainly_positive(tri.a, tri.b, tri.c, r.origin, r.direction)) return false;
  fill_triangle_hit(tri, r, t, u, v, rec);
  return true;
}
// [end]

// The method a program picks at run time (chapter 1.5's --method).
enum class triangle_method { edge_tests, moller_trumbore, watertight };

inline constexpr enum_name<triangle_method> triangle_method_names[] = {
    {triangle_method::edge_tests, "edge"}, {triangle_method::moller_trumbore, "mt"}, {triangle_method::watertight, "watertight"}};
constexpr std::span<const enum_name<triangle_method>> enum_names(triangle_method) { return triangle_method_names; }  // enum_names.hpp

template <class T>
bool intersect(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec,
               triangle_method m) {
  switch (m) {
    case triangle_method::edge_tests: return intersect_edge_tests(tri, r, t_min, t_max, rec);
    case triangle_method::moller_trumbore:
      return intersect_moller_trumbore(tri, r, t_min, t_max, rec);
    case triangle_method::watertight: return intersect_watertight(tri, r, t_min, t_max, rec);
  }
  return false;
}

// The default: watertight.
template <class T>
bool intersect(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec) {
  return intersect_watertight(tri, r, t_min, t_max, rec);
}

template <class T> bool occludes(const triangle_t<T>& tri, const ray_t<T>& r, T t_min, T t_max) {
  hit_t<T> ignored;
  return intersect(tri, r, t_min, t_max, ignored);
}

}  // namespace zraka

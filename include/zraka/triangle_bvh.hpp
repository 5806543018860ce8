#pragma once
// A BVH specialised for triangle meshes (book 5.2): compact and fast, for the teapot at a million
// triangles. The tree comes from bvh.hpp's builder (in float), collapsed to four children per
// node by wide_bvh.hpp, whose box test and front-to-back walk it shares with the scene's object
// BVH. What is special here is the leaf:
// * the triangles copied in leaf order as the watertight test (triangle.hpp) wants them: the
//   vertices A, B, C and the input index, 40 bytes each, so a leaf's triangles are contiguous
//   in memory;
// * a ray prepared once (bvh_ray): wide_bvh.hpp's box4_ray and the watertight test's axis
//   permutation and shear.
// No allocation per ray (wide_bvh.hpp's fixed stack).
// Hits report the triangle's index in the input, t and the barycentrics (u, v) of triangle.hpp's
// convention P = (1-u-v) A + u B + v C, bit for bit what intersect_watertight() gives on the
// same float triangle (the leaf calls the same two functions); among hits at exactly the same t
// the lowest index wins, so the result never depends on the tree.
#include <zraka/bvh.hpp>
#include <zraka/mesh.hpp>
#include <zraka/triangle.hpp>
#include <zraka/wide_bvh.hpp>

#include <cmath>
#include <cstdint>
#include <vector>

namespace zraka {

struct triangle_bvh_hit {
  float t = infinity<float>;
  float u = 0, v = 0;                   // barycentrics of B and C
  std::uint32_t triangle = UINT32_MAX;  // index in the input; UINT32_MAX: no hit
};

// [listing packed-triangle]
// One triangle as the watertight test wants it: its vertices as they are (an edge B - A would
// be rounded, and two triangles sharing an edge must see the very same numbers).
struct packed_triangle {
  vec3_t<float> a, b, c;
  std::uint32_t id;  // index in the input
};
// [end]
static_assert(sizeof(packed_triangle) == 40);

// The nodes are wide_bvh.hpp's; a leaf's entries are positions in triangles().
using triangle_bvh_node4 = bvh_node4;

// [listing bvh-ray]
// A ray prepared for many box and triangle tests: wide_bvh.hpp's half for the boxes (the
// reciprocal direction, which side of a box is near) and the watertight test's per-ray half
// (the axis permutation and the shear).
struct bvh_ray {
  vec3_t<float> origin, direction;
  box4_ray box;
  detail::watertight_ray<float> shear;
  bool valid;  // as triangle.hpp's can_hit() asks of a ray
  explicit bvh_ray(const ray_t<float>& r)
      : origin(r.origin), direction(r.direction), box(r), shear(r),
        valid(r.valid() && is_finite(r.direction)) {}
};
// [end]

class triangle_bvh {
 public:
  // Defaults measured on the teapot (book 5.2): leaves of up to 8 and a box test priced at 3
  // triangle tests give fewer, fuller leaves than bvh.hpp's defaults, 54 instead of 72 bytes
  // per triangle, at the same speed (within the noise of the benchmark).
  static bvh_build_options default_options() {
    bvh_build_options o;
    o.max_leaf_size = 8;
    o.traversal_cost = 3;
    return o;
  }

  triangle_bvh() = default;
  explicit triangle_bvh(const std::vector<triangle_t<float>>& tris,
                        const bvh_build_options& opt = default_options()) {
    build(tris, opt);
  }
  template <class T>
  explicit triangle_bvh(const mesh_t<T>& m, const bvh_build_options& opt = default_options()) {
    std::vector<triangle_t<float>> tris(m.triangle_count());
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const auto& f = m.triangles[i];
      tris[i] = {vec3_t<float>(m.positions[f[0]]), vec3_t<float>(m.positions[f[1]]),
                 vec3_t<float>(m.positions[f[2]])};
    }
    build(tris, opt);
  }

  const std::vector<triangle_bvh_node4>& nodes() const { return nodes_; }
  const std::vector<packed_triangle>& triangles() const { return tris_; }  // in leaf order
  std::size_t input_count() const { return input_count_; }
  int depth() const { return depth_; }
  // Memory of nodes and triangle data, and that per input triangle.
  std::size_t bytes() const {
    return nodes_.size() * sizeof(triangle_bvh_node4) + tris_.size() * sizeof(packed_triangle);
  }
  double bytes_per_triangle() const {
    return input_count_ ? double(bytes()) / double(input_count_) : 0.0;
  }

  // The nearest hit with t in (t_min, t_max).
  bool intersect(const ray_t<float>& r, float t_min, float t_max, triangle_bvh_hit& h,
                 bvh_stats* stats = nullptr) const {
    h = {};
    return stats ? nearest<true>(bvh_ray(r), t_min, t_max, h, stats)
                 : nearest<false>(bvh_ray(r), t_min, t_max, h, nullptr);
  }
  // Any hit with t in (t_min, t_max): for shadow rays; stops at the first.
  bool occluded(const ray_t<float>& r, float t_min, float t_max, bvh_stats* stats = nullptr) const {
    return stats ? any<true>(bvh_ray(r), t_min, t_max, stats)
                 : any<false>(bvh_ray(r), t_min, t_max, nullptr);
  }
  // Every triangle, the same test and the same tie rule: the reference the BVH must equal.
  bool intersect_brute_force(const ray_t<float>& r, float t_min, float t_max,
                             triangle_bvh_hit& h) const {
    h = {};
    const bvh_ray br(r);
    if (!br.valid) return false;
    bool found = false;
    for (const packed_triangle& tri : tris_)
      if (test(tri, br, t_min, t_max, h)) {
        found = true;
        t_max = h.t;
      }
    return found;
  }

 private:
  void build(const std::vector<triangle_t<float>>& tris, const bvh_build_options& opt) {
    input_count_ = tris.size();
    std::vector<aabb_t<float>> boxes(tris.size());
    std::vector<vec3_t<float>> centroids(tris.size());
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const triangle_t<float>& t = tris[i];
      // triangle.hpp never hits a degenerate (N = 0) or non-finite triangle: leave it out
      // (an empty box tells the builder so).
      const vec3_t<float> n = glm::cross(t.b - t.a, t.c - t.a);
      if (!is_finite(n) || n == vec3_t<float>(0.0f)) continue;
      boxes[i].grow(t.a);
      boxes[i].grow(t.b);
      boxes[i].grow(t.c);
      centroids[i] = boxes[i].center();
    }
    const bvh_t<float> b = build_bvh(boxes, centroids, opt);
    depth_ = b.depth;
    tris_.reserve(b.order.size());
    for (const std::uint32_t i : b.order)  // leaf order: a leaf's index points into tris_
      tris_.push_back({tris[i].a, tris[i].b, tris[i].c, i});
    nodes_ = collapse4(b);
  }

  // [listing packed-watertight]
  // triangle.hpp's intersect_watertight() on the packed data: the same two calls (the
  // per-triangle half of the test, then the certainty of t > 0), so the same bits; t in
  // (t_min, t_max). A hit at exactly the t of the hit found so far (h.t) counts too if its index
  // is lower: the nearest hit is then the smallest (t, index), like a brute force loop in index
  // order, whatever order the BVH visits the triangles in.
  static bool test(const packed_triangle& tri, const bvh_ray& r, float t_min, float t_max,
                   triangle_bvh_hit& h) {
    float t, u, v;
    if (!detail::watertight_test(r.shear, tri.a, tri.b, tri.c, t, u, v)) return false;
    if (!(t > t_min && (t < t_max || (t == h.t && tri.id < h.triangle)))) return false;
    if (!detail::t_certainly_positive(tri.a, tri.b, tri.c, r.origin, r.direction)) return false;
    h = {t, u, v, tri.id};
    return true;
  }
  // [end]

  // [listing triangle-traverse]
  // wide_bvh.hpp's walk with this leaf: the packed triangles, each hit lowering t_max.
  template <bool count>
  bool nearest(const bvh_ray& r, float t_min, float t_max, triangle_bvh_hit& h,
               bvh_stats* stats) const {
    if (!r.valid) return false;
    return wide_nearest(
        nodes_, r.box, t_min, t_max,
        [&](std::uint32_t first, std::uint32_t n, float& t_cull) {
          bool found = false;
          const packed_triangle* tri = &tris_[first];
          for (std::uint32_t k = 0; k < n; ++k)
            if (test(tri[k], r, t_min, t_cull, h)) {
              found = true;
              t_cull = h.t;
            }
          return found;
        },
        count ? stats : nullptr);
  }
  // [end]

  template <bool count>
  bool any(const bvh_ray& r, float t_min, float t_max, bvh_stats* stats) const {
    if (!r.valid) return false;
    return wide_any(
        nodes_, r.box, t_min, t_max,
        [&](std::uint32_t first, std::uint32_t n) {
          for (std::uint32_t k = 0; k < n; ++k) {
            triangle_bvh_hit ignored;
            if (test(tris_[first + k], r, t_min, t_max, ignored)) return true;
          }
          return false;
        },
        count ? stats : nullptr);
  }

  std::vector<triangle_bvh_node4> nodes_;
  std::vector<packed_triangle> tris_;
  std::size_t input_count_ = 0;
  int depth_ = 0;
};

}  // namespace zraka

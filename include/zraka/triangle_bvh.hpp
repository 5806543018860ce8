#pragma once
// A BVH specialised for triangle meshes (book 5.2): compact and fast, for the teapot at a million
// triangles. The tree comes from bvh.hpp's builder (in float); what is special is the memory
// layout and the loop:
// * four children per node (the builder's binary tree collapsed two levels into one), their
//   boxes stored axis by axis (lo.x of the four, then lo.y, ...), so that the four slab tests
//   are one loop the compiler turns into SIMD instructions; 128 bytes, two cache lines;
// * the triangles copied in leaf order as the watertight test (triangle.hpp) wants them: the
//   vertices A, B, C and the input index, 40 bytes each, so a leaf's triangles are contiguous
//   in memory;
// * a ray prepared once (bvh_ray): the reciprocal direction and, per axis, which side of a box
//   is near, so a box test has no branch; and the watertight test's axis permutation and shear;
// * front-to-back order: the children hit are pushed on a small fixed stack by entry distance,
//   nearest on top, and skipped when popped if a hit is already nearer. No allocation per ray.
// Hits report the triangle's index in the input, t and the barycentrics (u, v) of triangle.hpp's
// convention P = (1-u-v) A + u B + v C, bit for bit what intersect_watertight() gives on the
// same float triangle (the leaf calls the same two functions); among hits at exactly the same t the lowest index wins, so the result
// never depends on the tree.
#include <zraka/bvh.hpp>
#include <zraka/mesh.hpp>
#include <zraka/triangle.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <vector>

#if defined(__SSE2__) && !defined(ZRAKA_NO_SIMD)
#include <immintrin.h>
#endif

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

// [listing compact-node]
// A node with four children (a binary BVH with every other level removed). Child k's box is
// box[a][k] <= x[a] <= box[3 + a][k] (rows lo.x, lo.y, lo.z, hi.x, hi.y, hi.z). A child is a leaf
// of count[k] triangles from tris[child[k]], or an inner node nodes[child[k]] (count 0). Unused
// slots have an empty box, which no ray hits.
struct alignas(64) triangle_bvh_node4 {
  float box[6][4];
  std::uint32_t child[4];
  std::uint32_t count[4];
};
// [end]
static_assert(sizeof(triangle_bvh_node4) == 128);

// [listing bvh-ray]
// A ray prepared for many box and triangle tests: the reciprocal direction, and per axis which
// side of a box is near: lo where the direction is positive, hi where it is negative (by the
// sign bit, so that -0, whose reciprocal is -inf, counts as negative). And the watertight
// test's per-ray half: the axis permutation and the shear.
struct bvh_ray {
  vec3_t<float> origin, direction, inv_direction;
  std::array<int, 3> near_row, far_row;  // rows of triangle_bvh_node4::box
  detail::watertight_ray<float> shear;
  bool valid;  // as triangle.hpp's can_hit() asks of a ray
  explicit bvh_ray(const ray_t<float>& r)
      : origin(r.origin), direction(r.direction), inv_direction(1.0f / r.direction), shear(r),
        valid(r.valid() && is_finite(r.direction)) {
    for (int a = 0; a < 3; ++a) {
      const bool negative = std::signbit(direction[a]);
      near_row[a] = negative ? 3 + a : a;
      far_row[a] = negative ? a : 3 + a;
    }
  }
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
    if (b.empty()) return;
    nodes_.reserve(b.nodes.size() / 3 + 1);
    collapse(b, {0});
  }

  // [listing collapse]
  // Makes a 4-wide node of binary nodes `kids` (the root alone at first): an inner kid with the
  // largest box is replaced by its two children until there are four, or only leaves. Returns
  // the new node's index; its inner children are collapsed in turn, depth first.
  std::uint32_t collapse(const bvh_t<float>& b, std::vector<std::uint32_t> kids) {
    while (kids.size() < 4) {
      int widest = -1;
      float widest_area = -1;
      for (int k = 0; k < int(kids.size()); ++k) {
        const bvh_node_t<float>& n = b.nodes[kids[k]];
        if (!n.leaf() && n.box.surface_area() > widest_area) {
          widest = k;
          widest_area = n.box.surface_area();
        }
      }
      if (widest < 0) break;  // only leaves
      const std::uint32_t k = kids[widest];
      kids[widest] = k + 1;              // the first child follows its parent
      kids.push_back(b.nodes[k].index);  // the second
    }
    const auto me = static_cast<std::uint32_t>(nodes_.size());
    nodes_.emplace_back();
    for (int a = 0; a < 3; ++a)
      for (int k = 0; k < 4; ++k) {
        nodes_[me].box[a][k] = infinity<float>;  // an empty box: unused slot
        nodes_[me].box[3 + a][k] = -infinity<float>;
      }
    for (int k = 0; k < int(kids.size()); ++k) {
      const bvh_node_t<float>& n = b.nodes[kids[k]];
      for (int a = 0; a < 3; ++a) {
        nodes_[me].box[a][k] = n.box.lo[a];
        nodes_[me].box[3 + a][k] = n.box.hi[a];
      }
      nodes_[me].count[k] = n.count;
      nodes_[me].child[k] = n.leaf() ? n.index : collapse(b, {kids[k] + 1, n.index});
    }
    return me;
  }
  // [end]

  // [listing fast-slab]
  // The slab test of a node's four child boxes at once: the same few operations on four lanes,
  // one SSE instruction each on x86-64 (GCC did not vectorise the plain loop, which other
  // machines use; it gives the same results). The near side of each slab is lo or hi by the direction's
  // sign. A zero direction component gives inv = +-inf: the slab is then (-inf, inf) or empty,
  // except for an origin exactly in its plane, where 0 * inf = NaN; the comparisons ignore a
  // NaN, which keeps the box closed. The far t is widened by 1 + 2 gamma(3) as in aabb.hpp,
  // once for all three axes (multiplying by a positive constant commutes with the minimum).
  // Returns a bit mask of the boxes hit and their entry t.
  static unsigned hit_boxes(const triangle_bvh_node4& n, const bvh_ray& r, float t_min,
                            float t_max, float (&t_enter)[4]) {
    constexpr float widen = 1.0f + 2.0f * gamma<float>(3);
#if defined(__SSE2__) && !defined(ZRAKA_NO_SIMD)  // the same operations, four lanes at once
    __m128 t0 = _mm_set1_ps(t_min), t1 = _mm_set1_ps(infinity<float>);
    for (int a = 0; a < 3; ++a) {
      const __m128 o = _mm_set1_ps(r.origin[a]), inv = _mm_set1_ps(r.inv_direction[a]);
      const __m128 tn = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[r.near_row[a]]), o), inv);
      const __m128 tf = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[r.far_row[a]]), o), inv);
      t0 = _mm_max_ps(tn, t0);  // tn > t0 ? tn : t0, so a NaN tn leaves t0
      t1 = _mm_min_ps(tf, t1);  // tf < t1 ? tf : t1
    }
    _mm_storeu_ps(t_enter, t0);
    const __m128 hit = _mm_and_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(widen))),
                                  _mm_cmple_ps(t0, _mm_set1_ps(t_max)));
    return unsigned(_mm_movemask_ps(hit));
#else
    float t0[4], t1[4];
    for (int k = 0; k < 4; ++k) t0[k] = t_min, t1[k] = infinity<float>;
    for (int a = 0; a < 3; ++a) {
      const float o = r.origin[a], inv = r.inv_direction[a];
      const float* near_side = n.box[r.near_row[a]];
      const float* far_side = n.box[r.far_row[a]];
      for (int k = 0; k < 4; ++k) {
        const float tn = (near_side[k] - o) * inv, tf = (far_side[k] - o) * inv;
        t0[k] = tn > t0[k] ? tn : t0[k];
        t1[k] = tf < t1[k] ? tf : t1[k];
      }
    }
    unsigned mask = 0;
    for (int k = 0; k < 4; ++k) {
      t_enter[k] = t0[k];
      mask |= unsigned(t0[k] <= t1[k] * widen && t0[k] <= t_max) << k;
    }
    return mask;
#endif
  }
  // [end]

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

  // A stack entry: a leaf (count > 0) or a node (count 0), with the t where the ray enters it.
  struct entry {
    std::uint32_t child, count;
    float t_enter;
  };
  static constexpr int stack_size = 3 * bvh_max_depth + 4;  // at most 3 left behind per level
  // A box's entry t and a triangle's t round differently: a triangle on a box face (a shared
  // edge of two leaves, say) may hit at a t an ulp or two below the box's entry. So a box is
  // passed over only when it starts more than 32 ulps beyond the best hit, and a tie at equal
  // t (won by the lower index) or a hit an ulp nearer is never lost to the order of the walk.
  static constexpr float cull_margin = 1.0f + 0x1p-18f;

  // [listing triangle-traverse]
  // Pop the nearest entry; skip it if a hit is already nearer than its box; test a leaf's
  // triangles, or a node's four boxes, whose hits are pushed farthest first (nearest on top).
  template <bool count>
  bool nearest(const bvh_ray& r, float t_min, float t_max, triangle_bvh_hit& h,
               bvh_stats* stats) const {
    if (nodes_.empty() || !r.valid) return false;
    std::array<entry, stack_size> stack;
    int top = 0;
    stack[top++] = {0, 0, t_min};
    bool found = false;
    while (top > 0) {
      const entry e = stack[--top];
      if (e.t_enter > t_max * cull_margin) continue;
      if (e.count) {
        const packed_triangle* tri = &tris_[e.child];
        for (std::uint32_t k = 0; k < e.count; ++k)
          if (test(tri[k], r, t_min, t_max, h)) {
            found = true;
            t_max = h.t;
          }
        if constexpr (count) stats->primitives += e.count;
        continue;
      }
      const triangle_bvh_node4& n = nodes_[e.child];
      float t[4];
      unsigned mask = hit_boxes(n, r, t_min, t_max * cull_margin, t);
      if constexpr (count) stats->nodes += 4;
      const int first = top;
      for (; mask; mask &= mask - 1) {  // insert each hit child, keeping [first, top) by t
        const int k = std::countr_zero(mask);
        int j = top++;
        for (; j > first && stack[j - 1].t_enter < t[k]; --j) stack[j] = stack[j - 1];
        stack[j] = {n.child[k], n.count[k], t[k]};
      }
    }
    return found;
  }
  // [end]

  template <bool count>
  bool any(const bvh_ray& r, float t_min, float t_max, bvh_stats* stats) const {
    if (nodes_.empty() || !r.valid) return false;
    std::array<entry, stack_size> stack;
    int top = 0;
    stack[top++] = {0, 0, t_min};
    while (top > 0) {
      const entry e = stack[--top];
      if (e.count) {
        for (std::uint32_t k = 0; k < e.count; ++k) {
          triangle_bvh_hit ignored;
          if constexpr (count) ++stats->primitives;
          if (test(tris_[e.child + k], r, t_min, t_max, ignored)) return true;
        }
        continue;
      }
      const triangle_bvh_node4& n = nodes_[e.child];
      float t[4];
      if constexpr (count) stats->nodes += 4;
      for (unsigned mask = hit_boxes(n, r, t_min, t_max, t); mask; mask &= mask - 1) {
        const int k = std::countr_zero(mask);
        stack[top++] = {n.child[k], n.count[k], t[k]};
      }
    }
    return false;
  }

  std::vector<triangle_bvh_node4> nodes_;
  std::vector<packed_triangle> tris_;
  std::size_t input_count_ = 0;
  int depth_ = 0;
};

}  // namespace zraka

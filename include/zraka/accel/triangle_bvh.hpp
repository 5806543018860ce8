#pragma once
// A BVH specialised for triangle meshes (book 5.2): compact and fast, for the teapot at a million
// triangles. The tree comes from bvh.hpp's builder (in float), collapsed to N children per node
// by wide_bvh.hpp, whose box test and front-to-back walk it shares with the scene's object BVH:
// triangle_bvh has eight (AVX2 tests them at once where the processor has it, SSE in two rounds
// elsewhere: simd.hpp), triangle_bvh4 four (the OpenCL kernel's layout, gpu_scene.hpp). The walk
// is compiled once per SIMD level, and each query takes the best level the processor runs.
// What is special here is the leaf:
// * the triangles copied in leaf order as the watertight test (triangle.hpp) wants them, four to
//   a block (watertight4.hpp's triangle4: the vertices A, B, C and the input index of each, 40
//   bytes a triangle), a leaf being whole blocks, its last one filled up with empty lanes;
// * a ray prepared once (bvh_ray): wide_bvh.hpp's box4_ray and the watertight test's axis
//   permutation and shear;
// * the watertight test on a block's four triangles at once (watertight4.hpp), where SSE is
//   there; the scalar test (packed-watertight below) is the reference and the fallback.
// No allocation per ray (wide_bvh.hpp's fixed stack).
// Hits report the triangle's index in the input, t and the barycentrics (u, v) of triangle.hpp's
// convention P = (1-u-v) A + u B + v C, bit for bit what intersect_watertight() gives on the
// same float triangle; among hits at exactly the same t the lowest index wins, so the result
// never depends on the tree.
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/simd.hpp>
#include <zraka/accel/watertight4.hpp>
#include <zraka/accel/wide_bvh.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/geometry/mesh.hpp>
#include <zraka/geometry/triangle.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>
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

// The nodes are wide_bvh.hpp's; a leaf's entries are positions in the blocks of four (triangle(k)).
using triangle_bvh_node4 = bvh_node4;
using triangle_bvh_node8 = bvh_node8;

// [listing bvh-ray]
// A ray prepared for many box and triangle tests: wide_bvh.hpp's half for the boxes (the
// reciprocal direction, which side of a box is near) and the watertight test's per-ray half
// (the axis permutation and the shear).
struct bvh_ray {
  vec3_t<float> origin, direction;
  box4_ray box;
  detail::watertight_ray<float> shear;
  bool valid;  // as triangle.hpp's can_hit() asks of a ray: box.valid and a finite direction
  explicit bvh_ray(const ray_t<float>& r)
      : origin(r.origin), direction(r.direction), box(r), shear(r), valid(box.valid & is_finite(r.direction)) {}
};
// [end]

template <int N> class wide_triangle_bvh {
 public:
  using node = wide_node<N>;
  static constexpr int width = N;  // children a node
  // Defaults measured on the teapot (book 5.2): the SAH prices a leaf by its blocks of four (a
  // leaf of 5 costs as much as one of 8), so leaves fill their blocks. The binary tree is built
  // to leaves of up to 12 with a box test priced at 2 block tests; the wide tree is then chosen
  // by cost from it (collapse_by_cost), with leaves of up to 16 and a wide node priced at 5.
  static bvh_build_options default_options() {
    bvh_build_options o;
    o.max_leaf_size = 12;
    o.traversal_cost = 2;
    o.leaf_block = 4;
    o.wide_leaf_size = 16;
    o.wide_node_cost = 5;
    return o;
  }

  wide_triangle_bvh() = default;
  explicit wide_triangle_bvh(const std::vector<triangle_t<float>>& tris,
                             const bvh_build_options& opt = default_options()) {
    build(tris, opt);
  }
  template <class T>
  explicit wide_triangle_bvh(const mesh_t<T>& m, const bvh_build_options& opt = default_options()) {
    std::vector<triangle_t<float>> tris(m.triangle_count());
    for (std::size_t i = 0; i < tris.size(); ++i) {
      const auto& f = m.triangles[i];
      tris[i] = {vec3_t<float>(m.positions[f[0]]), vec3_t<float>(m.positions[f[1]]),
                 vec3_t<float>(m.positions[f[2]])};
    }
    build(tris, opt);
  }

  // The full nodes; none where the tree is quantized (below).
  const std::vector<node>& nodes() const { return nodes_; }
  // Eight-wide only: the nodes in half the bytes (wide_bvh.hpp's wide_qnode8), which the walks
  // then use instead. The build quantizes a tree larger than eight L2 caches (bvh_build_options::
  // quantize, detail::quantize_above_bytes); a tree is quantized once and stays so.
  const std::vector<wide_qnode8>& quantized_nodes() const { return qnodes_; }
  bool quantized() const { return !qnodes_.empty(); }
  std::size_t node_count() const { return nodes_.size() + qnodes_.size(); }
  const std::vector<triangle4>& blocks() const { return blocks_; }  // in leaf order
  // Triangle k of the blocks (lane k % 4 of block k / 4): a leaf's triangles are the positions
  // [child, child + count) of its node; empty lanes have id UINT32_MAX.
  packed_triangle triangle(std::size_t k) const { return lane(blocks_[k / 4], k % 4); }
  static packed_triangle lane(const triangle4& q, std::size_t l) {
    return {{q.v[0][l], q.v[1][l], q.v[2][l]}, {q.v[3][l], q.v[4][l], q.v[5][l]},
            {q.v[6][l], q.v[7][l], q.v[8][l]}, q.id[l]};
  }
  std::size_t positions() const { return 4 * blocks_.size(); }  // triangles and empty lanes
  std::size_t triangle_count() const { return triangle_count_; }  // triangles stored
  std::size_t input_count() const { return input_count_; }
  int depth() const { return depth_; }
  // Memory of nodes and triangle data, and that per input triangle.
  std::size_t bytes() const {
    return nodes_.size() * sizeof(node) + qnodes_.size() * sizeof(wide_qnode8) + blocks_.size() * sizeof(triangle4);
  }
  double bytes_per_triangle() const {
    return input_count_ ? double(bytes()) / double(input_count_) : 0.0;
  }

  // The queries are defined below the class (and compiled once in zraka::compiled, compiled.hpp).
  // `simd` is the level of SIMD instructions the walk uses (simd.hpp): by default the best this
  // processor runs, never more than that (usable_simd). Every level gives the same hits.
  // The nearest hit with t in (t_min, t_max).
  bool intersect(const ray_t<float>& r, float t_min, float t_max, triangle_bvh_hit& h, bvh_stats* stats = nullptr,
                 simd_level simd = cpu_simd()) const;
  // Any hit with t in (t_min, t_max): for shadow rays; stops at the first.
  bool occluded(const ray_t<float>& r, float t_min, float t_max, bvh_stats* stats = nullptr,
                simd_level simd = cpu_simd()) const;
  // Every triangle, one at a time with the scalar test and the same tie rule: the reference the
  // BVH and its four-lane leaf must equal.
  bool intersect_brute_force(const ray_t<float>& r, float t_min, float t_max, triangle_bvh_hit& h) const;

 private:
  // The tree over the triangles, then their blocks.
  void build(const std::vector<triangle_t<float>>& tris, const bvh_build_options& opt);

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
    return accept(tri, r, t_min, t_max, t, u, v, h);
  }
  static bool accept(const packed_triangle& tri, const bvh_ray& r, float t_min, float t_max,
                     float t, float u, float v, triangle_bvh_hit& h) {
    const bool tie = h.triangle != UINT32_MAX && t == h.t && tri.id < h.triangle;
    if (!(t > t_min && (t < t_max || tie))) return false;
    if (!detail::t_certainly_positive(tri.a, tri.b, tri.c, r.origin, r.direction)) return false;
    h = {t, u, v, tri.id};
    return true;
  }
  // [end]

  // [listing block-test]
  // The four triangles of block q, as test() would take them one after the other: the four-lane
  // test (watertight4.hpp) finds the lanes hit, with their t, u and v, and the lanes whose edge
  // function rounded to 0. Without the four-lane test (or at the scalar level), test() on each lane.
  template <class Ray4, class Simd>
  static bool test_block(const triangle4& q, const bvh_ray& r, [[maybe_unused]] const Ray4& r4, float t_min,
                         float t_max, triangle_bvh_hit& h, Simd) {
#if ZRAKA_HAS_SSE
    if constexpr (detail::watertight4_available && !std::is_same_v<Simd, simd_scalar>) {
      // A lane can only be accepted with t < t_max or at a tie with the hit so far.
      const float bound = h.triangle != UINT32_MAX ? std::max(t_max, h.t) : t_max;
      lanes4 l;
      l.hit = detail::watertight_test4(r4, q, t_min, bound, l.t, l.u, l.v, l.scalar);
      return (l.hit | l.scalar) != 0 && accept_lanes(q, l, r, t_min, t_max, h);
    }
#endif
    bool found = false;
    for (std::size_t k = 0; k < 4; ++k) {
      const packed_triangle tri = lane(q, k);
      if (tri.id != UINT32_MAX && test(tri, r, t_min, t_max, h)) {
        found = true;
        t_max = h.t;
      }
    }
    return found;
  }
  // What the four-lane test found in a block: the lanes hit and their t, u, v; the lanes left to
  // test().
  struct lanes4 {
    float t[4], u[4], v[4];
    unsigned hit, scalar;
  };
  // Each lane found, in lane order, accepted or not by test()'s own rules (the interval with the
  // tie, the certainty of t > 0, which look at the hit found so far), or tested by test() itself.
  // (Inlined into the walk with the rest: with the eight-wide nodes that is faster than a call,
  // 0.72 -> 0.80 of Embree's speed on incoherent rays at 65k triangles, book 5.2.)
  static bool accept_lanes(const triangle4& q, const lanes4& l, const bvh_ray& r, float t_min, float t_max,
                           triangle_bvh_hit& h) {
    bool found = false;
    for (unsigned lanes = l.hit | l.scalar; lanes; lanes &= lanes - 1) {
      const int k = std::countr_zero(lanes);
      const packed_triangle tri = lane(q, std::size_t(k));
      if ((l.scalar >> k) & 1u ? test(tri, r, t_min, t_max, h) : accept(tri, r, t_min, t_max, l.t[k], l.u[k], l.v[k], h)) {
        found = true;
        t_max = h.t;
      }
    }
    return found;
  }
  // [end]

  // [listing triangle-traverse]
  // wide_bvh.hpp's walk with this leaf: its blocks of four triangles, each hit lowering t_max.
  template <class Simd>
  bool nearest(const bvh_ray& r, float t_min, float t_max, triangle_bvh_hit& h, bvh_stats* stats, Simd simd) const {
    if (!r.valid) return false;
    const auto r4 = ray4(r);
    auto leaf = [&](std::uint32_t first, std::uint32_t n, float& t_cull) {
      bool found = false;
      for (std::uint32_t k = 0; k < n; k += 4)
        if (test_block(blocks_[(first + k) / 4], r, r4, t_min, t_cull, h, simd)) {
          found = true;
          t_cull = h.t;
        }
      return found;
    };
    if constexpr (N == 8)
      if (quantized()) return wide_nearest(qnodes_, r.box, t_min, t_max, leaf, stats, simd);
    return wide_nearest(nodes_, r.box, t_min, t_max, leaf, stats, simd);
  }
  // [end]

  template <class Simd>
  bool any(const bvh_ray& r, float t_min, float t_max, bvh_stats* stats, Simd simd) const {
    if (!r.valid) return false;
    const auto r4 = ray4(r);
    auto leaf = [&](std::uint32_t first, std::uint32_t n) {
      for (std::uint32_t k = 0; k < n; k += 4) {
        triangle_bvh_hit ignored;
        if (test_block(blocks_[(first + k) / 4], r, r4, t_min, t_max, ignored, simd)) return true;
      }
      return false;
    };
    if constexpr (N == 8)
      if (quantized()) return wide_any(qnodes_, r.box, t_min, t_max, leaf, stats, simd);
    return wide_any(nodes_, r.box, t_min, t_max, leaf, stats, simd);
  }

  // [listing simd-walks]
  // The walks compiled once per SIMD level, with everything they call inlined into them
  // (flatten): the AVX2 ones are then AVX2 code throughout, the leaf's four lanes included, and
  // are only called on a processor that has it. Without statistics, a second copy that counts
  // nothing.
  template <class Simd> bool nearest_at(const bvh_ray& r, float t_min, float t_max, triangle_bvh_hit& h,
                                        bvh_stats* stats, Simd simd) const {
    return stats ? nearest(r, t_min, t_max, h, stats, simd) : nearest(r, t_min, t_max, h, nullptr, simd);
  }
  template <class Simd> bool any_at(const bvh_ray& r, float t_min, float t_max, bvh_stats* stats, Simd simd) const {
    return stats ? any(r, t_min, t_max, stats, simd) : any(r, t_min, t_max, nullptr, simd);
  }
  [[gnu::flatten]] bool nearest_scalar(const bvh_ray& r, float t_min, float t_max, triangle_bvh_hit& h,
                                       bvh_stats* stats) const {
    return nearest_at(r, t_min, t_max, h, stats, simd_scalar{});
  }
  [[gnu::flatten]] bool nearest_sse(const bvh_ray& r, float t_min, float t_max, triangle_bvh_hit& h,
                                    bvh_stats* stats) const {
    return nearest_at(r, t_min, t_max, h, stats, simd_sse{});
  }
  ZRAKA_TARGET_AVX2 [[gnu::flatten]] bool nearest_avx2(const bvh_ray& r, float t_min, float t_max,
                                                       triangle_bvh_hit& h, bvh_stats* stats) const {
    return nearest_at(r, t_min, t_max, h, stats, simd_avx2{});
  }
  [[gnu::flatten]] bool any_scalar(const bvh_ray& r, float t_min, float t_max, bvh_stats* stats) const {
    return any_at(r, t_min, t_max, stats, simd_scalar{});
  }
  [[gnu::flatten]] bool any_sse(const bvh_ray& r, float t_min, float t_max, bvh_stats* stats) const {
    return any_at(r, t_min, t_max, stats, simd_sse{});
  }
  ZRAKA_TARGET_AVX2 [[gnu::flatten]] bool any_avx2(const bvh_ray& r, float t_min, float t_max,
                                                   bvh_stats* stats) const {
    return any_at(r, t_min, t_max, stats, simd_avx2{});
  }
  // [end]

  // The four-lane test's ray, or nothing where there is none.
  // (An explicit return type: clang refuses a deduced one used above its definition.)
#if ZRAKA_HAS_SSE
  static detail::watertight_ray4 ray4(const bvh_ray& r) { return detail::watertight_ray4(r.shear); }
#else
  static bool ray4(const bvh_ray& r) { return r.valid; }
#endif

  std::vector<node> nodes_;
  std::vector<wide_qnode8> qnodes_;  // instead of nodes_, where quantized (eight-wide only)
  std::vector<triangle4> blocks_;
  std::size_t triangle_count_ = 0;
  std::size_t input_count_ = 0;
  int depth_ = 0;
};

template <int N>
bool wide_triangle_bvh<N>::intersect(const ray_t<float>& r, float t_min, float t_max, triangle_bvh_hit& h,
                                     bvh_stats* stats, simd_level simd) const {
  h = {};
  const bvh_ray br(r);
  switch (usable_simd(simd)) {
    case simd_level::avx2: return nearest_avx2(br, t_min, t_max, h, stats);
    case simd_level::sse: return nearest_sse(br, t_min, t_max, h, stats);
    case simd_level::scalar: break;
  }
  return nearest_scalar(br, t_min, t_max, h, stats);
}

template <int N>
bool wide_triangle_bvh<N>::occluded(const ray_t<float>& r, float t_min, float t_max, bvh_stats* stats,
                                    simd_level simd) const {
  const bvh_ray br(r);
  switch (usable_simd(simd)) {
    case simd_level::avx2: return any_avx2(br, t_min, t_max, stats);
    case simd_level::sse: return any_sse(br, t_min, t_max, stats);
    case simd_level::scalar: break;
  }
  return any_scalar(br, t_min, t_max, stats);
}

template <int N>
bool wide_triangle_bvh<N>::intersect_brute_force(const ray_t<float>& r, float t_min, float t_max,
                                                 triangle_bvh_hit& h) const {
  h = {};
  const bvh_ray br(r);
  if (!br.valid) return false;
  bool found = false;
  for (std::size_t k = 0; k < positions(); ++k) {
    const packed_triangle tri = triangle(k);
    if (tri.id != UINT32_MAX && test(tri, br, t_min, t_max, h)) {
      found = true;
      t_max = h.t;
    }
  }
  return found;
}

template <int N>
void wide_triangle_bvh<N>::build(const std::vector<triangle_t<float>>& tris, const bvh_build_options& opt) {
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
  triangle_count_ = b.order.size();
  nodes_ = collapse_by_cost<N>(b, {opt.wide_node_cost, opt.leaf_block, opt.wide_leaf_size});
  // Each leaf's triangles to whole blocks of four, in leaf order; its child index becomes the
  // position of its first triangle there (4 times its first block).
  triangle4 empty;
  for (auto& row : empty.v)
    for (float& x : row) x = std::numeric_limits<float>::quiet_NaN();
  for (std::uint32_t& id : empty.id) id = UINT32_MAX;
  for (node& n : nodes_)
    for (int k = 0; k < N; ++k) {
      if (n.count[k] == 0) continue;
      const std::uint32_t first = n.child[k];
      n.child[k] = std::uint32_t(4 * blocks_.size());
      for (std::uint32_t j = 0; j < n.count[k]; ++j) {
        if (j % 4 == 0) blocks_.push_back(empty);
        const std::uint32_t i = b.order[first + j];
        const float* v[3] = {glm::value_ptr(tris[i].a), glm::value_ptr(tris[i].b),
                             glm::value_ptr(tris[i].c)};
        for (int row = 0; row < 9; ++row) blocks_.back().v[row][j % 4] = v[row / 3][row % 3];
        blocks_.back().id[j % 4] = i;
      }
    }
  if constexpr (N == 8) {
    if (opt.quantize == 1 || (opt.quantize < 0 && bytes() > detail::quantize_above_bytes())) {
      qnodes_.resize(nodes_.size());
      for (std::size_t k = 0; k < nodes_.size(); ++k) quantize(nodes_[k], qnodes_[k]);
      nodes_ = {};
    }
  }
}

using triangle_bvh = wide_triangle_bvh<8>;   // the CPU's
using triangle_bvh4 = wide_triangle_bvh<4>;  // the OpenCL kernel's layout (gpu_scene.hpp)
ZRAKA_INSTANCE(class wide_triangle_bvh<8>)   // compiled.hpp
ZRAKA_INSTANCE(class wide_triangle_bvh<4>)

}  // namespace zraka

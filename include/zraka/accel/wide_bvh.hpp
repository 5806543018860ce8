#pragma once
// The wide BVH (book 5.2): bvh.hpp's binary tree collapsed into nodes of N children (4 or 8)
// whose boxes are tested at once, one SIMD instruction per step for all of them (simd.hpp: SSE
// takes four, AVX2 eight). One layout, one box test and one traversal, for any N, serve both users:
// * triangle_bvh.hpp, a mesh's triangles (float rays), eight children a node;
// * the scene's object BVH (scene.hpp, scene_query.hpp): spheres, quads, triangles, meshes and
//   user shapes, in float or double, four children a node.
// The boxes are stored in float whatever the tree's precision, rounded outward, so that a float
// box contains its double box; a double ray is made a float one the same careful way (its origin
// rounded towards the side that lengthens each slab). The box test therefore keeps every box the
// exact test keeps, and the hits are those of the readable binary traversal (bvh_intersect), as
// tests/test_wide_bvh.cpp checks; only the order of the walk differs.
// No allocation per ray: the traversal stack is a fixed array, sized by bvh_max_depth, which the
// builder respects (bvh.hpp) and collapse() checks.
#include <zraka/geometry/aabb.hpp>
#include <zraka/accel/bvh.hpp>
#include <zraka/core/error.hpp>
#include <zraka/accel/simd.hpp>

#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>  // sysconf
#endif

#if ZRAKA_HAS_SSE
#include <immintrin.h>
#endif

namespace zraka {

// [listing compact-node]
// A node with N children (4: a binary BVH with every other level removed; 8: two of every three).
// Child k's box is box[a][k] <= x[a] <= box[3 + a][k] (rows lo.x, lo.y, lo.z, hi.x, hi.y, hi.z).
// A child is a leaf of count[k] entries from position child[k] of the primitive order, or an
// inner node nodes[child[k]] (count 0). Unused slots have an empty box, which no ray hits.
template <int N> struct alignas(64) wide_node {
  static constexpr int width = N;
  float box[6][N];
  std::uint32_t child[N];
  std::uint32_t count[N];
};
using bvh_node4 = wide_node<4>;
using bvh_node8 = wide_node<8>;
// [end]
static_assert(sizeof(bvh_node4) == 128, "two cache lines");
static_assert(sizeof(bvh_node8) == 256, "four cache lines");

// x rounded to a float towards -inf (down) or +inf (up): float(x) rounds to nearest, one step
// fixes the side. Beyond float's range: down(1e300) = FLT_MAX, up(1e300) = inf. The step is
// std::nextafter's done on the bits without a branch: whether float(x) fell below or above x is
// a coin toss for a ray's origin, and a mispredicted branch costs more than the box test.
namespace detail {
inline float float_step(float f, bool up, bool step) {
  auto bits = std::bit_cast<std::uint32_t>(f);
  if (up) bits = bits == 0x80000000u ? 0u : bits;  // from -0 up: as from +0
  else bits = bits == 0u ? 0x80000000u : bits;     // from +0 down: as from -0
  const bool negative = (bits >> 31) != 0;
  const std::uint32_t delta = up != negative ? 1u : ~0u;  // away from 0 (+1) or towards it (-1)
  return std::bit_cast<float>(bits + (step ? delta : 0u));
}
}  // namespace detail
template <class T> float float_down(T x) {
  const float f = static_cast<float>(x);
  return detail::float_step(f, false, static_cast<T>(f) > x);
}
template <class T> float float_up(T x) {
  const float f = static_cast<float>(x);
  return detail::float_step(f, true, static_cast<T>(f) < x);
}

// [listing box4-ray]
// A ray prepared for the four-box test: the reciprocal direction, per axis which row of a node
// is the near side of a slab (lo where the direction is positive, hi where negative, by the sign
// bit: 1/(-0) = -inf), and the origin. A double origin is rounded to float in two ways, so that
// each slab only grows: towards the far side for the near plane and towards the near side for
// the far plane. A float ray keeps its origin. `exact` is false when the reciprocal direction
// does not fit in float's normal range (a component below ~1e-38 but not 0, or beyond ~1e38):
// the traversal then visits every leaf rather than risk losing one. So does an infinite
// component (its reciprocal 0 is below that range). A NaN component: no ray at all.
struct box4_ray {
  float near_origin[3], far_origin[3], inv_direction[3];
  int near_row[3], far_row[3];
  bool valid = false;  // a finite origin and a finite, non-zero direction
  bool exact = true;
  template <class T> explicit box4_ray(const ray_t<T>& r) {
#if ZRAKA_HAS_SSE
    if constexpr (std::is_same_v<T, float>) {
      prepare_sse(r);
      return;
    }
#endif
    prepare(r);
  }
  template <class T> box4_ray(const ray_t<T>& r, simd_scalar) { prepare(r); }
  template <class T> void prepare(const ray_t<T>& r) {
    // Every test below is a bitwise & or | of comparisons and every choice a select, not a
    // branch: for incoherent rays the signs of the direction are coin tosses, and mispredicted
    // branches made this setup a sixth of a small mesh's walk.
    const T* o = glm::value_ptr(r.origin);
    const T* d = glm::value_ptr(r.direction);
    bool finite = true, nonzero = false, in_range = true;
    for (int a = 0; a < 3; ++a) {
      const int negative = std::signbit(d[a]);
      near_row[a] = a + 3 * negative;
      far_row[a] = a + 3 - 3 * negative;
      const T inv = T(1) / d[a];
      inv_direction[a] = static_cast<float>(inv);
      finite = finite & std::isfinite(o[a]) & !std::isnan(d[a]);
      nonzero = nonzero | (d[a] != T(0));
      in_range = in_range & ((d[a] == T(0)) | ((std::abs(inv) >= T(std::numeric_limits<float>::min())) &
                                               (std::abs(inv) <= T(std::numeric_limits<float>::max()))));
      if constexpr (std::is_same_v<T, float>) {  // already float: nothing to round
        near_origin[a] = far_origin[a] = o[a];
      } else {
        const float down = float_down(o[a]), up = float_up(o[a]);
        near_origin[a] = negative ? down : up;
        far_origin[a] = negative ? up : down;
      }
    }
    valid = finite & nonzero;
    exact = in_range;
  }
#if ZRAKA_HAS_SSE
  // The same with the three axes in SSE lanes (lane 3 a dummy 1): one division instead of three,
  // and the tests as four-lane comparisons (a quarter of the instructions of a small mesh's ray
  // went to this setup). The same members, bit for bit (test_triangle_bvh.cpp).
  void prepare_sse(const ray_t<float>& r) {
    const __m128 o = _mm_setr_ps(r.origin.x, r.origin.y, r.origin.z, 0.0f);
    const __m128 d = _mm_setr_ps(r.direction.x, r.direction.y, r.direction.z, 1.0f);
    const __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), d);
    float lanes[4];
    _mm_storeu_ps(lanes, inv);
    const int negative = _mm_movemask_ps(d);  // the sign bits, as std::signbit
    for (int a = 0; a < 3; ++a) {
      inv_direction[a] = lanes[a];
      const int n = (negative >> a) & 1;
      near_row[a] = a + 3 * n;
      far_row[a] = a + 3 - 3 * n;
      near_origin[a] = far_origin[a] = glm::value_ptr(r.origin)[a];
    }
    const __m128 magnitude = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
    const __m128 abs_o = _mm_and_ps(o, magnitude), abs_inv = _mm_and_ps(inv, magnitude);
    const int finite = _mm_movemask_ps(_mm_and_ps(_mm_cmplt_ps(abs_o, _mm_set1_ps(infinity<float>)), _mm_cmpord_ps(d, d)));
    const int zero = _mm_movemask_ps(_mm_cmpeq_ps(d, _mm_setzero_ps()));
    const int in_range = _mm_movemask_ps(_mm_and_ps(_mm_cmpge_ps(abs_inv, _mm_set1_ps(std::numeric_limits<float>::min())),
                                                    _mm_cmple_ps(abs_inv, _mm_set1_ps(std::numeric_limits<float>::max()))));
    valid = (finite & 7) == 7 && (~zero & 7) != 0;
    exact = ((zero | in_range) & 7) == 7;
  }
#endif
};
// [end]

// [listing fast-slab]
// The slab test of a node's N child boxes at once: the same few operations on every lane. Here in
// plain loops (simd_scalar), which any machine runs; below as SSE instructions on four lanes at a
// time and AVX2 on eight (simd.hpp), which give the same results. A zero direction component
// gives inv = +-inf: the slab is then (-inf, inf) or empty, except for an origin exactly in its
// plane, where 0 * inf = NaN; the maximum and minimum below take their second operand when the
// first is NaN (as SSE's and AVX2's do), so a NaN keeps the slab open: the careful side. The far
// t is widened by 1 + 2 gamma(4), once for all three axes (a positive factor commutes with the
// minimum): aabb.hpp's gamma(3) for the subtraction, the reciprocal and the product, and one more
// for a double reciprocal rounded to float. An unused slot is left out by its empty box
// (lo > hi), not by its slabs: an origin beyond float's range is infinite in float, and
// inf - inf = NaN would keep them open. Returns a bit mask of the boxes hit and their entry t.
constexpr float wide_slab_widen = 1.0f + 2.0f * gamma<float>(4);

template <int N>
unsigned hit_boxes(const wide_node<N>& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[N],
                   simd_scalar) {
  float t0[N], t1[N];
  for (int k = 0; k < N; ++k) t0[k] = t_min, t1[k] = infinity<float>;
  for (int a = 0; a < 3; ++a) {
    const float inv = r.inv_direction[a];
    const float* near_side = n.box[r.near_row[a]];
    const float* far_side = n.box[r.far_row[a]];
    for (int k = 0; k < N; ++k) {
      const float tn = (near_side[k] - r.near_origin[a]) * inv;
      const float tf = (far_side[k] - r.far_origin[a]) * inv;
      t0[k] = tn > t0[k] ? tn : t0[k];
      t1[k] = tf < t1[k] ? tf : t1[k];
    }
  }
  unsigned mask = 0;
  for (int k = 0; k < N; ++k) {
    t_enter[k] = t0[k];
    mask |= unsigned(t0[k] <= t1[k] * wide_slab_widen && t0[k] <= t_max && n.box[0][k] <= n.box[3][k]) << k;
  }
  return mask;
}
// [end]

#if ZRAKA_HAS_SSE
// [listing sse-slab]
// The same on four lanes per SSE instruction (GCC did not vectorise the plain loop): N / 4 rounds.
template <int N>
unsigned hit_boxes(const wide_node<N>& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[N],
                   simd_sse) {
  unsigned mask = 0;
  for (int h = 0; h < N; h += 4) {
    __m128 t0 = _mm_set1_ps(t_min), t1 = _mm_set1_ps(infinity<float>);
    for (int a = 0; a < 3; ++a) {
      const __m128 inv = _mm_set1_ps(r.inv_direction[a]);
      const __m128 on = _mm_set1_ps(r.near_origin[a]), of = _mm_set1_ps(r.far_origin[a]);
      const __m128 tn = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[r.near_row[a]] + h), on), inv);
      const __m128 tf = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(n.box[r.far_row[a]] + h), of), inv);
      t0 = _mm_max_ps(tn, t0);  // tn > t0 ? tn : t0, so a NaN tn leaves t0
      t1 = _mm_min_ps(tf, t1);  // tf < t1 ? tf : t1
    }
    _mm_storeu_ps(t_enter + h, t0);
    const __m128 used = _mm_cmple_ps(_mm_load_ps(n.box[0] + h), _mm_load_ps(n.box[3] + h));
    const __m128 hit = _mm_and_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(wide_slab_widen))),
                                  _mm_and_ps(_mm_cmple_ps(t0, _mm_set1_ps(t_max)), used));
    mask |= unsigned(_mm_movemask_ps(hit)) << h;
  }
  return mask;
}
// [end]
#else
template <int N>
unsigned hit_boxes(const wide_node<N>& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[N],
                   simd_sse) {
  return hit_boxes(n, r, t_min, t_max, t_enter, simd_scalar{});
}
#endif

#if ZRAKA_HAS_AVX2_TARGET && ZRAKA_HAS_SSE
// [listing avx2-slab]
// And on eight lanes per AVX2 instruction: an eight-wide node in one round. Compiled for AVX2
// whatever the build's flags; run only where cpu_simd() found it (simd.hpp).
ZRAKA_TARGET_AVX2 inline unsigned hit_boxes(const bvh_node8& n, const box4_ray& r, float t_min, float t_max,
                                            float (&t_enter)[8], simd_avx2) {
  __m256 t0 = _mm256_set1_ps(t_min), t1 = _mm256_set1_ps(infinity<float>);
  for (int a = 0; a < 3; ++a) {
    const __m256 inv = _mm256_set1_ps(r.inv_direction[a]);
    const __m256 on = _mm256_set1_ps(r.near_origin[a]), of = _mm256_set1_ps(r.far_origin[a]);
    const __m256 tn = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.box[r.near_row[a]]), on), inv);
    const __m256 tf = _mm256_mul_ps(_mm256_sub_ps(_mm256_load_ps(n.box[r.far_row[a]]), of), inv);
    t0 = _mm256_max_ps(tn, t0);
    t1 = _mm256_min_ps(tf, t1);
  }
  _mm256_storeu_ps(t_enter, t0);
  const __m256 used = _mm256_cmp_ps(_mm256_load_ps(n.box[0]), _mm256_load_ps(n.box[3]), _CMP_LE_OQ);
  const __m256 near_enough = _mm256_cmp_ps(t0, _mm256_set1_ps(t_max), _CMP_LE_OQ);
  const __m256 hit = _mm256_and_ps(
      _mm256_cmp_ps(t0, _mm256_mul_ps(t1, _mm256_set1_ps(wide_slab_widen)), _CMP_LE_OQ),
      _mm256_and_ps(near_enough, used));
  return unsigned(_mm256_movemask_ps(hit));
}
// [end]
#endif
// Four boxes take four lanes whatever AVX2 offers; without AVX2, eight take two rounds of four.
template <int N>
unsigned hit_boxes(const wide_node<N>& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[N],
                   simd_avx2)
  requires(N != 8 || !(ZRAKA_HAS_AVX2_TARGET && ZRAKA_HAS_SSE))
{
  return hit_boxes(n, r, t_min, t_max, t_enter, simd_sse{});
}

namespace detail {
// A wide node with every slot unused: empty boxes (lo > hi), which no ray hits.
template <int N> wide_node<N> empty_wide_node() {
  wide_node<N> n;
  for (int k = 0; k < N; ++k) {
    for (int a = 0; a < 3; ++a) n.box[a][k] = infinity<float>, n.box[3 + a][k] = -infinity<float>;
    n.child[k] = n.count[k] = 0;
  }
  return n;
}

// Slot k of wide node w holds binary node n's box, rounded outward to float, and child/count.
template <int N, class T>
void set_slot(wide_node<N>& w, int k, const bvh_node_t<T>& n, std::uint32_t child, std::uint32_t count) {
  for (int a = 0; a < 3; ++a) {
    w.box[a][k] = float_down(n.box.lo[a]);
    w.box[3 + a][k] = float_up(n.box.hi[a]);
  }
  w.child[k] = child;
  w.count[k] = count;
}
// Both collapses keep the wide tree no deeper than b, so b must fit the traversal stack.
template <class T> void check_depth(const bvh_t<T>& b) {
  if (b.depth > bvh_max_depth)
    throw error("wide BVH: the tree is " + std::to_string(b.depth) + " levels deep, the traversal stack holds " +
                std::to_string(bvh_max_depth));
}

// The N children of one wide node are binary nodes; they start as one node's two children.
template <int N, class T>
std::uint32_t collapse_node(const bvh_t<T>& b, std::uint32_t first, std::uint32_t second,
                            std::vector<wide_node<N>>& out) {
  std::array<std::uint32_t, N> kids{first, second};
  int count = 2;
  while (count < N) {  // open the inner kid with the largest box
    int widest = -1;
    T widest_area = -1;
    for (int k = 0; k < count; ++k) {
      const bvh_node_t<T>& n = b.nodes[kids[std::size_t(k)]];
      if (!n.leaf() && n.box.surface_area() > widest_area) {
        widest = k;
        widest_area = n.box.surface_area();
      }
    }
    if (widest < 0) break;  // only leaves
    const std::uint32_t k = kids[std::size_t(widest)];
    kids[std::size_t(widest)] = k + 1;  // the first child follows its parent
    kids[std::size_t(count++)] = b.nodes[k].index;  // the second
  }
  const auto me = static_cast<std::uint32_t>(out.size());
  out.push_back(empty_wide_node<N>());
  for (int k = 0; k < count; ++k) {
    const bvh_node_t<T>& n = b.nodes[kids[std::size_t(k)]];
    const std::uint32_t child = n.leaf() ? n.index : collapse_node<N>(b, kids[std::size_t(k)] + 1, n.index, out);
    set_slot(out[me], k, n, child, n.count);
  }
  return me;
}
}  // namespace detail

// [listing collapse]
// The wide nodes of binary tree b, the root's first: a wide node takes the binary node's two
// children and, while it has fewer than N and one of them is an inner node, replaces the one
// with the largest box by its two children. Its inner children are collapsed in turn, depth
// first. Boxes are rounded outward to float. A leaf's entries keep their positions in b.order.
// Each wide level consumes at least one binary level, so the wide tree is no deeper than b.
template <int N, class T> std::vector<wide_node<N>> collapse(const bvh_t<T>& b) {
  detail::check_depth(b);
  std::vector<wide_node<N>> out;
  if (b.empty()) return out;
  out.reserve(b.nodes.size() / (N - 1) + 1);
  if (b.nodes[0].leaf()) {  // a root leaf: one wide node with one child
    detail::set_slot(out.emplace_back(detail::empty_wide_node<N>()), 0, b.nodes[0], b.nodes[0].index,
                     b.nodes[0].count);
    return out;
  }
  detail::collapse_node<N>(b, 1, b.nodes[0].index, out);
  return out;
}
// [end]

// [listing collapse-by-cost]
// The same conversion, chosen by cost instead of by box size (triangle_bvh.hpp): the SAH of the
// wide tree, a wide node costing node_cost and a leaf its blocks (ceil(n / leaf_block)), each
// times its box's area, is made as small as this binary tree allows, by dynamic programming from
// the leaves up. For binary node n and i = 1..N, cost(n, i) is the least cost of n's subtree
// given i slots of the wide node above it. One slot: n is a wide leaf (its primitives are
// contiguous in b.order; at most max_leaf of them) or a wide node whose N slots its two children
// share. More: the two children share the i slots, or fewer are used. A leaf of b is a leaf.
struct collapse_costs {
  double node = 5;     // a wide node's box tests, in leaf blocks
  int leaf_block = 4;  // primitives tested at once
  int max_leaf = 16;   // primitives a wide leaf may hold (at most 255)
};
namespace detail {
template <int N, class T> class cost_collapse {
 public:
  cost_collapse(const bvh_t<T>& b, const collapse_costs& c, std::vector<wide_node<N>>& out)
      : b_(b), c_(c), out_(out), f_(b.nodes.size()) {}
  void run() {
    solve(0);
    if (f_[0].leaf) {  // the whole tree is one leaf: one wide node with one child
      out_.push_back(empty_wide_node<N>());
      put(0, 0, 0);
      return;
    }
    emit(0);
  }
  double cost() const { return f_.empty() ? 0.0 : f_[0].cost[1]; }

 private:
  struct sub {
    double cost[N + 1];  // cost(n, i)
    int left[N + 1];     // the slots the first child gets; 0: i - 1 slots do as well
    bool leaf;           // with one slot: a wide leaf (else a wide node)
    std::uint32_t first, count;  // the subtree's primitives: b.order[first, first + count)
  };
  double blocks(std::uint32_t n) const { return double((n + std::uint32_t(c_.leaf_block) - 1) / std::uint32_t(c_.leaf_block)); }
  void solve(std::uint32_t n) {
    const bvh_node_t<T>& node = b_.nodes[n];
    sub& f = f_[n];
    const double area = double(node.box.surface_area());
    if (node.leaf()) {
      f.first = node.index, f.count = node.count, f.leaf = true;
      for (int i = 1; i <= N; ++i) f.cost[i] = area * blocks(node.count), f.left[i] = 0;
      return;
    }
    const std::uint32_t l = n + 1, r = node.index;  // the first child follows its parent
    solve(l);
    solve(r);
    f.first = f_[l].first, f.count = f_[l].count + f_[r].count;
    double shared[N + 1];  // the two children in j slots
    int left[N + 1];
    for (int j = 2; j <= N; ++j) {
      shared[j] = infinity<double>, left[j] = 1;
      for (int k = 1; k < j; ++k)
        if (const double c = f_[l].cost[k] + f_[r].cost[j - k]; c < shared[j]) shared[j] = c, left[j] = k;
    }
    const double as_leaf = f.count <= std::uint32_t(c_.max_leaf) ? area * blocks(f.count) : infinity<double>;
    const double as_node = area * c_.node + shared[N];
    f.leaf = as_leaf <= as_node;
    f.cost[1] = std::min(as_leaf, as_node), f.left[1] = 0;
    f.left[0] = left[N];  // as a wide node: the first child's share of its N slots
    for (int i = 2; i <= N; ++i) {
      if (f.cost[i - 1] <= shared[i]) f.cost[i] = f.cost[i - 1], f.left[i] = 0;
      else f.cost[i] = shared[i], f.left[i] = left[i];
    }
  }
  // The binary nodes that fill i slots for n's subtree.
  void slots(std::uint32_t n, int i, std::array<std::uint32_t, N>& s, int& count) const {
    while (i > 1 && f_[n].left[i] == 0) --i;
    if (i == 1 || b_.nodes[n].leaf()) {
      s[std::size_t(count++)] = n;
      return;
    }
    slots(n + 1, f_[n].left[i], s, count);
    slots(b_.nodes[n].index, i - f_[n].left[i], s, count);
  }
  // Binary node n as slot k of wide node w.
  void put(std::uint32_t w, int k, std::uint32_t n) {
    if (f_[n].leaf) set_slot(out_[w], k, b_.nodes[n], f_[n].first, f_[n].count);
    else {
      const std::uint32_t child = emit(n);  // grows out_: index w afresh after it
      set_slot(out_[w], k, b_.nodes[n], child, 0);
    }
  }
  // Binary node n (inner) as a wide node: its children share the N slots.
  std::uint32_t emit(std::uint32_t n) {
    std::array<std::uint32_t, N> s{};
    int count = 0;
    slots(n + 1, f_[n].left[0], s, count);
    slots(b_.nodes[n].index, N - f_[n].left[0], s, count);
    const auto me = static_cast<std::uint32_t>(out_.size());
    out_.push_back(empty_wide_node<N>());
    for (int k = 0; k < count; ++k) put(me, k, s[std::size_t(k)]);
    return me;
  }
  const bvh_t<T>& b_;
  collapse_costs c_;
  std::vector<wide_node<N>>& out_;
  std::vector<sub> f_;
};
}  // namespace detail
template <int N, class T>
std::vector<wide_node<N>> collapse_by_cost(const bvh_t<T>& b, const collapse_costs& c, double* cost = nullptr) {
  detail::check_depth(b);
  if (c.max_leaf < 1 || c.max_leaf > 255)
    throw error("wide BVH: collapse costs: max_leaf must be in 1..255, got " + std::to_string(c.max_leaf));
  if (c.leaf_block < 1) throw error("wide BVH: collapse costs: leaf_block must be at least 1");
  if (!(c.node >= 0) || !std::isfinite(c.node)) throw error("wide BVH: collapse costs: node must be finite and >= 0");
  std::vector<wide_node<N>> out;
  if (b.empty()) return out;
  out.reserve(b.nodes.size() / (N - 1) + 1);
  detail::cost_collapse<N, T> d(b, c, out);
  d.run();
  if (cost) *cost = d.cost();
  return out;
}
// [end]

// [listing quantized-node]
// An eight-wide node in half the bytes, two cache lines instead of four, for trees too large for
// the cache (triangle_bvh.hpp): each bound of a child's box is a byte q, read back as
//     b = q * scale[a] + origin[a],
// origin the smallest lower bound of the node's children on axis a and scale a power of two,
// so that q * scale is exact and the sum is rounded once (a fused multiply-add gives the same
// float). Rounding is monotone, so the byte of a lower bound is the largest q whose b is not
// above it, and of an upper bound the smallest whose b is not below it: the box read back
// contains the child's box, and a ray that hits the child hits its byte box (and perhaps a
// little more, never less). Unused slots are left out by `used`, not by their bytes.
struct alignas(64) wide_qnode8 {
  static constexpr int width = 8;
  float origin[3], scale[3];
  std::uint8_t q[6][8];  // rows lo.x, lo.y, lo.z, hi.x, hi.y, hi.z, as wide_node's box
  std::uint32_t child[8];
  std::uint8_t count[8];  // as wide_node's (a leaf holds at most 255 entries)
  std::uint8_t used;      // bit k: slot k holds a child
};
static_assert(sizeof(wide_qnode8) == 128, "two cache lines");

namespace detail {
// The size of one core's L2 cache, as the C library reports it (1 MiB where it does not).
inline std::size_t l2_cache_bytes() {
  static const std::size_t bytes = [] {
#if defined(_SC_LEVEL2_CACHE_SIZE)
    if (const long b = sysconf(_SC_LEVEL2_CACHE_SIZE); b > 0) return std::size_t(b);
#endif
    return std::size_t(1) << 20;
  }();
  return bytes;
}
// Where the build quantizes by itself: trees of more than eight L2 caches. Measured with
// bench/bvh_embree (book 5.2): up to six caches the full nodes are as fast or faster (coherent
// rays lose with the extra work), at twelve and at twenty-five the incoherent rays gain.
inline std::size_t quantize_above_bytes() { return 8 * l2_cache_bytes(); }

inline float dequantize(std::uint8_t q, float scale, float origin) { return float(q) * scale + origin; }
inline int byte_estimate(double x) { return x >= 0 ? int(std::min(x, 255.0)) : 0; }  // NaN too: 0
}  // namespace detail

// n's bytes for full node f. A leaf's count must fit a byte: bvh.hpp holds leaves to 255.
inline void quantize(const bvh_node8& f, wide_qnode8& n) {
  n = {};
  for (int k = 0; k < 8; ++k) {
    n.child[k] = f.child[k];
    if (f.count[k] > 255) throw error("quantize: a leaf of " + std::to_string(f.count[k]) + " entries (at most 255)");
    n.count[k] = std::uint8_t(f.count[k]);
    n.used |= std::uint8_t(unsigned(f.box[0][k] <= f.box[3][k]) << k);
  }
  for (int a = 0; a < 3; ++a) {
    float lo = infinity<float>, hi = -infinity<float>;
    for (int k = 0; k < 8; ++k)
      if ((n.used >> k) & 1u) lo = std::min(lo, f.box[a][k]), hi = std::max(hi, f.box[3 + a][k]);
    if (!(lo <= hi)) lo = hi = 0;  // no child
    n.origin[a] = lo;
    // The smallest power of two that spans the extent in 255 steps (the extent in double: a
    // float's may overflow), raised while the top byte still reads back below hi.
    int e = -149;
    if (const double extent = double(hi) - double(lo); extent > 0) e = std::max(-149, int(std::ceil(std::log2(extent / 255))));
    while (e < 127 && detail::dequantize(255, std::ldexp(1.0f, e), lo) < hi) ++e;
    n.scale[a] = std::ldexp(1.0f, e);
    const auto read = [&](int q) { return detail::dequantize(std::uint8_t(q), n.scale[a], lo); };
    for (int k = 0; k < 8; ++k) {
      if (!((n.used >> k) & 1u)) continue;
      // From the estimate in double, stepped to the exact answer in float (a step or two).
      int q_lo = detail::byte_estimate(std::floor((double(f.box[a][k]) - lo) / n.scale[a]));
      while (q_lo > 0 && read(q_lo) > f.box[a][k]) --q_lo;
      while (q_lo < 255 && read(q_lo + 1) <= f.box[a][k]) ++q_lo;
      int q_hi = detail::byte_estimate(std::ceil((double(f.box[3 + a][k]) - lo) / n.scale[a]));
      while (q_hi < 255 && read(q_hi) < f.box[3 + a][k]) ++q_hi;
      while (q_hi > 0 && read(q_hi - 1) >= f.box[3 + a][k]) --q_hi;
      n.q[a][k] = std::uint8_t(q_lo);
      n.q[3 + a][k] = std::uint8_t(q_hi);
    }
  }
}
// [end]

// [listing quantized-slab]
// The slab test of fast-slab on the boxes read back from the bytes: the same operations after
// one multiply and one add per bound.
inline unsigned hit_boxes(const wide_qnode8& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[8],
                          simd_scalar) {
  float t0[8], t1[8];
  for (int k = 0; k < 8; ++k) t0[k] = t_min, t1[k] = infinity<float>;
  for (int a = 0; a < 3; ++a) {
    const float inv = r.inv_direction[a];
    for (int k = 0; k < 8; ++k) {
      const float near_side = detail::dequantize(n.q[r.near_row[a]][k], n.scale[a], n.origin[a]);
      const float far_side = detail::dequantize(n.q[r.far_row[a]][k], n.scale[a], n.origin[a]);
      const float tn = (near_side - r.near_origin[a]) * inv;
      const float tf = (far_side - r.far_origin[a]) * inv;
      t0[k] = tn > t0[k] ? tn : t0[k];
      t1[k] = tf < t1[k] ? tf : t1[k];
    }
  }
  unsigned mask = 0;
  for (int k = 0; k < 8; ++k) {
    t_enter[k] = t0[k];
    mask |= unsigned(t0[k] <= t1[k] * wide_slab_widen && t0[k] <= t_max) << k;
  }
  return mask & n.used;
}
// [end]

#if ZRAKA_HAS_SSE
// The same with SSE, four children at a time: bytes to ints by unpacking with zeros (SSE2).
inline unsigned hit_boxes(const wide_qnode8& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[8],
                          simd_sse) {
  unsigned mask = 0;
  const __m128i zero = _mm_setzero_si128();
  auto bounds = [&](int row, int h, __m128 scale, __m128 origin) {
    std::int32_t four;
    std::memcpy(&four, &n.q[row][h], 4);
    const __m128i q = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(four), zero), zero);
    return _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(q), scale), origin);
  };
  for (int h = 0; h < 8; h += 4) {
    __m128 t0 = _mm_set1_ps(t_min), t1 = _mm_set1_ps(infinity<float>);
    for (int a = 0; a < 3; ++a) {
      const __m128 scale = _mm_set1_ps(n.scale[a]), origin = _mm_set1_ps(n.origin[a]);
      const __m128 inv = _mm_set1_ps(r.inv_direction[a]);
      const __m128 tn = _mm_mul_ps(_mm_sub_ps(bounds(r.near_row[a], h, scale, origin), _mm_set1_ps(r.near_origin[a])), inv);
      const __m128 tf = _mm_mul_ps(_mm_sub_ps(bounds(r.far_row[a], h, scale, origin), _mm_set1_ps(r.far_origin[a])), inv);
      t0 = _mm_max_ps(tn, t0);
      t1 = _mm_min_ps(tf, t1);
    }
    _mm_storeu_ps(t_enter + h, t0);
    const __m128 hit = _mm_and_ps(_mm_cmple_ps(t0, _mm_mul_ps(t1, _mm_set1_ps(wide_slab_widen))),
                                  _mm_cmple_ps(t0, _mm_set1_ps(t_max)));
    mask |= unsigned(_mm_movemask_ps(hit)) << h;
  }
  return mask & n.used;
}
#else
inline unsigned hit_boxes(const wide_qnode8& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[8],
                          simd_sse) {
  return hit_boxes(n, r, t_min, t_max, t_enter, simd_scalar{});
}
#endif

#if ZRAKA_HAS_AVX2_TARGET && ZRAKA_HAS_SSE
// And with AVX2, the eight at once (bytes to ints: vpmovzxbd). (A function, not a lambda: a
// lambda is not compiled for AVX2.)
ZRAKA_TARGET_AVX2 inline __m256 quantized_bounds(const wide_qnode8& n, int row, __m256 scale, __m256 origin) {
  const __m128i q = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(n.q[row]));
  return _mm256_add_ps(_mm256_mul_ps(_mm256_cvtepi32_ps(_mm256_cvtepu8_epi32(q)), scale), origin);
}
ZRAKA_TARGET_AVX2 inline unsigned hit_boxes(const wide_qnode8& n, const box4_ray& r, float t_min, float t_max,
                                            float (&t_enter)[8], simd_avx2) {
  __m256 t0 = _mm256_set1_ps(t_min), t1 = _mm256_set1_ps(infinity<float>);
  for (int a = 0; a < 3; ++a) {
    const __m256 scale = _mm256_set1_ps(n.scale[a]), origin = _mm256_set1_ps(n.origin[a]);
    const __m256 inv = _mm256_set1_ps(r.inv_direction[a]);
    const __m256 near_side = quantized_bounds(n, r.near_row[a], scale, origin);
    const __m256 far_side = quantized_bounds(n, r.far_row[a], scale, origin);
    const __m256 tn = _mm256_mul_ps(_mm256_sub_ps(near_side, _mm256_set1_ps(r.near_origin[a])), inv);
    const __m256 tf = _mm256_mul_ps(_mm256_sub_ps(far_side, _mm256_set1_ps(r.far_origin[a])), inv);
    t0 = _mm256_max_ps(tn, t0);
    t1 = _mm256_min_ps(tf, t1);
  }
  _mm256_storeu_ps(t_enter, t0);
  const __m256 hit = _mm256_and_ps(_mm256_cmp_ps(t0, _mm256_mul_ps(t1, _mm256_set1_ps(wide_slab_widen)), _CMP_LE_OQ),
                                   _mm256_cmp_ps(t0, _mm256_set1_ps(t_max), _CMP_LE_OQ));
  return unsigned(_mm256_movemask_ps(hit)) & n.used;
}
#else
inline unsigned hit_boxes(const wide_qnode8& n, const box4_ray& r, float t_min, float t_max, float (&t_enter)[8],
                          simd_avx2) {
  return hit_boxes(n, r, t_min, t_max, t_enter, simd_sse{});
}
#endif

// Entries pushed per wide level: at most N - 1 left behind while the last is walked.
template <int N> constexpr int wide_stack_size = (N - 1) * bvh_max_depth + N;

// A box's entry t and a primitive's t round differently: a triangle on a box face (a shared edge
// of two leaves, say) may hit at a t an ulp or two below the box's entry. So a box is passed over
// only when it starts more than 32 ulps beyond the best hit, and a tie at equal t or a hit an ulp
// nearer is never lost to the order of the walk.
constexpr float wide_cull_margin = 1.0f + 0x1p-18f;

namespace detail {
// The children to visit: those hit, or for a ray that is not exact every child but the unused.
template <int N> unsigned used_slots(const wide_node<N>& n) {
  unsigned mask = 0;
  for (int k = 0; k < N; ++k) mask |= unsigned(n.box[0][k] <= n.box[3][k]) << k;
  return mask;
}
inline unsigned used_slots(const wide_qnode8& n) { return n.used; }
template <class Node, class Simd>
unsigned boxes_to_visit(const Node& n, const box4_ray& r, float t_min, float t_max, float (&t)[Node::width],
                        Simd simd) {
  if (r.exact) return hit_boxes(n, r, t_min, t_max, t, simd);
  for (float& x : t) x = t_min;
  return used_slots(n);
}
}  // namespace detail

namespace detail {
// Child k of n, pushed to be walked later: if it is an inner node, start fetching its cache
// lines now (incoherent rays on a million triangles: 0.48 -> 0.57 of Embree's speed; the
// leaves' triangles too: no gain).
template <class Node>
void prefetch_node([[maybe_unused]] const std::vector<Node>& nodes, [[maybe_unused]] const Node& n,
                   [[maybe_unused]] int k) {
#if ZRAKA_HAS_SSE
  if (n.count[k] == 0) {
    const char* p = reinterpret_cast<const char*>(&nodes[n.child[k]]);
    for (std::size_t line = 0; line < sizeof(Node); line += 64) _mm_prefetch(p + line, _MM_HINT_T0);
  }
#endif
}
}  // namespace detail

// [listing wide-traverse]
// The nearest-hit walk shared by every wide BVH. leaf(first, count, t_cull) tests the entries
// [first, first + count) of the primitive order and, on a hit, returns true and lowers t_cull
// (a float no smaller than the best hit's t). Take the nearest entry; skip it if a hit is already
// nearer than its box; test a leaf, or a node's N boxes (with the instructions of `simd`). A
// node with one box hit goes on to that child directly (the most common case, and no trip
// through the stack's memory); with two, the farther is pushed and the nearer walked at once;
// with three, the same after a sort by three exchanges without branches; with more, they are
// pushed farthest first (nearest on top). A ray that is not `exact` visits every box: slower,
// never wrong.
template <class Node, class Leaf, class Simd = simd_default>
bool wide_nearest(const std::vector<Node>& nodes, const box4_ray& r, float t_min, float t_cull, Leaf&& leaf,
                  bvh_stats* stats = nullptr, Simd simd = {}) {
  constexpr int N = Node::width;
  struct entry {
    std::uint32_t child, count;
    float t_enter;
  };
  if (nodes.empty() || !r.valid) return false;
  std::array<entry, wide_stack_size<N>> stack;
  int top = 0;
  entry e = {0, 0, t_min};
  bool found = false;
  for (;;) {
    if (e.t_enter <= t_cull * wide_cull_margin) {
      if (e.count) {
        if (leaf(e.child, e.count, t_cull)) found = true;
        if (stats) stats->primitives += e.count;
      } else {
        const Node& n = nodes[e.child];
        float t[N];
        unsigned mask = detail::boxes_to_visit(n, r, t_min, t_cull * wide_cull_margin, t, simd);
        if (stats) stats->nodes += N;
        if (mask != 0 && (mask & (mask - 1)) == 0) {  // one child hit: on to it
          const int k = std::countr_zero(mask);
          e = {n.child[k], n.count[k], t[k]};
          continue;
        }
        // Two: the farther onto the stack, on to the nearer. (Two bits: one left once the lowest
        // is cleared. std::popcount is a library call on plain x86-64.)
        if (const unsigned rest = mask & (mask - 1); rest != 0 && (rest & (rest - 1)) == 0) {
          const int k0 = std::countr_zero(mask), k1 = std::countr_zero(rest);
          const int swap = (k0 ^ k1) & -int(t[k1] < t[k0]);  // k0 ^ k1 or 0: a coin toss, so no branch
          const int k_near = k0 ^ swap, k_far = k1 ^ swap;
          stack[std::size_t(top++)] = {n.child[k_far], n.count[k_far], t[k_far]};
          detail::prefetch_node(nodes, n, k_far);
          e = {n.child[k_near], n.count[k_near], t[k_near]};
          continue;
        }
        // Three: sorted by three exchanges of that kind (an insertion sort's comparisons are
        // branches, coin tosses for incoherent rays), the two farther pushed, on to the nearest.
        // (Written out: the exchange as a function compiled to a slower walk, 2-3 %.)
        if (const unsigned rest = mask & (mask - 1), rest2 = rest & (rest - 1);
            rest2 != 0 && (rest2 & (rest2 - 1)) == 0) {
          int k0 = std::countr_zero(mask), k1 = std::countr_zero(rest), k2 = std::countr_zero(rest2);
          int swap = (k0 ^ k1) & -int(t[k1] < t[k0]);
          k0 ^= swap, k1 ^= swap;
          swap = (k1 ^ k2) & -int(t[k2] < t[k1]);
          k1 ^= swap, k2 ^= swap;
          swap = (k0 ^ k1) & -int(t[k1] < t[k0]);
          k0 ^= swap, k1 ^= swap;
          stack[std::size_t(top++)] = {n.child[k2], n.count[k2], t[k2]};
          stack[std::size_t(top++)] = {n.child[k1], n.count[k1], t[k1]};
          detail::prefetch_node(nodes, n, k2);
          detail::prefetch_node(nodes, n, k1);
          e = {n.child[k0], n.count[k0], t[k0]};
          continue;
        }
        const int first = top;
        for (; mask; mask &= mask - 1) {  // insert each hit child, keeping [first, top) by t
          const int k = std::countr_zero(mask);
          int j = top++;
          for (; j > first && stack[std::size_t(j - 1)].t_enter < t[k]; --j) stack[std::size_t(j)] = stack[std::size_t(j - 1)];
          stack[std::size_t(j)] = {n.child[k], n.count[k], t[k]};
          detail::prefetch_node(nodes, n, k);
        }
      }
    }
    if (top == 0) break;
    e = stack[std::size_t(--top)];
  }
  return found;
}
// [end]

// Any hit: leaf(first, count) returns true when an entry blocks the ray; the walk stops there.
template <class Node, class Leaf, class Simd = simd_default>
bool wide_any(const std::vector<Node>& nodes, const box4_ray& r, float t_min, float t_max, Leaf&& leaf,
              bvh_stats* stats = nullptr, Simd simd = {}) {
  constexpr int N = Node::width;
  struct entry {
    std::uint32_t child, count;
  };
  if (nodes.empty() || !r.valid) return false;
  std::array<entry, wide_stack_size<N>> stack;
  int top = 0;
  stack[top++] = {0, 0};
  while (top > 0) {
    const entry e = stack[--top];
    if (e.count) {
      if (stats) stats->primitives += e.count;
      if (leaf(e.child, e.count)) return true;
      continue;
    }
    const Node& n = nodes[e.child];
    float t[N];
    unsigned mask = detail::boxes_to_visit(n, r, t_min, t_max, t, simd);
    if (stats) stats->nodes += N;
    for (; mask; mask &= mask - 1) {
      const int k = std::countr_zero(mask);
      stack[std::size_t(top++)] = {n.child[k], n.count[k]};
    }
  }
  return false;
}

// A wide BVH over any primitives: the wide nodes and bvh.hpp's order of the primitives, the
// drop-in for bvh_intersect and bvh_occluded (the scene's object BVH uses it).
struct wide_bvh {
  std::vector<bvh_node4> nodes;
  std::vector<std::uint32_t> order;
  bool empty() const { return nodes.empty(); }
};

template <class T> wide_bvh make_wide_bvh(const bvh_t<T>& b) { return {collapse<4>(b), b.order}; }

// The nearest hit, with the contract of bvh_intersect (bvh.hpp): test(i, t_max) intersects
// primitive i on (t_min, t_max) and, on a hit, shrinks t_max and returns true.
template <class T, class Test>
bool wide_intersect(const wide_bvh& w, const ray_t<T>& r, T t_min, T t_max, Test&& test,
                    bvh_stats* stats = nullptr) {
  if (w.empty() || !r.valid() || !(t_min < t_max)) return false;
  const box4_ray br(r);
  return wide_nearest(
      w.nodes, br, float_down(t_min), float_up(t_max),
      [&](std::uint32_t first, std::uint32_t count, float& t_cull) {
        bool hit = false;
        for (std::uint32_t k = first; k < first + count; ++k)
          if (test(w.order[k], t_max)) hit = true;
        if (hit) t_cull = float_up(t_max);
        return hit;
      },
      stats);
}

// Any hit, with the contract of bvh_occluded: test(i) returns true when primitive i blocks.
template <class T, class Test>
bool wide_occluded(const wide_bvh& w, const ray_t<T>& r, T t_min, T t_max, Test&& test,
                   bvh_stats* stats = nullptr) {
  if (w.empty() || !r.valid() || !(t_min < t_max)) return false;
  const box4_ray br(r);
  return wide_any(
      w.nodes, br, float_down(t_min), float_up(t_max),
      [&](std::uint32_t first, std::uint32_t count) {
        for (std::uint32_t k = first; k < first + count; ++k)
          if (test(w.order[k])) return true;
        return false;
      },
      stats);
}

}  // namespace zraka

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
// The five ideas are five headers: wide_node.hpp (the node and the ray's box test),
// wide_collapse.hpp and wide_collapse_cost.hpp (binary to wide, by rule and by cost),
// wide_quantized.hpp (nodes in bytes) and this one (the walks, and the object BVH's wide_bvh).
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/simd.hpp>
#include <zraka/accel/wide_collapse.hpp>
#include <zraka/accel/wide_collapse_cost.hpp>
#include <zraka/accel/wide_node.hpp>
#include <zraka/accel/wide_quantized.hpp>
#include <zraka/core/ray.hpp>

#include <cstdint>
#include <vector>

#if ZRAKA_HAS_SSE
#include <immintrin.h>
#endif

namespace zraka {

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

#pragma once
// Collapsing bvh.hpp's binary tree into wide nodes (book 5.2) by the simple rule: a wide node's
// slots are filled by opening the child with the largest box until N are used. The
// dynamic-programming collapse by cost is wide_collapse_cost.hpp.
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/simd.hpp>
#include <zraka/accel/wide_node.hpp>
#include <zraka/core/error.hpp>
#include <zraka/geometry/aabb.hpp>

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

namespace zraka {

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

}  // namespace zraka

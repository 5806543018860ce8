#pragma once
// Collapsing bvh.hpp's binary tree into wide nodes chosen by cost (book 5.2, after Ylitie, Karras
// and Laine 2017): the wide SAH minimised over the binary tree by dynamic programming.
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/simd.hpp>
#include <zraka/accel/wide_collapse.hpp>
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

}  // namespace zraka

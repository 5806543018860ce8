#pragma once
// A bounding volume hierarchy (book 5.2): a binary tree of axis-aligned boxes over primitives,
// so that a ray tests a few boxes and a few primitives instead of every primitive.
//
// Generic over the primitive: the builder sees only each primitive's box (and a centroid to sort
// by), and traversal calls back `test(i, t_max)` for primitive i. So one BVH serves triangles
// (triangle_bvh.hpp specialises it) and the objects of a scene (scene.hpp's object_ref) alike.
//
// * Build: top down, splitting by the surface area heuristic (SAH) evaluated at the borders of
//   a few bins per axis; leaves hold at most max_leaf_size primitives.
// * Layout: one flat array in depth-first order. An inner node's first child is the next node,
//   its second child is at `index`; a leaf's primitives are order[index, index + count).
// * Traversal: front to back (the child on the side the ray comes from first, by the sign of the
//   ray's direction on the split axis) with a small fixed stack, no allocation; the any-hit
//   variant for shadow rays stops at the first primitive that blocks.
#include <zraka/accel/simd.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/geometry/aabb.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#if ZRAKA_HAS_SSE
#include <immintrin.h>
#endif

namespace zraka {

// The traversal stack holds one entry per level; the builder keeps the depth below it.
constexpr int bvh_max_depth = 64;

struct bvh_build_options {
  int bins = 16;               // SAH candidate planes per axis: the borders between bins
  int max_leaf_size = 4;       // a leaf never holds more
  double traversal_cost = 1.0; // C_trav: one box test relative to one primitive test (C_isect = 1)
  int leaf_block = 1;          // primitives tested this many at a time: a leaf of n costs
                               // ceil(n / leaf_block) tests (triangle_bvh.hpp's blocks of four)
  bool vector_binning = true;  // float with SSE: bin a box's six bounds in two instructions;
                               // the same tree (false runs the plain pass, for the tests)
  int wide_leaf_size = 16;     // triangle_bvh's wide tree (wide_bvh.hpp's collapse_by_cost): a
                               // leaf may join binary leaves up to this many primitives
  double wide_node_cost = 5;   // and a wide node costs this many leaf blocks
  int quantize = -1;           // triangle_bvh's eight-wide nodes in half the bytes (wide_bvh.hpp's
                               // wide_qnode8): 1 yes, 0 no, -1 where the tree is larger than
                               // eight L2 caches (there the walk waits for memory)
};

template <class T> struct bvh_node_t {
  aabb_t<T> box;
  std::uint32_t index = 0;  // inner: the second child's node; leaf: first entry in bvh_t::order
  std::uint16_t count = 0;  // primitives in a leaf; 0 marks an inner node
  std::uint8_t axis = 0;    // inner: the split axis, for front-to-back order
  std::uint8_t unused = 0;
  bool leaf() const { return count != 0; }
};
static_assert(sizeof(bvh_node_t<float>) == 32, "a float node fills half a cache line");

template <class T> struct bvh_t {
  std::vector<bvh_node_t<T>> nodes;  // depth-first; nodes[0] is the root
  std::vector<std::uint32_t> order;  // primitive indices, leaf by leaf
  std::size_t primitive_count = 0;   // as given to the builder (some may be left out: see build)
  int depth = 0;                     // levels, the root's counted as 1
  bool empty() const { return nodes.empty(); }
};

using bvh = bvh_t<double>;

// What a traversal did, summed over calls: for "nodes visited per ray" and the like.
struct bvh_stats {
  std::uint64_t nodes = 0;       // box tests
  std::uint64_t primitives = 0;  // primitive tests
};

namespace detail {

template <class T> class bvh_builder {
 public:
  bvh_builder(const std::vector<aabb_t<T>>& boxes, const std::vector<vec3_t<T>>& centroids,
              const bvh_build_options& opt, bvh_t<T>& out)
      : boxes_(boxes), centroids_(centroids), opt_(opt), out_(out), bins_(3 * std::size_t(opt.bins)),
        right_area_(opt.bins), right_count_(opt.bins) {}

  void run() {
    if (boxes_.size() >= std::size_t(UINT32_MAX)) throw error("bvh: too many primitives");
    out_.primitive_count = boxes_.size();
    // A primitive with an empty or non-finite box, or a non-finite centroid, can never be hit:
    // it is left out, so that NaNs cannot disturb the binning.
    for (std::size_t i = 0; i < boxes_.size(); ++i)
      if (!boxes_[i].empty() && is_finite(boxes_[i].lo) && is_finite(boxes_[i].hi) &&
          is_finite(centroids_[i]))
        out_.order.push_back(static_cast<std::uint32_t>(i));
    if (out_.order.empty()) return;
    out_.nodes.reserve(2 * out_.order.size() / std::max(1, opt_.max_leaf_size) + 1);
    build(0, static_cast<std::uint32_t>(out_.order.size()), 1);
  }

 private:
  struct split {
    int axis = -1;
    int bin = 0;  // primitives in bins < bin go left
    T cost = infinity<T>;
  };
  struct bin {
    aabb_t<T> box;
    std::uint32_t count = 0;
  };

  // The bin of centroid c on axis a; the same expression for binning and partitioning, so the
  // two always agree.
  static int bin_of(T c, T lo, T scale, int bins) {
    return std::clamp(static_cast<int>((c - lo) * scale), 0, bins - 1);
  }

  static int ceil_log2(std::uint32_t n) {
    int k = 0;
    while ((std::uint64_t(1) << k) < n) ++k;
    return k;
  }

  // Primitive tests for a leaf of n: n, or its blocks when primitives are tested several at once.
  T tests(std::uint32_t n) const {
    const auto b = std::uint32_t(opt_.leaf_block);
    // A shift where the block is a power of two: a division per candidate plane was a tenth of
    // the build.
    return T(block_shift_ >= 0 ? (n + b - 1) >> block_shift_ : (n + b - 1) / b);
  }

  // A box's lo and hi, each in one four-lane register (the fourth lane unused): in the vector
  // binning a bin grows by one min and one max instead of six, and the chain of updates of one
  // bin through memory is shorter. The bins' boxes are the same numbers (up to the sign of a
  // zero, which no area sees), so the tree is the same.
#if ZRAKA_HAS_SSE
  static constexpr bool four_wide_bins = std::is_same_v<T, float>;
  struct box_lanes {
    __m128 lo = _mm_set1_ps(infinity<float>), hi = _mm_set1_ps(-infinity<float>);
    void grow(const box_lanes& b) {
      lo = _mm_min_ps(lo, b.lo);
      hi = _mm_max_ps(hi, b.hi);
    }
    // aabb_t::surface_area of a box that is not empty, with the same roundings.
    float surface_area() const {
      const __m128 e = _mm_sub_ps(hi, lo);
      const float x = _mm_cvtss_f32(e), y = _mm_cvtss_f32(_mm_shuffle_ps(e, e, 1)),
                  z = _mm_cvtss_f32(_mm_movehl_ps(e, e));
      return 2.0f * (x * y + y * z + z * x);
    }
  };
  static box_lanes lanes_of(const aabb_t<T>& box) {
    static_assert(sizeof(aabb_t<float>) == 24 && offsetof(aabb_t<float>, hi) == 12);
    const float* p = reinterpret_cast<const float*>(&box);  // lo.x lo.y lo.z hi.x hi.y hi.z
    const __m128 hi = _mm_loadu_ps(p + 2);                   // (lo.z) hi.x hi.y hi.z
    return {_mm_loadu_ps(p), _mm_shuffle_ps(hi, hi, _MM_SHUFFLE(3, 3, 2, 1))};
  }
  static box_lanes point_lanes(const vec3_t<T>& p) {
    const __m128 v = _mm_setr_ps(float(p.x), float(p.y), float(p.z), 0.0f);
    return {v, v};
  }
  static aabb_t<T> box_of(const box_lanes& b) {
    alignas(16) float lo[4], hi[4];
    _mm_store_ps(lo, b.lo);
    _mm_store_ps(hi, b.hi);
    return {vec3_t<T>(lo[0], lo[1], lo[2]), vec3_t<T>(hi[0], hi[1], hi[2])};
  }
  // bin_of on the three axes at once; clamping before the conversion to int gives the same
  // numbers, so the binning and the partition still agree.
  struct centroid_bins {
    __m128 lo, scale, top;
    centroid_bins(const aabb_t<T>& cbox, const vec3_t<T>& s, int bins)
        : lo(_mm_setr_ps(float(cbox.lo.x), float(cbox.lo.y), float(cbox.lo.z), 0.0f)),
          scale(_mm_setr_ps(float(s.x), float(s.y), float(s.z), 0.0f)), top(_mm_set1_ps(float(bins - 1))) {}
    void operator()(const vec3_t<T>& c, int (&j)[4]) const {
      const __m128 x = _mm_mul_ps(_mm_sub_ps(_mm_setr_ps(float(c.x), float(c.y), float(c.z), 0.0f), lo), scale);
      _mm_store_si128(reinterpret_cast<__m128i*>(j), _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(x, _mm_setzero_ps()), top)));
    }
  };
#else
  static constexpr bool four_wide_bins = false;
  struct box_lanes {  // without SSE: never used (four_wide_bins is false), kept so the code compiles
    aabb_t<T> box;
    void grow(const box_lanes& b) {
      box.lo = glm::min(box.lo, b.box.lo);
      box.hi = glm::max(box.hi, b.box.hi);
    }
    T surface_area() const { return box.surface_area(); }
  };
  static box_lanes lanes_of(const aabb_t<T>& box) { return {box}; }
  static box_lanes point_lanes(const vec3_t<T>& p) { return {aabb_t<T>{p, p}}; }
  static aabb_t<T> box_of(const box_lanes& b) { return b.box; }
  struct centroid_bins {
    centroid_bins(const aabb_t<T>&, const vec3_t<T>&, int) {}
    void operator()(const vec3_t<T>&, int (&)[4]) const {}
  };
#endif

  // [listing sah]
  // One pass bins every primitive of [first, last) on all three axes: each box is read once,
  // not three times (a third faster build of a million triangles); then each axis notes the
  // lowest and highest bin it filled. Vector: the float pass in four lanes (box_lanes and
  // centroid_bins, above).
  template <bool Vector>
  void bin_primitives(std::uint32_t first, std::uint32_t last, const aabb_t<T>& cbox, const vec3_t<T>& scale,
                      int (&lo_bin)[3], int (&hi_bin)[3]) {
    const int nb = opt_.bins;
    if constexpr (Vector) std::fill(bins4_.begin(), bins4_.end(), box_lanes{});
    const centroid_bins bins_of(cbox, scale, nb);
    for (std::uint32_t k = first; k < last; ++k) {
      const std::uint32_t i = out_.order[k];
      const aabb_t<T>& box = boxes_[i];  // never empty: run() left those out
      [[maybe_unused]] box_lanes lanes;
      [[maybe_unused]] alignas(16) int j4[4];
      if constexpr (Vector) {
        lanes = lanes_of(box);
        bins_of(centroids_[i], j4);
      }
      for (int a = 0; a < 3; ++a) {
        if (scale[a] == T(0)) continue;
        int j;
        if constexpr (Vector) j = j4[a];
        else j = bin_of(centroids_[i][a], cbox.lo[a], scale[a], nb);
        bin& b = bins_[std::size_t(a * nb + j)];
        if constexpr (Vector) {
          bins4_[std::size_t(a * nb + j)].grow(lanes);
        } else {
          b.box.lo = glm::min(b.box.lo, box.lo);
          b.box.hi = glm::max(b.box.hi, box.hi);
        }
        ++b.count;
      }
    }
    for (int a = 0; a < 3; ++a)  // the bins filled: after the pass, not per primitive
      for (int j = 0; j < nb; ++j)
        if (bins_[std::size_t(a * nb + j)].count != 0) {
          lo_bin[a] = std::min(lo_bin[a], j);
          hi_bin[a] = j;
        }
  }

  // The SAH cost of splitting [first, last) at a bin border, in units of one primitive test:
  // C_trav + (A_L N_L + A_R N_R) / A, with A the parent's area. A ray that hits the parent hits
  // a child with probability A_child / A (for uniformly distributed rays), so this is the
  // expected cost of the split if the children become leaves. Compared times A (no division:
  // a flat parent has A = 0). (N counts tests: blocks of leaf_block primitives, if more than 1.)
  split best_sah_split(std::uint32_t first, std::uint32_t last, const aabb_t<T>& cbox) {
    split best;
    const int nb = opt_.bins;
    std::vector<bin>& bins = bins_;  // nb bins per axis, axis by axis
    std::vector<T>& right_area = right_area_;
    std::vector<std::uint32_t>& right_count = right_count_;
    vec3_t<T> scale(T(0));
    bool any = false;
    for (int a = 0; a < 3; ++a) {
      const T extent = cbox.hi[a] - cbox.lo[a];
      if (!(extent > T(0)) || !std::isfinite(extent)) continue;  // all centroids in one plane
      scale[a] = T(nb) / extent;
      any = true;
    }
    if (!any) return best;
    std::fill(bins.begin(), bins.end(), bin{});
    // The bins used on each axis lie in [lo_bin, hi_bin]; borders outside it leave one side
    // empty, so the sweeps below skip them (a small node fills few of its bins).
    int lo_bin[3] = {nb, nb, nb}, hi_bin[3] = {-1, -1, -1};
    const bool vector = four_wide_bins && opt_.vector_binning;
    if (vector) bin_primitives<four_wide_bins>(first, last, cbox, scale, lo_bin, hi_bin);
    else bin_primitives<false>(first, last, cbox, scale, lo_bin, hi_bin);
    // The sweeps, on the bins' boxes as the pass left them (four lanes, or aabb_t).
    auto sweep = [&](int a, auto box_at) {
      const bin* axis_bins = &bins[std::size_t(a * nb)];
      decltype(box_at(0)) acc;  // sweep from the right: area and count of bins [j, nb)
      std::uint32_t n = 0;
      for (int j = hi_bin[a]; j > lo_bin[a]; --j) {
        acc.grow(box_at(j));
        n += axis_bins[j].count;
        right_area[j] = acc.surface_area();
        right_count[j] = n;
      }
      acc = {};
      n = 0;
      for (int j = lo_bin[a] + 1; j <= hi_bin[a]; ++j) {  // the border between bins j-1 and j
        acc.grow(box_at(j - 1));
        n += axis_bins[j - 1].count;
        const T cost = acc.surface_area() * tests(n) + right_area[j] * tests(right_count[j]);
        if (cost < best.cost) best = {a, j, cost};
      }
    };
    for (int a = 0; a < 3; ++a) {
      if (scale[a] == T(0)) continue;
      if (vector) sweep(a, [&](int j) { return bins4_[std::size_t(a * nb + j)]; });
      else sweep(a, [&](int j) { return bins[std::size_t(a * nb + j)].box; });
    }
    return best;
  }
  // [end]

  std::uint32_t build(std::uint32_t first, std::uint32_t last, int depth) {
    const auto me = static_cast<std::uint32_t>(out_.nodes.size());
    out_.nodes.emplace_back();
    out_.depth = std::max(out_.depth, depth);
    aabb_t<T> box, cbox;
    if (four_wide_bins && opt_.vector_binning) {  // in four lanes, as the binning (the same numbers)
      box_lanes b, c;
      for (std::uint32_t k = first; k < last; ++k) {
        const std::uint32_t i = out_.order[k];
        b.grow(lanes_of(boxes_[i]));
        c.grow(point_lanes(centroids_[i]));
      }
      box = box_of(b);
      cbox = box_of(c);
    } else {
      for (std::uint32_t k = first; k < last; ++k) {  // boxes never empty (run()): plain min, max
        const std::uint32_t i = out_.order[k];
        box.lo = glm::min(box.lo, boxes_[i].lo);
        box.hi = glm::max(box.hi, boxes_[i].hi);
        cbox.grow(centroids_[i]);
      }
    }
    out_.nodes[me].box = box;
    const std::uint32_t n = last - first;

    std::uint32_t mid = first;
    int axis = 0;
    // Near the depth limit only halving splits are used: then depth + ceil(log2 n) never grows,
    // so the tree stays within the traversal stack whatever SAH would have liked.
    const bool must_halve = depth + ceil_log2(n) >= bvh_max_depth - 1;
    const split s = (n > 1 && !must_halve) ? best_sah_split(first, last, cbox) : split{};
    const T area = box.surface_area();
    const T split_cost = T(opt_.traversal_cost) * area + s.cost;  // both times A
    if (n == 1 || (n <= std::uint32_t(opt_.max_leaf_size) && !must_halve && tests(n) * area <= split_cost)) {
      out_.nodes[me].index = first;
      out_.nodes[me].count = static_cast<std::uint16_t>(n);
      return me;
    }
    if (s.axis >= 0) {
      const T scale = T(opt_.bins) / (cbox.hi[s.axis] - cbox.lo[s.axis]);
      const auto it = std::partition(
          out_.order.begin() + first, out_.order.begin() + last, [&](std::uint32_t i) {
            return bin_of(centroids_[i][s.axis], cbox.lo[s.axis], scale, opt_.bins) < s.bin;
          });
      mid = static_cast<std::uint32_t>(it - out_.order.begin());
      axis = s.axis;
    } else {
      // No SAH split: all centroids coincide, or the depth limit. Halve by count along the
      // widest centroid extent (any order if they coincide): the recursion always ends.
      const vec3_t<T> e = cbox.extent();
      axis = e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
      mid = first + n / 2;
      std::nth_element(out_.order.begin() + first, out_.order.begin() + mid,
                       out_.order.begin() + last, [&](std::uint32_t i, std::uint32_t j) {
                         return centroids_[i][axis] < centroids_[j][axis];
                       });
    }
    build(first, mid, depth + 1);  // the first child lands right after its parent
    const std::uint32_t second = build(mid, last, depth + 1);
    out_.nodes[me].index = second;
    out_.nodes[me].axis = static_cast<std::uint8_t>(axis);
    return me;
  }

  const std::vector<aabb_t<T>>& boxes_;
  const std::vector<vec3_t<T>>& centroids_;
  const bvh_build_options& opt_;
  bvh_t<T>& out_;
  std::vector<bin> bins_;  // scratch for best_sah_split, allocated once
  std::vector<box_lanes> bins4_ = std::vector<box_lanes>(four_wide_bins ? bins_.size() : 0);  // bin_primitives<true>'s
  std::vector<T> right_area_;
  int block_shift_ = std::has_single_bit(unsigned(opt_.leaf_block)) ? std::countr_zero(unsigned(opt_.leaf_block)) : -1;
  std::vector<std::uint32_t> right_count_;
};

}  // namespace detail

// Builds a BVH over primitives 0..n-1 with the given boxes and centroids (the points that the
// SAH bins sort by; usually the boxes' centres).
template <class T>
bvh_t<T> build_bvh(const std::vector<aabb_t<T>>& boxes, const std::vector<vec3_t<T>>& centroids,
                   const bvh_build_options& opt = {}) {
  if (boxes.size() != centroids.size())
    throw error("bvh: " + std::to_string(boxes.size()) + " boxes but " +
                std::to_string(centroids.size()) + " centroids");
  if (opt.bins < 2 || opt.bins > 256)
    throw error("bvh: bins must be in 2..256, got " + std::to_string(opt.bins));
  if (opt.max_leaf_size < 1 || opt.max_leaf_size > 255)
    throw error("bvh: max_leaf_size must be in 1..255, got " + std::to_string(opt.max_leaf_size));
  if (opt.leaf_block < 1 || opt.leaf_block > 255)
    throw error("bvh: leaf_block must be in 1..255, got " + std::to_string(opt.leaf_block));
  if (!(opt.traversal_cost >= 0) || !std::isfinite(opt.traversal_cost))
    throw error("bvh: traversal_cost must be finite and >= 0");
  if (opt.wide_leaf_size < 1 || opt.wide_leaf_size > 255)
    throw error("bvh: wide_leaf_size must be in 1..255, got " + std::to_string(opt.wide_leaf_size));
  if (!(opt.wide_node_cost >= 0) || !std::isfinite(opt.wide_node_cost))
    throw error("bvh: wide_node_cost must be finite and >= 0");
  bvh_t<T> out;
  detail::bvh_builder<T>(boxes, centroids, opt, out).run();
  return out;
}

template <class T>
bvh_t<T> build_bvh(const std::vector<aabb_t<T>>& boxes, const bvh_build_options& opt = {}) {
  std::vector<vec3_t<T>> centroids;
  centroids.reserve(boxes.size());
  for (const auto& b : boxes) centroids.push_back(b.center());
  return build_bvh(boxes, centroids, opt);
}

// [listing traverse]
// The nearest hit along r in (t_min, t_max). test(i, t_max) intersects primitive i on
// (t_min, t_max); on a hit it records what the caller wants, shrinks t_max to the hit's t and
// returns true. Boxes beyond the nearest hit so far are skipped, and nearer boxes come first,
// so t_max shrinks early.
template <class T, class Test>
bool bvh_intersect(const bvh_t<T>& bvh, const ray_t<T>& r, T t_min, T t_max, Test&& test,
                   bvh_stats* stats = nullptr) {
  if (bvh.empty() || !r.valid()) return false;
  const box_ray_t<T> br(r);
  std::array<std::uint32_t, bvh_max_depth> stack;
  int top = 0;
  std::uint32_t i = 0;  // the root
  bool found = false;
  for (;;) {
    const bvh_node_t<T>& node = bvh.nodes[i];
    if (stats) ++stats->nodes;
    if (intersect(node.box, br, t_min, t_max)) {
      if (node.leaf()) {
        for (std::uint32_t k = node.index; k < node.index + node.count; ++k) {
          if (stats) ++stats->primitives;
          if (test(bvh.order[k], t_max)) found = true;
        }
      } else if (r.direction[node.axis] < T(0)) {  // the second child is nearer
        stack[top++] = i + 1;
        i = node.index;
        continue;
      } else {
        stack[top++] = node.index;
        i = i + 1;
        continue;
      }
    }
    if (top == 0) break;
    i = stack[--top];
  }
  return found;
}
// [end]

// Any hit in (t_min, t_max), for shadow rays: test(i) returns true when primitive i blocks the
// segment, and the traversal stops right there (no ordering needed, no t to shrink).
template <class T, class Test>
bool bvh_occluded(const bvh_t<T>& bvh, const ray_t<T>& r, T t_min, T t_max, Test&& test,
                  bvh_stats* stats = nullptr) {
  if (bvh.empty() || !r.valid()) return false;
  const box_ray_t<T> br(r);
  std::array<std::uint32_t, bvh_max_depth> stack;
  int top = 0;
  std::uint32_t i = 0;
  for (;;) {
    const bvh_node_t<T>& node = bvh.nodes[i];
    if (stats) ++stats->nodes;
    if (intersect(node.box, br, t_min, t_max)) {
      if (node.leaf()) {
        for (std::uint32_t k = node.index; k < node.index + node.count; ++k) {
          if (stats) ++stats->primitives;
          if (test(bvh.order[k])) return true;
        }
      } else {
        stack[top++] = node.index;
        i = i + 1;
        continue;
      }
    }
    if (top == 0) break;
    i = stack[--top];
  }
  return false;
}

// Compiled once at double and float (compiled.hpp).
ZRAKA_INSTANCE(bvh_t<double> build_bvh(const std::vector<aabb_t<double>>&,
                                       const std::vector<vec3_t<double>>&, const bvh_build_options&))
ZRAKA_INSTANCE(bvh_t<double> build_bvh(const std::vector<aabb_t<double>>&, const bvh_build_options&))
ZRAKA_INSTANCE(bvh_t<float> build_bvh(const std::vector<aabb_t<float>>&,
                                      const std::vector<vec3_t<float>>&, const bvh_build_options&))
ZRAKA_INSTANCE(bvh_t<float> build_bvh(const std::vector<aabb_t<float>>&, const bvh_build_options&))

}  // namespace zraka

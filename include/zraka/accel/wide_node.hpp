#pragma once
// A wide node of the BVH (book 5.2) and the ray's test against its boxes: N children's boxes in
// float, stored axis by axis so that one SIMD instruction tests four (SSE) or eight (AVX2) of
// them; a ray prepared once per walk (box4_ray); the slab test written plainly, with SSE and with
// AVX2 (simd.hpp chooses when the program runs). The boxes are rounded outward from the tree's
// precision and the ray's origin towards the side that lengthens each slab, so the float test
// keeps every box the exact test keeps. wide_bvh.hpp walks these nodes.
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/simd.hpp>
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

}  // namespace zraka

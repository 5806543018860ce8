#pragma once
// Quantized eight-wide nodes (book 5.2): each child's box as bytes against the node's origin, for
// trees too large for the cache; half the bytes of wide_node<8>, walked by the same walks.
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

#if defined(__unix__) || defined(__APPLE__)
#include <unistd.h>  // sysconf
#endif

#if ZRAKA_HAS_SSE
#include <immintrin.h>
#endif

namespace zraka {

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

}  // namespace zraka

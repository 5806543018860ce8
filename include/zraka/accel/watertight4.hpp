#pragma once
// The watertight ray-triangle test (triangle.hpp) on four triangles at once (book 5.2): the
// per-triangle half, detail::watertight_test, as the same SSE operations on four lanes, for the
// leaves of triangle_bvh.hpp. Each lane computes what the scalar test computes, in the same order
// with the same roundings, so t, u and v are the same bits; what the lanes cannot do alike is
// left to the scalar test:
// * an edge function that rounds to exactly 0 (a ray through an edge or a vertex, or in the
//   plane of an edge): the scalar test recomputes it in double. Such a lane is reported in
//   `scalar`, unless its other edge functions already put the ray outside;
// * a target where the compiler may fuse a product and a sum (FMA; triangle.hpp's may_fuse):
//   then the scalar test's own roundings depend on the compiler's choices, and no four-lane copy
//   can promise its bits. There, and without SSE, watertight4_available is false and the BVH's
//   leaf runs the scalar test lane by lane.
#include <zraka/accel/simd.hpp>
#include <zraka/geometry/triangle.hpp>

#include <cstdint>

#if ZRAKA_HAS_SSE
#include <immintrin.h>
#endif

namespace zraka {

// [listing triangle4]
// Four triangles as the four-lane test reads them: row 3v + a holds coordinate a of vertex v
// (A, B, C) of the four triangles, so that one load gives one coordinate of four vertices. A lane
// without a triangle has NaN coordinates, which no ray hits, and id UINT32_MAX.
struct alignas(16) triangle4 {
  float v[9][4];
  std::uint32_t id[4];
};
// [end]
static_assert(sizeof(triangle4) == 160);

namespace detail {

#if ZRAKA_HAS_SSE
inline constexpr bool watertight4_available = !may_fuse;
#else
inline constexpr bool watertight4_available = false;
#endif

#if ZRAKA_HAS_SSE
// watertight_ray's numbers, each in four lanes.
struct watertight_ray4 {
  __m128 ox, oy, oz, sx, sy, sz;
  int kx, ky, kz;
  explicit watertight_ray4(const watertight_ray<float>& r)
      : ox(_mm_set1_ps(r.ox)), oy(_mm_set1_ps(r.oy)), oz(_mm_set1_ps(r.oz)), sx(_mm_set1_ps(r.sx)),
        sy(_mm_set1_ps(r.sy)), sz(_mm_set1_ps(r.sz)), kx(r.kx), ky(r.ky), kz(r.kz) {}
};

// [listing watertight4]
// watertight_test on the four lanes of q, each operation the scalar one's twin. Returns the lanes
// that the scalar test would accept with t in (t_min, t_bound], their t, u, v stored in t4, u4,
// v4; `scalar` gets the lanes the scalar test must decide (an edge function rounded to 0).
ZRAKA_FORCE_INLINE unsigned watertight_test4(const watertight_ray4& r, const triangle4& q, float t_min,
                                             float t_bound, float (&t4)[4], float (&u4)[4], float (&v4)[4],
                                             unsigned& scalar) {
  struct ray_space {
    __m128 x, y, z;
  };
  auto to_ray_space = [&](int vertex) {  // q = p - O, permuted, sheared
    const float(*p)[4] = &q.v[3 * vertex];
    const __m128 qx = _mm_sub_ps(_mm_load_ps(p[r.kx]), r.ox);
    const __m128 qy = _mm_sub_ps(_mm_load_ps(p[r.ky]), r.oy);
    const __m128 qz = _mm_sub_ps(_mm_load_ps(p[r.kz]), r.oz);
    return ray_space{_mm_sub_ps(qx, _mm_mul_ps(r.sx, qz)), _mm_sub_ps(qy, _mm_mul_ps(r.sy, qz)), qz};
  };
  const ray_space a = to_ray_space(0), b = to_ray_space(1), c = to_ray_space(2);
  auto edge = [](__m128 w, __m128 x, __m128 y, __m128 z) {  // w x - y z, rounded as in the scalar
    return _mm_sub_ps(_mm_mul_ps(w, x), _mm_mul_ps(y, z));
  };
  const __m128 zero = _mm_setzero_ps();
  const __m128 e_a = edge(c.x, b.y, c.y, b.x);
  const __m128 e_b = edge(a.x, c.y, a.y, c.x);
  const __m128 e_c = edge(b.x, a.y, b.y, a.x);
  // Weights of both signs: outside, whatever a 0 among them would become in double. (The
  // scalar test's early out after two edge functions, here for four lanes at once: slower.)
  const __m128 negative =
      _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(e_a, zero), _mm_cmplt_ps(e_b, zero)), _mm_cmplt_ps(e_c, zero));
  const __m128 positive =
      _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(e_a, zero), _mm_cmpgt_ps(e_b, zero)), _mm_cmpgt_ps(e_c, zero));
  const __m128 outside = _mm_and_ps(negative, positive);
  const __m128 has_zero =
      _mm_or_ps(_mm_or_ps(_mm_cmpeq_ps(e_a, zero), _mm_cmpeq_ps(e_b, zero)), _mm_cmpeq_ps(e_c, zero));
  scalar = unsigned(_mm_movemask_ps(_mm_andnot_ps(outside, has_zero)));
  const __m128 det = _mm_add_ps(_mm_add_ps(e_a, e_b), e_c);
  const __m128 abs_det = _mm_andnot_ps(_mm_set1_ps(-0.0f), det);
  __m128 ok = _mm_andnot_ps(_mm_or_ps(outside, has_zero), _mm_cmpgt_ps(abs_det, zero));  // NaN: no
  if (_mm_movemask_ps(ok) == 0) return 0;
  const __m128 inv_det = _mm_div_ps(_mm_set1_ps(1.0f), det);
  const __m128 t = _mm_mul_ps(_mm_add_ps(_mm_add_ps(_mm_mul_ps(e_a, _mm_mul_ps(r.sz, a.z)),
                                                    _mm_mul_ps(e_b, _mm_mul_ps(r.sz, b.z))),
                                         _mm_mul_ps(e_c, _mm_mul_ps(r.sz, c.z))),
                              inv_det);
  ok = _mm_and_ps(ok, _mm_and_ps(_mm_cmpgt_ps(t, _mm_set1_ps(t_min)), _mm_cmple_ps(t, _mm_set1_ps(t_bound))));
  const unsigned lanes = unsigned(_mm_movemask_ps(ok));
  if (lanes) {
    _mm_storeu_ps(t4, t);
    _mm_storeu_ps(u4, _mm_mul_ps(e_b, inv_det));
    _mm_storeu_ps(v4, _mm_mul_ps(e_c, inv_det));
  }
  return lanes;
}
// [end]
#endif

}  // namespace detail
}  // namespace zraka

#pragma once
// Which SIMD instructions the wide BVH's walk uses (book 5.2), chosen when the program runs, so
// that one binary runs on any x86-64 and still uses AVX2 where the processor has it:
// * scalar: plain loops, on any machine (and the readable form the others must equal);
// * sse: four lanes; SSE2 is part of x86-64, so every such processor has it;
// * avx2: eight lanes. The code is compiled for AVX2 (ZRAKA_TARGET_AVX2) only in functions that
//   are called after cpu_simd() said the processor has it, never for the whole program.
// The levels are tags (simd_scalar, simd_sse, simd_avx2) that select a function at compile time;
// cpu_simd() picks one at run time, once per query, not once per box.
// ZRAKA_NO_SIMD (a build flag) leaves only the scalar level. ZRAKA_HAS_SSE is the one test of
// whether this build has SSE, for every four-lane piece (bvh.hpp's binning, watertight4.hpp,
// wide_bvh.hpp).
#include <string>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && !defined(ZRAKA_NO_SIMD)
#define ZRAKA_HAS_AVX2_TARGET 1
// AVX2 without FMA: a fused product and sum would round differently from the scalar test, whose
// bits the triangle lanes repeat (watertight4.hpp).
#define ZRAKA_TARGET_AVX2 [[gnu::target("avx2")]]
#else
#define ZRAKA_HAS_AVX2_TARGET 0
#define ZRAKA_TARGET_AVX2
#endif

#if defined(__SSE2__) && !defined(ZRAKA_NO_SIMD)
#define ZRAKA_HAS_SSE 1
#else
#define ZRAKA_HAS_SSE 0
#endif

namespace zraka {

enum class simd_level { scalar, sse, avx2 };

struct simd_scalar {};
struct simd_sse {};
struct simd_avx2 {};
// The level every build has: what the code used where nothing chose.
#if ZRAKA_HAS_SSE
using simd_default = simd_sse;
#else
using simd_default = simd_scalar;
#endif

inline const char* to_string(simd_level s) {
  return s == simd_level::avx2 ? "avx2" : s == simd_level::sse ? "sse" : "scalar";
}

// The best level this processor runs and this build allows (asked of the processor once).
inline simd_level cpu_simd() {
  static const simd_level level = [] {
#if ZRAKA_HAS_AVX2_TARGET && ZRAKA_HAS_SSE
    if (__builtin_cpu_supports("avx2")) return simd_level::avx2;
#endif
    return ZRAKA_HAS_SSE ? simd_level::sse : simd_level::scalar;
  }();
  return level;
}

// A level asked for, lowered to what this processor and build run.
inline simd_level usable_simd(simd_level wanted) { return wanted < cpu_simd() ? wanted : cpu_simd(); }

}  // namespace zraka

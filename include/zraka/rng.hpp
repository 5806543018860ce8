#pragma once
// Random numbers that any program can regenerate: a counter-based generator. The n-th number of
// a stream is a hash of (key, n), and the key is a hash of (seed, pixel, sample index), so one
// pixel's sample can be recomputed without running the others, results do not depend on the
// number of threads, and the same arithmetic runs unchanged in OpenCL C (kernels/rng.cl).
//
// The hash is PCG's output permutation used as a hash ("pcg_hash"; Jarzynski & Olano, "Hash
// Functions for GPU Rendering", JCGT 2020), chained once per input word.
#include <zraka/vec.hpp>

#include <cstdint>

namespace zraka {

// [listing pcg-hash]
constexpr std::uint32_t pcg_hash(std::uint32_t v) {
  const std::uint32_t state = v * 747796405u + 2891336453u;
  const std::uint32_t word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
// [end]

// Hash of several 32-bit words: each word is mixed into the running hash.
constexpr std::uint32_t hash_combine(std::uint32_t h, std::uint32_t word) {
  return pcg_hash(h ^ (word + 0x9e3779b9u + (h << 6) + (h >> 2)));
}

class rng {
 public:
  // A stream for (seed, pixel, sample); `dimension` counts the numbers drawn from it so far.
  explicit constexpr rng(std::uint64_t seed, std::uint32_t pixel = 0, std::uint32_t sample = 0)
      : key_(hash_combine(hash_combine(hash_combine(pcg_hash(std::uint32_t(seed)),
                                                    std::uint32_t(seed >> 32)),
                                       pixel),
                          sample)) {}

  constexpr std::uint32_t next_u32() { return hash_combine(key_, dimension_++); }

  // Uniform in [0,1): 24 random bits for float, 53 for double (never exactly 1).
  float uniform_float() { return float(next_u32() >> 8) * 0x1p-24f; }
  double uniform() {
    const std::uint64_t hi = next_u32() >> 5, lo = next_u32() >> 6;  // 27 + 26 bits
    return double((hi << 26) | lo) * 0x1p-53;
  }
  vec2 uniform2() {
    const double a = uniform();
    return {a, uniform()};
  }

  std::uint32_t dimension() const { return dimension_; }
  void skip_to(std::uint32_t dimension) { dimension_ = dimension; }

 private:
  std::uint32_t key_;
  std::uint32_t dimension_ = 0;
};

}  // namespace zraka

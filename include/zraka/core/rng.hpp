#pragma once
// Random numbers that any program can regenerate: a counter-based generator. The n-th number of
// a stream is a hash of (key, n), and the key is a hash of (seed, pixel, sample index), so one
// pixel's sample can be recomputed without running the others, results do not depend on the
// number of threads, and the same arithmetic runs unchanged in OpenCL C (kernels/rng.cl).
//
// The hash is PCG's output permutation used as a hash ("pcg_hash"; Jarzynski & Olano, "Hash
// Functions for GPU Rendering", JCGT 2020), chained once per input word.
//
// The key is two words, one from the pixel and one from the sample index, each a bijection of
// its input for a fixed seed: two different (pixel, sample) pairs never share a key. (A single
// 32-bit key allows only 2^32 distinct streams, so by the birthday bound 2^20 (pixel, sample)
// pairs, one small image at 4 spp, would already share about 128 identical streams.)
#include <zraka/core/vec.hpp>

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

// The 64-bit seed folded into one word.
constexpr std::uint32_t seed_word(std::uint64_t seed) {
  return hash_combine(pcg_hash(std::uint32_t(seed)), std::uint32_t(seed >> 32));
}

// Where the numbers of a stream may come from instead of the hash: chapter 6.4's primary
// sample space (pss.hpp), whose Markov chain keeps and mutates every number a path drew, so
// the unchanged path tracer follows the chain; or a low-discrepancy sampler's point
// (samplers.hpp, book 5.1). Number `dimension` of the stream is asked for.
class number_source {
 public:
  virtual std::uint32_t number(std::uint32_t dimension) = 0;

 protected:
  ~number_source() = default;
};

class rng {
 public:
  // A stream for (seed, pixel, sample); `dimension` counts the numbers drawn from it so far.
  // pixel + s and sample + t are bijections, and so is pcg_hash, hence the two key words.
  explicit constexpr rng(std::uint64_t seed, std::uint32_t pixel = 0, std::uint32_t sample = 0)
      : key_pixel_(pcg_hash(pixel + seed_word(seed))),
        key_sample_(pcg_hash(sample + pcg_hash(seed_word(seed) ^ 0x5bd1e995u))) {}

  // [listing rng-next]
  // Number `dimension` of the stream: a hash of (key, dimension), no state but the counter.
  constexpr std::uint32_t next_u32() {
    if (dimension_ < sourced_) return source_->number(dimension_++);  // a well-predicted branch elsewhere
    return pcg_hash(key_pixel_ ^ hash_combine(key_sample_, dimension_++));
  }
  // [end]

  // [listing rng-uniform]
  // Uniform in [0,1): 24 random bits for float, 53 for double, the most each type holds
  // exactly below 1. Using all 32 bits would round values near 1 up to exactly 1.
  static constexpr float unit_float(std::uint32_t u) { return float(u >> 8) * 0x1p-24f; }
  static constexpr double unit_double(std::uint32_t u, std::uint32_t v) {
    const std::uint64_t hi = u >> 5, lo = v >> 6;  // 27 + 26 bits
    return double((hi << 26) | lo) * 0x1p-53;
  }
  float uniform_float() { return unit_float(next_u32()); }
  double uniform() {
    const std::uint32_t u = next_u32();  // two statements: the order of the draws is fixed
    return unit_double(u, next_u32());
  }
  // [end]
  vec2 uniform2() {
    const double a = uniform();
    return {a, uniform()};
  }

  std::uint32_t dimension() const { return dimension_; }
  void skip_to(std::uint32_t dimension) { dimension_ = dimension; }
  // A stream whose numbers come from `source` (not owned), from dimension 0.
  static rng from(number_source& source) {
    rng g(0);
    g.source_ = &source;
    g.sourced_ = ~0u;
    return g;
  }
  // Numbers 0 .. count - 1 of this stream come from a sampler's point `source` (not owned), the
  // rest from the stream's own hash, so a path longer than the sampler's dimensions stays right.
  void follow(number_source& source, std::uint32_t count) {
    source_ = &source;
    sourced_ = count;
    aligned_ = true;
  }
  // A stream that follows a sampler jumps forward to number `dimension`, where the path's next
  // draw lives (path.hpp's fixed blocks); never back, so no number is used twice. Other streams
  // are not moved: their numbers need no alignment, and 6.4's chain keeps its own order.
  void seek(std::uint32_t dimension) {
    if (aligned_ && dimension_ < dimension) dimension_ = dimension;
  }

 private:
  std::uint32_t key_pixel_, key_sample_;
  std::uint32_t dimension_ = 0;
  std::uint32_t sourced_ = 0;  // numbers below this come from source_
  bool aligned_ = false;       // follows a sampler: seek moves it
  number_source* source_ = nullptr;
};

}  // namespace zraka

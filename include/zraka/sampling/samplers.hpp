#pragma once
// Samplers (book 5.1, "Low-discrepancy samplers"): where the numbers of a sample come from.
// A path is an integral over many dimensions (the pixel position, then per bounce a light, a
// point on it, a direction, ...); a sampler gives sample `index` of a pixel's `count` one point
// of that space, coordinate j for the path's j-th draw (path.hpp lays the draws out in fixed
// blocks, so coordinate j means the same draw in every sample).
//   independent  every number a hash of (seed, pixel, sample, number): rng.hpp alone, n^(-1/2)
//   stratified   per pair of coordinates a jittered grid of `count` cells (strata_for), each
//                pair visiting its cells in its own random order; stratified only once all
//                `count` samples are in (a progressive run's earlier passes hold a random
//                subset of the cells: unbiased, not stratified)
//   halton       coordinate j the radical inverse of the sample index in the j-th prime base,
//                Owen-scrambled per (seed, pixel, coordinate)
//   sobol        per pair of coordinates the first two Sobol dimensions, a (0,2)-sequence, of a
//                shuffled index, Owen-scrambled per (seed, pixel, coordinate): "padded", as
//                pbrt-v4's PaddedSobolSampler, so different pairs are not correlated
// Every point is a function of (seed, pixel, index, count): any thread computes any sample.
// Scrambling keeps what makes the points good (Halton's first b^k points fill the k-digit
// intervals of base b, each Sobol pair's first 2^k points fill every elementary interval of area
// 2^-k) and makes each point uniform, so the estimate stays unbiased.
//
// A program backs a sample's stream with its point (sample_point::drive); the first
// `coordinates` coordinates come from the sampler, the rest of a long path from the stream's
// own hash (rng.hpp), still correct, only no longer low-discrepancy.
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/pixel_sampling.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace zraka {

enum class sampler_kind { independent, stratified, halton, sobol };

inline constexpr enum_name<sampler_kind> sampler_kind_names[] = {{sampler_kind::independent, "independent"},
                                                                 {sampler_kind::stratified, "stratified"},
                                                                 {sampler_kind::halton, "halton"},
                                                                 {sampler_kind::sobol, "sobol"}};
constexpr std::span<const enum_name<sampler_kind>> enum_names(sampler_kind) { return sampler_kind_names; }  // enum_names.hpp
inline const std::string sampler_names = enum_name_list<sampler_kind>();  // "independent, stratified, halton, sobol"
inline sampler_kind parse_sampler(std::string_view s) { return parse_enum<sampler_kind>(s, "sampler"); }

constexpr std::uint32_t reverse_bits(std::uint32_t x) {
  x = (x >> 16) | (x << 16);
  x = ((x & 0xff00ff00u) >> 8) | ((x & 0x00ff00ffu) << 8);
  x = ((x & 0xf0f0f0f0u) >> 4) | ((x & 0x0f0f0f0fu) << 4);
  x = ((x & 0xccccccccu) >> 2) | ((x & 0x33333333u) << 2);
  return ((x & 0xaaaaaaaau) >> 1) | ((x & 0x55555555u) << 1);
}

// [listing owen-scramble]
// A nested uniform (Owen) scramble of a 32-bit fraction: bit k from the top is flipped by a
// random function of the key and of the bits above it, so points that share their first k bits
// share the flips of those bits: an elementary interval goes to a random one of the same size,
// and a net stays a net. Done as Laine and Karras do: with the bits reversed, "the bits above"
// are the bits below, and sums and products only carry upward.
constexpr std::uint32_t owen_scramble(std::uint32_t x, std::uint32_t key) {
  x = reverse_bits(x);
  x += key;                // bit k: flipped by key bit k and the carry from the bits below
  x ^= x * 0x2c1b3c6cu;    // an even multiplier adds only bits below to each bit
  x *= (key >> 15) | 1u;   // an odd one keeps bit k and adds bits below
  x ^= x * 0x7a4e9d58u;
  x += pcg_hash(key);
  x ^= x * 0xd3a2646cu;
  return reverse_bits(x);
}
// [end]

// [listing sobol-pair]
// The first two dimensions of Sobol's sequence, as 32-bit fractions of index i. The first is the
// van der Corput sequence (the bits of i mirrored); the second takes for bit k of i the column
// v_k of its generator matrix, v_0 = 1/2 and v_k = v_(k-1) xor v_(k-1)/2 (the primitive
// polynomial x + 1), which is Pascal's triangle mod 2. Together a (0,2)-sequence: every aligned
// block of 2^k points has one point in each elementary interval of area 2^-k.
constexpr std::uint32_t sobol_0(std::uint32_t i) { return reverse_bits(i); }
constexpr std::uint32_t sobol_1(std::uint32_t i) {
  std::uint32_t x = 0;
  for (std::uint32_t v = 0x80000000u; i != 0; i >>= 1, v ^= v >> 1)
    if (i & 1u) x ^= v;
  return x;
}
// [end]

namespace detail {
// The first n primes, the bases of Halton's coordinates.
template <std::size_t N> constexpr std::array<std::uint32_t, N> first_primes() {
  std::array<std::uint32_t, N> p{};
  std::size_t n = 0;
  for (std::uint32_t c = 2; n < N; ++c) {
    bool prime = true;
    for (std::size_t i = 0; i < n && p[i] * p[i] <= c; ++i) prime = prime && c % p[i] != 0;
    if (prime) p[n++] = c;
  }
  return p;
}

// A fraction in [0, 1) as 32 bits (rounding up to 1 is kept below it).
constexpr std::uint32_t fraction_bits(double v) {
  const double x = v * 0x1p32;
  return x < 4294967295.0 ? std::uint32_t(x) : 4294967295u;
}

// A bijection of [0, n) chosen by `key` (a permutation without a table): a mixing bijection of
// the smallest power of two at least n, applied again until the value falls below n.
constexpr std::uint32_t permute_index(std::uint32_t i, std::uint32_t n, std::uint32_t key) {
  if (n <= 1) return 0;
  int bits = 0;
  while ((std::uint64_t(1) << bits) < n) ++bits;
  const std::uint32_t mask = std::uint32_t((std::uint64_t(1) << bits) - 1), shift = std::uint32_t(bits + 1) / 2;
  do {  // each step is a bijection of [0, mask]: xor, odd multiply mod 2^bits, xor-shift
    for (std::uint32_t r = 0, k = key; r < 3; ++r, k = pcg_hash(k)) {
      i = (i ^ k) & mask;
      i = (i * ((k >> 8) | 1u)) & mask;
      i ^= i >> shift;
    }
  } while (i >= n);
  return i;
}
}  // namespace detail

inline constexpr std::array<std::uint32_t, 128> halton_bases = detail::first_primes<128>();

// [listing halton]
// Coordinate of point `index` in base b: its digits d_0 d_1 ... (index = sum d_k b^k) mirrored
// to 0.d_0 d_1 ... (the radical inverse), each digit permuted by a map chosen by the key and the
// digits before it (Owen's nested scramble in base b). The maps are d -> a d + c mod b with
// random a != 0 and c: they take any two different digits to a uniformly random pair of
// different digits, which is all Owen's variance depends on. Only the digits that tell the
// indices below `count` apart are computed; the scrambled digits after them are uniform, so one
// uniform number stands in for them.
inline std::uint32_t halton_bits(std::uint32_t index, std::uint32_t b, std::uint32_t key, std::uint32_t count) {
  const double inv = 1.0 / double(b);
  double v = 0, w = inv;  // the value so far, the weight of the next digit
  std::uint32_t h = key;
  for (std::uint32_t n = index, m = count > 0 ? count - 1 : 0; n > 0 || m > 0; n /= b, m /= b) {
    const std::uint32_t d = n % b;
    const std::uint32_t a = 1 + (h & 0xffffu) % (b - 1), c = (h >> 16) % b;  // b prime: any a != 0 will do
    v += double((a * d + c) % b) * w;  // a, c, d < b <= 719: no overflow
    w *= inv;
    h = hash_combine(h, d);
  }
  const double rest = w * double(b);  // the width of the interval the digits so far fix
  return detail::fraction_bits(v + rng::unit_double(pcg_hash(h ^ 0x68e31da4u), pcg_hash(h)) * rest);
}
// [end]

// [listing sample-point]
// Sample `index` of `count` in a pixel: coordinate j of its point, and the stream numbers a
// path draws (two per coordinate: rng::uniform makes a double of two numbers).
class sample_point final : public number_source {
 public:
  static constexpr std::uint32_t coordinates = 128;  // from the sampler; beyond them the hash

  sample_point(sampler_kind kind, std::uint64_t seed, std::uint32_t pixel, std::uint32_t index, std::uint32_t count)
      : kind_(kind), index_(index), count_(count < 1 ? 1 : count) {
    if (kind == sampler_kind::independent) return;  // nothing to prepare: the stream stays as it is
    pixel_key_ = hash_combine(seed_word(seed), pixel);
    jitter_key_ = hash_combine(hash_combine(pixel_key_, 0x2545f491u), index);
    if (kind == sampler_kind::stratified) grid_ = strata_for(int(count_ > 65536 ? 65536 : count_));  // --spp's most
  }

  // Backs stream g with this point while it lives (independent: leaves g alone).
  void drive(rng& g) {
    if (kind_ != sampler_kind::independent) g.follow(*this, 2 * coordinates);
  }

  // Coordinate j as a 32-bit fraction.
  std::uint32_t coordinate(std::uint32_t j) const {
    const std::uint32_t pair_key = hash_combine(pixel_key_, j / 2), key = hash_combine(pixel_key_, j + 0x40000000u);
    switch (kind_) {
      case sampler_kind::halton: return halton_bits(index_, halton_bases[j % coordinates], key, count_);
      case sampler_kind::sobol: {  // the pair's own order of the index, then its own scramble
        const std::uint32_t i = owen_scramble(index_, pair_key);
        return owen_scramble(j % 2 == 0 ? sobol_0(i) : sobol_1(i), key);
      }
      case sampler_kind::stratified: {  // the pair's own order of the cells
        const std::uint32_t n = std::uint32_t(grid_.nx * grid_.ny);
        const std::uint32_t cell = detail::permute_index(index_ % n, n, pair_key);
        const double jitter = rng::unit_double(pcg_hash(jitter_key_ ^ j), pcg_hash(jitter_key_ + j));
        return j % 2 == 0 ? detail::fraction_bits((cell % std::uint32_t(grid_.nx) + jitter) / grid_.nx)
                          : detail::fraction_bits((cell / std::uint32_t(grid_.nx) + jitter) / grid_.ny);
      }
      case sampler_kind::independent: break;  // a hash: no stream asks (drive leaves it alone)
    }
    return pcg_hash(jitter_key_ ^ hash_combine(j, 0x1b873593u));
  }

  // Stream number d: the high word of coordinate d/2, then a hashed low word, so the double is
  // uniform inside the point's 2^-27 cell.
  std::uint32_t number(std::uint32_t d) override {
    return d % 2 == 0 ? coordinate(d / 2) : pcg_hash(jitter_key_ ^ hash_combine(d, 0x85ebca6bu));
  }

 private:
  sampler_kind kind_;
  std::uint32_t index_, count_;
  std::uint32_t pixel_key_ = 0, jitter_key_ = 0;
  strata grid_;
};
// [end]

}  // namespace zraka

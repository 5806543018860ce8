// The counter-based random numbers of include/zraka/core/rng.hpp, in OpenCL C 1.2, with the same
// arithmetic word for word, so a kernel draws bit-identical numbers to the CPU for the same
// (seed, pixel, sample, dimension). tests/test_cl.cpp checks that on many inputs.
// uint is 32 bits and wraps on overflow in OpenCL C exactly as std::uint32_t does in C++.
// Use: build it in front of the kernel that calls it (zraka::cl::build_program with a list).

// [listing pcg-hash-cl]
uint pcg_hash(uint v) {
  const uint state = v * 747796405u + 2891336453u;
  const uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
// [end]

uint hash_combine(uint h, uint word) {
  return pcg_hash(h ^ (word + 0x9e3779b9u + (h << 6) + (h >> 2)));
}

uint seed_word(ulong seed) {
  return hash_combine(pcg_hash((uint)seed), (uint)(seed >> 32));
}

// [listing rng-cl]
// One stream per (seed, pixel, sample); `dimension` counts the numbers drawn so far.
typedef struct {
  uint key_pixel, key_sample, dimension;
} rng_t;

rng_t rng_make(ulong seed, uint pixel, uint sample) {
  rng_t r;
  r.key_pixel = pcg_hash(pixel + seed_word(seed));
  r.key_sample = pcg_hash(sample + pcg_hash(seed_word(seed) ^ 0x5bd1e995u));
  r.dimension = 0;
  return r;
}

uint rng_next_u32(rng_t* r) {
  return pcg_hash(r->key_pixel ^ hash_combine(r->key_sample, r->dimension++));
}

// Uniform in [0,1) with 24 random bits: exact in float, never rounds up to 1.
float rng_uniform_float(rng_t* r) {
  return (float)(rng_next_u32(r) >> 8) * 5.9604644775390625e-8f;  // 2^-24
}
// [end]

#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
// 53 random bits from two draws, in the same order as rng::uniform().
double rng_uniform(rng_t* r) {
  const ulong hi = rng_next_u32(r) >> 5;
  const ulong lo = rng_next_u32(r) >> 6;
  return (double)((hi << 26) | lo) * 1.1102230246251565404e-16;  // 2^-53
}
#endif

// Built after kernels/rng.cl: tests/test_cl.cpp compares these numbers with rng.hpp's.
// Work item i draws `count` numbers from the stream (seed[i], pixel[i], sample[i]).
kernel void rng_check(global const ulong* seed, global const uint* pixel,
                      global const uint* sample, uint count, global uint* out_u32,
                      global float* out_float) {
  const size_t i = get_global_id(0);
  rng_t a = rng_make(seed[i], pixel[i], sample[i]);
  rng_t b = a;
  for (uint d = 0; d < count; ++d) {
    out_u32[i * count + d] = rng_next_u32(&a);
    out_float[i * count + d] = rng_uniform_float(&b);
  }
}

#ifdef cl_khr_fp64
kernel void rng_check_double(global const ulong* seed, global const uint* pixel,
                             global const uint* sample, uint count, global double* out) {
  const size_t i = get_global_id(0);
  rng_t r = rng_make(seed[i], pixel[i], sample[i]);
  for (uint d = 0; d < count; ++d) out[i * count + d] = rng_uniform(&r);
}
#endif

// The way a renderer uses it: one work item per pixel, the stream keyed by the pixel's index.
kernel void rng_image(ulong seed, uint sample, uint width, global float* out) {
  const uint x = get_global_id(0), y = get_global_id(1);
  const uint pixel = y * width + x;
  rng_t r = rng_make(seed, pixel, sample);
  out[2 * pixel] = rng_uniform_float(&r);
  out[2 * pixel + 1] = rng_uniform_float(&r);
}

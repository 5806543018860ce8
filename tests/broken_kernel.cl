// Deliberately broken (tests/test_cl.cpp and chapter 3.3's smoke test): the thesis's Listing 3.6
// prints `results`, but the array is called `c` here as well as `result` there (errata B13).
kernel void vector_add(global const float* a, global const float* b, global float* c, uint n) {
  const size_t i = get_global_id(0);
  if (i < n) results[i] = a[i] + b[i];
}

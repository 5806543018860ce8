// Book 3.3, the thesis's Listing 3.7: c = a + b, one work item per element.
// The global size may be rounded up past n, so every work item checks its index first.
// [listing vector-add]
kernel void vector_add(global const float* a, global const float* b, global float* c, uint n) {
  const size_t i = get_global_id(0);
  if (i < n) c[i] = a[i] + b[i];
}
// [end]

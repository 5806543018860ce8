#pragma once
// A light kind's numbers for the OpenCL kernel (book 4.3): what a kind that the kernel renders
// fills in (its pack()), and gpu/gpu_scene.hpp copies into its gpu_light record. Plain floats,
// so that lights/ needs nothing of gpu/.
namespace zraka {

struct kernel_light {
  int kind = -1;  // gpu_light_kind in gpu/gpu_scene.hpp and kernels/pathtrace.cl
  float position[3] = {0, 0, 0};
  float intensity[3] = {0, 0, 0};
};

}  // namespace zraka

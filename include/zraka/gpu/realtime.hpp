#pragma once
// The host side of the real-time path tracer (book 4.3): a packed scene (gpu_scene.hpp) on an
// OpenCL device, kernels/pathtrace.cl built for that scene's features, and progressive
// accumulation: every launch adds samples to a per-pixel sum on the device and writes the
// running mean as sRGB bytes, ready for glTexSubImage2D (PoCL has no CL/GL sharing, so the
// bytes come back to the host; 4 bytes a pixel instead of 16 for the float sums).
//
//   zraka::gpu_renderer r(ctx, packed, width, height, seed);
//   r.launch(1); r.read_display(bytes);  // one frame, one sample per pixel
//   r.reset();                           // the camera moved: start the sums again
// The chapter's in-code scenes are here too (realtime_scene()), so that the chapter, its test
// and its benchmark render the same ones; they need no OpenCL.
// Link with OpenCL::OpenCL (a test's first line: // links: OpenCL).
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/gpu/cl.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/scene/named_scenes.hpp>
#include <zraka/scene/scene.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace zraka {

// The chapter's in-code scenes come from the registry of named scenes (named_scenes.hpp), so
// that `--scene cornell` is the same scene here as in every other program.
inline scene realtime_scene(const std::string& name) { return builtin_scene(name); }
}  // namespace zraka

#if __has_include(<CL/cl.h>)
namespace zraka {

class gpu_renderer {
 public:
  // all_features: compile every code path instead of the scene's (the benchmark's comparison).
  // kernel_file: another kernel with the same interface (or a broken one, to see the build log).
  gpu_renderer(const cl::context& c, const gpu_scene& s, int width, int height, std::uint64_t seed,
               bool all_features = false,
               const std::filesystem::path& kernel_file = "kernels/pathtrace.cl");
  ~gpu_renderer();

  const std::string& options() const { return options_; }
  double build_seconds() const { return build_seconds_; }
  int width() const { return width_; }
  int height() const { return height_; }
  std::uint32_t samples() const { return samples_; }  // per pixel, summed so far

  // Adds n samples per pixel (enqueued; read_* waits for it).
  void launch(std::uint32_t n);
  // The camera moved (or anything else changed): the next launch starts the sums afresh.
  void set_camera(const gpu_camera& cam);
  void reset() { samples_ = 0; }

  void finish() const { ctx_.finish(); }

  // The running mean as sRGB bytes, RGBA, bottom row first (a texture's order).
  void read_display(std::vector<std::uint8_t>& rgba) const {
    rgba.resize(std::size_t(width_) * std::size_t(height_) * 4);
    ctx_.read(display_, rgba.size(), rgba.data());
  }
  // The same without waiting: the copy is queued behind the launches, and wait_display() blocks
  // until it is done. The viewer draws frame k while the device renders frame k + 1.
  void read_display_async(std::vector<std::uint8_t>& rgba);
  void wait_display() {
    if (!pending_) return;
    const cl_event e = pending_.get();
    cl::check(clWaitForEvents(1, &e), "clWaitForEvents");
    pending_.reset();
  }

  // The running mean in linear floats, top row first (zraka::image's order).
  image read_image() const;

  // Each pixel's sample variance (unbiased, per channel) from the sums of the samples and of
  // their squares, top row first: the standard error of a pixel is sqrt(variance / samples()).
  image read_variance() const;

 private:
  // An empty array still needs a buffer to pass (OpenCL has no zero-size buffers): one zeroed
  // element, which the kernel never reads because its count is 0.
  template <class V> cl::buffer upload(const std::vector<V>& v) const {
    if (v.empty()) {
      const V zero{};
      return ctx_.make_buffer(CL_MEM_READ_ONLY, sizeof(V), &zero);
    }
    return ctx_.make_buffer(CL_MEM_READ_ONLY, v.size() * sizeof(V), v.data());
  }

  const cl::context& ctx_;
  int width_, height_;
  std::uint64_t seed_;
  gpu_scene scene_;
  std::string options_;
  int pixels_per_item_ = 1;  // gpu_pixels_per_item: 8 with the eight-lane loop
  double build_seconds_ = 0;
  cl::program_handle program_;
  cl::kernel_handle kernel_;
  cl::buffer spheres_, quads_, quad_groups_, planes_, tris_, nodes_, materials_, lights_, light_tris_, camera_, accum_,
      accum_sq_, display_, textures_, texels_, tri_uvs_, env_, env_tables_, noise_, srgb_steps_;
  std::uint32_t samples_ = 0;
  using event_handle = cl::handle<cl_event, clReleaseEvent>;
  event_handle pending_;
};

#if ZRAKA_OPENCL_DEFINITIONS
ZRAKA_OPENCL_FN gpu_renderer::gpu_renderer(const cl::context& c, const gpu_scene& s, int width, int height,
                                           std::uint64_t seed, bool all_features,
                                           const std::filesystem::path& kernel_file)
    : ctx_(c), width_(width), height_(height), seed_(seed), scene_(s) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                " is out of range (1..16384)");
  options_ = build_options(s.features, all_features);
  pixels_per_item_ = gpu_pixels_per_item(s.features, all_features);
  stopwatch clock;
  program_ = cl::build_program_files(c, {"kernels/rng.cl", kernel_file}, options_);
  kernel_ = cl::make_kernel(program_, "render");
  build_seconds_ = clock.seconds();
  spheres_ = upload(s.spheres);
  quads_ = upload(s.quads);
  quad_groups_ = upload(s.quad_groups);
  planes_ = upload(s.planes);
  tris_ = upload(s.triangles);
  nodes_ = upload(s.nodes);
  materials_ = upload(s.materials);
  lights_ = upload(s.lights);
  light_tris_ = upload(s.light_triangles);
  textures_ = upload(s.textures);
  texels_ = upload(s.texels);
  tri_uvs_ = upload(s.triangle_uvs);
  env_ = c.make_buffer(CL_MEM_READ_ONLY, sizeof(gpu_environment), &s.environment);
  env_tables_ = upload(s.env_tables);
  noise_ = upload(s.noise_permutation);
  const std::array<float, 256> steps = srgb_byte_steps();  // the display's encoding (image_io.hpp)
  srgb_steps_ = c.make_buffer(CL_MEM_READ_ONLY, sizeof steps, steps.data());
  camera_ = c.make_buffer(CL_MEM_READ_ONLY, sizeof(gpu_camera), &s.camera);
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  accum_ = c.make_buffer(CL_MEM_READ_WRITE, pixels * 16);
  accum_sq_ = c.make_buffer(CL_MEM_READ_WRITE, pixels * 16);
  display_ = c.make_buffer(CL_MEM_WRITE_ONLY, pixels * 4);
}

ZRAKA_OPENCL_FN gpu_renderer::~gpu_renderer() = default;

// [listing realtime-launch]
// Adds n samples per pixel (enqueued; read_* waits for it).
ZRAKA_OPENCL_FN void gpu_renderer::launch(std::uint32_t n) {
  const gpu_scene& s = scene_;
  const cl_float4 bg = {{s.background.x, s.background.y, s.background.z, 0.0f}};
  cl::set_args(kernel_, spheres_, quads_, quad_groups_, planes_, tris_, nodes_, materials_, lights_, light_tris_,
               camera_, accum_, accum_sq_, display_, cl_int(s.spheres.size()), cl_int(s.quads.size()),
               cl_int(s.planes.size()), cl_int(s.lights.size()), cl_int(s.nodes.size()),
               cl_uint(width_), cl_uint(height_), cl_uint(samples_), cl_uint(n),
               cl_ulong(seed_), bg, textures_, texels_, tri_uvs_, cl_int(s.triangle_uvs.empty() ? 0 : 1), env_,
               env_tables_, noise_, srgb_steps_);
  // The lanes loop (PATH_LANES) renders several pixels of a row in each work item.
  const int per_item = pixels_per_item_;
  cl::run_2d(ctx_, kernel_, std::size_t((width_ + per_item - 1) / per_item), std::size_t(height_));
  samples_ += n;
}
// The camera moved (or anything else changed): the next launch starts the sums afresh.
ZRAKA_OPENCL_FN void gpu_renderer::set_camera(const gpu_camera& cam) {
  scene_.camera = cam;
  ctx_.write(camera_, sizeof cam, &cam);
  reset();
}
// [end]

ZRAKA_OPENCL_FN void gpu_renderer::read_display_async(std::vector<std::uint8_t>& rgba) {
  rgba.resize(std::size_t(width_) * std::size_t(height_) * 4);
  cl_event e = nullptr;
  cl::check(clEnqueueReadBuffer(ctx_.queue.get(), display_.get(), CL_FALSE, 0, rgba.size(),
                                rgba.data(), 0, nullptr, &e),
            "clEnqueueReadBuffer");
  pending_ = event_handle(e);
  cl::check(clFlush(ctx_.queue.get()), "clFlush");
}

ZRAKA_OPENCL_FN image gpu_renderer::read_image() const {
  std::vector<float> sums(std::size_t(width_) * std::size_t(height_) * 4);
  ctx_.read(accum_, sums.size() * sizeof(float), sums.data());
  image img(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const float* p = &sums[4 * (std::size_t(y) * std::size_t(width_) + std::size_t(x))];
      const float n = p[3] > 0 ? p[3] : 1.0f;
      img.at(x, y) = rgb(p[0] / n, p[1] / n, p[2] / n);
    }
  return img;
}

ZRAKA_OPENCL_FN image gpu_renderer::read_variance() const {
  const std::size_t n = std::size_t(width_) * std::size_t(height_) * 4;
  std::vector<float> sums(n), squares(n);
  ctx_.read(accum_, n * sizeof(float), sums.data());
  ctx_.read(accum_sq_, n * sizeof(float), squares.data());
  image img(width_, height_);
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = 4 * (std::size_t(y) * std::size_t(width_) + std::size_t(x));
      const double k = sums[i + 3];
      rgb v(0);
      for (int c = 0; c < 3 && k > 1; ++c) {
        const double mean = sums[i + std::size_t(c)] / k;
        v[c] = float(std::max(0.0, (squares[i + std::size_t(c)] - k * mean * mean) / (k - 1)));
      }
      img.at(x, y) = v;
    }
  return img;
}
#endif

}  // namespace zraka
#endif

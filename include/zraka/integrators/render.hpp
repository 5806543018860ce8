#pragma once
// Rendering an image with many samples per pixel on all cores.
//
// The caller supplies one function: the colour of sample s of pixel (x, y). It gets that
// sample's own random stream rng(seed, pixel, sample), so every sample can be recomputed alone
// and the image does not depend on how pixels are split among threads: tiles of pixels are the
// items of parallel_for (parallel.hpp), each pixel's samples are summed in a fixed order, and the
// same seed gives the same bits for 1, 2 or 16 threads and any tile size.
//
// A sample that comes back NaN or infinite is counted and left out of the sum (so one bad path
// does not turn the pixel black or white); the count is reported, because it signals a bug.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/function_ref.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/core/parallel.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <cstdio>
#include <string>

namespace zraka {

struct render_options {
  int threads = 0;        // 0 = all hardware threads
  int tile = 16;          // tile side in pixels
  bool progress = true;   // a bar on stderr, drawn only when stderr is a terminal
};

struct render_stats {
  double seconds = 0;
  int threads = 1;
  std::uint64_t samples = 0;    // samples computed
  std::uint64_t rays = 0;       // rays the caller counted (0 if it did not)
  std::uint64_t nonfinite = 0;  // samples that were NaN or infinite (left out)
};

// What the per-sample function receives.
struct sample_context {
  int x, y, sample, spp;
  rng& random;               // this sample's stream
  std::uint64_t& rays;       // add the rays you trace, if you want rays/s reported
};

// The caller's per-sample function with its type left out, so that render's tiles and threads
// (render_with) are compiled once, in zraka::compiled, rather than again for every function of
// every program; the cost is one call through a pointer per sample. Returns the double vec3
// that the pixel sums add (rgb converts).
using sample_fn_ref = function_ref<vec3(sample_context&)>;

// fn(sample_context&) -> rgb. Pixel (x, y) gets the mean of its spp samples; the samples of
// pixel index x + y * width use rng(seed, index, s). The work is render_with's, below; its
// samples are s = first, ..., first + spp - 1 of `total` (render_progressive's passes; total 0:
// spp), which is what sample_context says.
ZRAKA_COMPILED_FN render_stats render_with(image& img, int spp, std::uint64_t seed, sample_fn_ref fn,
                                           const render_options& opt, int first = 0, int total = 0);
template <class SampleFn>
render_stats render(image& img, int spp, std::uint64_t seed, SampleFn&& fn, const render_options& opt = {}) {
  auto sample = [&fn](sample_context& c) { return fn(c); };  // fn may be a plain function
  return render_with(img, spp, seed, sample_fn_ref(sample), opt);
}

// "rendered 320x240, 16 spp in 1.23 s on 2 threads: 1.00 M samples/s, 3.2 M rays/s, 0 NaN/inf samples"
inline std::string summary(const image& img, int spp, const render_stats& s) {
  char buf[256];
  const double secs = std::max(s.seconds, 1e-9);
  int n = std::snprintf(buf, sizeof buf, "rendered %dx%d, %d spp in %.2f s on %d thread%s: %.2f M samples/s",
                        img.width, img.height, spp, s.seconds, s.threads, s.threads == 1 ? "" : "s",
                        double(s.samples) / secs * 1e-6);
  if (s.rays > 0)
    n += std::snprintf(buf + n, sizeof buf - size_t(n), ", %.2f M rays/s", double(s.rays) / secs * 1e-6);
  std::snprintf(buf + n, sizeof buf - size_t(n), ", %llu NaN/inf samples",
                static_cast<unsigned long long>(s.nonfinite));
  return buf;
}

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
// [listing render]
// Tiles of pixels are parallel_for's items; each pixel sums its samples in double, in a fixed
// order, and is written by its own tile only.
ZRAKA_COMPILED_FN render_stats render_with(image& img, int spp, std::uint64_t seed, sample_fn_ref fn,
                                           const render_options& opt, int first, int total) {
  if (spp < 1) throw error("--spp must be at least 1, got " + std::to_string(spp));
  if (total == 0) total = spp;
  if (first < 0 || first > total - spp) throw error("render_with: samples outside 0 .. total - 1");
  if (opt.tile < 1) throw error("tile size must be at least 1");
  check_render_size(img.width, img.height, spp);
  const int threads = resolve_threads(opt.threads);
  const int tiles_x = (img.width + opt.tile - 1) / opt.tile;
  const int tiles_y = (img.height + opt.tile - 1) / opt.tile;
  std::atomic<std::uint64_t> rays{0}, nonfinite{0};
  stopwatch clock;
  parallel_for(std::size_t(tiles_x) * std::size_t(tiles_y), parallel_options{threads, opt.progress}, [&](std::size_t t) {
    const int x0 = int(t % std::size_t(tiles_x)) * opt.tile, y0 = int(t / std::size_t(tiles_x)) * opt.tile;
    std::uint64_t tile_rays = 0, tile_bad = 0;
    for (int y = y0; y < std::min(y0 + opt.tile, img.height); ++y)
      for (int x = x0; x < std::min(x0 + opt.tile, img.width); ++x) {
        const auto pixel = static_cast<std::uint32_t>(y) * std::uint32_t(img.width) + std::uint32_t(x);
        vec3 sum(0);  // double sums: the order is fixed, the result is the same everywhere
        for (int s = first; s < first + spp; ++s) {
          rng g(seed, pixel, static_cast<std::uint32_t>(s));
          sample_context ctx{x, y, s, total, g, tile_rays};
          const vec3 c(fn(ctx));
          if (is_finite(c)) sum += c;
          else ++tile_bad;
        }
        img.at(x, y) = rgb(sum / double(spp));
      }
    rays += tile_rays;
    nonfinite += tile_bad;
  });
  return {clock.seconds(), threads, std::uint64_t(img.width) * std::uint64_t(img.height) * std::uint64_t(spp),
          rays.load(), nonfinite.load()};
}
// [end]
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

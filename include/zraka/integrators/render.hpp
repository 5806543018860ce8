#pragma once
// Rendering an image with many samples per pixel on all cores.
//
// The caller supplies one function: the colour of sample s of pixel (x, y). It gets that
// sample's own random stream rng(seed, pixel, sample), so every sample can be recomputed alone
// and the image does not depend on how pixels are split among threads: tiles of pixels go to
// std::threads from a shared counter, each pixel's samples are summed in a fixed order, and the
// same seed gives the same bits for 1, 2 or 16 threads and any tile size.
//
// A sample that comes back NaN or infinite is counted and left out of the sum (so one bad path
// does not turn the pixel black or white); the count is reported, because it signals a bug.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/function_ref.hpp>
#include <zraka/image/image.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include <unistd.h>  // isatty: the progress bar only draws on a terminal

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

// At most limits().threads_per_core per hardware thread: more gain nothing, and a typo such as
// 100000 would otherwise end in std::terminate when the system runs out of threads.
ZRAKA_COMPILED_FN int resolve_threads(int requested);

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
// Tiles of pixels go to the threads from one shared counter; each pixel sums its samples in
// double, in a fixed order.
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
  const int tiles = tiles_x * tiles_y;

  std::atomic<int> next_tile{0}, done_tiles{0};
  std::atomic<std::uint64_t> rays{0}, nonfinite{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  stopwatch clock;

  auto worker = [&] {
    try {
      for (int t = next_tile++; t < tiles; t = next_tile++) {
        const int x0 = (t % tiles_x) * opt.tile, y0 = (t / tiles_x) * opt.tile;
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
        ++done_tiles;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      failed = true;
      next_tile = tiles;  // the others stop after their current tile
    }
  };

  std::vector<std::thread> pool;
  try {
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker);
  } catch (const std::system_error& e) {  // no more threads: stop those started, then say so
    next_tile = tiles;
    for (auto& th : pool) th.join();
    throw error("cannot start " + std::to_string(threads) + " threads (" + e.what() + "); try fewer --threads");
  }
  const bool bar = opt.progress && isatty(STDERR_FILENO);
  if (bar) {  // this thread draws the bar while the others work, then joins in
    std::thread drawer([&] {
      while (done_tiles < tiles && !failed) {
        const int pct = 100 * done_tiles / tiles;
        std::fprintf(stderr, "\r[%-40s] %3d%%", std::string(size_t(pct * 40 / 100), '#').c_str(), pct);
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    });
    worker();
    for (auto& th : pool) th.join();
    drawer.join();
    std::fprintf(stderr, "\r%60s\r", "");
  } else {
    worker();
    for (auto& th : pool) th.join();
  }
  if (failure) std::rethrow_exception(failure);
  return {clock.seconds(), threads, std::uint64_t(img.width) * std::uint64_t(img.height) * std::uint64_t(spp),
          rays.load(), nonfinite.load()};
}
// [end]

ZRAKA_COMPILED_FN int resolve_threads(int requested) {
  if (requested < 0) throw error("--threads must be 0 (all) or positive, got " + std::to_string(requested));
  const long long cap = max_threads();
  if (requested > cap)
    throw error("--threads " + std::to_string(requested) + " is more than " + std::to_string(cap) + " (" +
                std::to_string(limits().threads_per_core) + " per core on this " +
                std::to_string(std::max(1u, std::thread::hardware_concurrency())) + "-core machine) " +
                raise_hint("threads_per_core"));
  if (requested > 0) return requested;
  return int(std::max(1u, std::thread::hardware_concurrency()));
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

#pragma once
// Progressive rendering (book 2.3, 4.2): the image is refined in passes that double the samples
// per pixel (1, 2, 4, ... spp in total), and after each pass the caller sees the current mean,
// e.g. to measure its error against a reference and write one row of an error-against-time
// table. A wall-clock budget stops the doubling early.
//
// Sample s of pixel p always uses the stream rng(seed, p, s), whichever pass computes it, so the
// image after N spp holds the same samples as a single render of N spp (equal up to float
// rounding of the running sums), for any number of threads.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/function_ref.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/convergence.hpp>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace zraka {

struct progressive_options {
  int max_spp = 1024;        // the last pass ends here (need not be a power of two)
  double time_budget = 0;    // seconds; 0 = none. A pass that would end past it is not started
  std::uint64_t seed = 1;
  render_options render;
};

struct progressive_totals {
  int spp = 0;               // samples per pixel so far
  double seconds = 0;        // wall-clock time of all passes so far
  render_stats stats;        // summed over the passes (samples, rays, NaN/inf)
  bool out_of_time = false;  // the budget stopped it before max_spp
};

// What runs after every pass, its type left out (function_ref.hpp): false stops the doubling.
using pass_fn_ref = function_ref<bool(const image&, const progressive_totals&)>;

// fn(sample_context&) -> rgb as for render(); on_pass(const image& mean, const progressive_totals&)
// runs after every pass; if it returns a bool, false stops the doubling there. The passes are
// render_progressive_with's, compiled once (below).
ZRAKA_COMPILED_FN image render_progressive_with(int width, int height, const progressive_options& opt,
                                                sample_fn_ref fn, pass_fn_ref on_pass,
                                                progressive_totals* totals_out);
template <class SampleFn, class PassFn>
image render_progressive(int width, int height, const progressive_options& opt, SampleFn&& fn,
                         PassFn&& on_pass, progressive_totals* totals_out = nullptr) {
  auto pass = [&](const image& m, const progressive_totals& t) {
    if constexpr (std::is_same_v<decltype(on_pass(m, t)), bool>) {
      return bool(on_pass(m, t));
    } else {
      on_pass(m, t);
      return true;
    }
  };
  auto sample = [&fn](sample_context& c) { return fn(c); };  // fn may be a plain function
  return render_progressive_with(width, height, opt, sample_fn_ref(sample), pass_fn_ref(pass), totals_out);
}

// [listing seconds-to-reach]
// When did a progressive run's error (column `column`) first fall to `target`? Between the two
// rows that bracket it, log(error) is interpolated linearly in log(seconds) (a power law, as
// error ~ t^(-1/2) is). NaN if it never got there.
inline double seconds_to_reach(const convergence_log& log, double target, std::string_view column = "rmse") {
  const std::size_t c = log.column_index(column);
  const auto& rows = log.rows();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double e = rows[i].values[c], t = rows[i].seconds;
    if (!(e <= target)) continue;
    if (i == 0) return t;  // already below after the first pass
    const double e0 = rows[i - 1].values[c], t0 = rows[i - 1].seconds;
    if (!(e0 > e) || !(t > t0) || !(t0 > 0)) return t;
    const double f = std::log(e0 / target) / std::log(e0 / e);  // in [0, 1]
    return t0 * std::pow(t / t0, f);
  }
  return std::numeric_limits<double>::quiet_NaN();
}
// [end]

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
// [listing progressive]
// fn(sample_context&) -> rgb as for render(); on_pass(mean, totals) runs after every pass and
// returns false to stop the doubling there.
ZRAKA_COMPILED_FN image render_progressive_with(int width, int height, const progressive_options& opt,
                                                sample_fn_ref fn, pass_fn_ref on_pass,
                                                progressive_totals* totals_out) {
  if (opt.max_spp < 1) throw error("--spp must be at least 1, got " + std::to_string(opt.max_spp));
  image::check_size(width, height);
  check_render_size(width, height, opt.max_spp);  // before the images are made
  if (!(opt.time_budget >= 0)) throw error("--time-budget must not be negative");
  image mean(width, height), pass(width, height);
  std::vector<vec3> sum(mean.pixels.size(), vec3(0));
  progressive_totals tot;
  const stopwatch clock;
  while (tot.spp < opt.max_spp) {
    const int n = std::min(std::max(tot.spp, 1), opt.max_spp - tot.spp);  // doubles the total
    // The next pass costs about as much as all before it: skip it if that would overrun.
    if (opt.time_budget > 0 && tot.spp > 0 && clock.seconds() * (1.0 + double(n) / tot.spp) > opt.time_budget) {
      tot.out_of_time = true;
      break;
    }
    // Samples tot.spp ... tot.spp + n - 1 of each pixel, each with its own stream.
    const render_stats s = render_with(pass, n, opt.seed, fn, opt.render, tot.spp, opt.max_spp);
    tot.spp += n;
    tot.stats.samples += s.samples, tot.stats.rays += s.rays, tot.stats.nonfinite += s.nonfinite;
    tot.stats.threads = s.threads;
    for (std::size_t i = 0; i < sum.size(); ++i) {
      sum[i] += vec3(pass.pixels[i]) * double(n);
      mean.pixels[i] = rgb(sum[i] / double(tot.spp));
    }
    tot.seconds = tot.stats.seconds = clock.seconds();
    if (!on_pass(mean, tot)) break;  // the caller has seen enough
  }
  if (totals_out) *totals_out = tot;
  return mean;
}
// [end]
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

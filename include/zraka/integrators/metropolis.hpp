#pragma once
// Metropolis light transport in primary sample space (Kelemen et al. 2002; Veach and Guibas
// 1997 for Metropolis light transport itself), on top of the path tracer of chapter 2.3.
//
// One sample is a vector of uniform numbers u (pss.hpp): its first two give the point on the
// film, the rest drive the unchanged path tracer, which returns the radiance L(u) the sample
// carries to its pixel. The chains are distributed in proportion to the scalar contribution
// I(u) = luminance(L(u)); each pixel then receives
//
//   pixel_j = (W H b / M) sum_{k=1..M} [L(u_k) / I(u_k)] 1_j(u_k),    b = E[I(u)] = integral of I,
//
// over all M mutations of all chains. b, the normalisation, is estimated beforehand from a
// bootstrap of independent samples, which also gives the chains their start states (chosen in
// proportion to I, so no burn-in is needed: the chains start already in the target distribution).
// Each step adds the expected value of the proposal and the current state (weights a and 1 - a,
// a the acceptance probability), so rejected proposals still contribute.
//
// Determinism: bootstrap sample i uses rng(seed, i, bootstrap_stream), chain c its own streams;
// both are parallel_for's items (parallel.hpp); each chain splats into an image of its own, and
// the chains' images are added in chain order (in_order), so the image is the same for a seed
// whatever the thread count.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/parallel.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/pss.hpp>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <string>
#include <vector>

namespace zraka {

struct metropolis_options {
  pss_options pss;
  std::uint64_t bootstrap = 100000;  // independent samples that estimate b and seed the chains
  int chains = 64;                   // fixed, not tied to threads (determinism)
  int threads = 0;                   // 0 = all hardware threads
};

struct metropolis_render_t {
  image img;
  double b = 0;                      // the bootstrap's estimate of E[I]
  double acceptance = 0;             // accepted / proposed, over all chains
  double large_acceptance = 0, small_acceptance = 0;
  std::uint64_t mutations = 0;
  double bootstrap_seconds = 0, seconds = 0;  // seconds: the whole render, bootstrap included
  std::uint64_t rays = 0, nonfinite = 0;
};

namespace detail {
constexpr std::uint32_t bootstrap_stream = 0x4d4c5400u;  // "MLT": the bootstrap's sample index base
constexpr std::uint32_t chain_stream = 0x4d4c5401u;
constexpr std::uint32_t select_stream = 0x4d4c5402u;
}  // namespace detail

// [listing mlt-sample]
// One sample of primary sample space: the film point from the first two numbers, then a path.
struct mlt_sample_t {
  rgb L{0};
  double I = 0;  // luminance(L); 0 also for a NaN/inf L (counted, and never accepted)
  int x = 0, y = 0;
};
template <class T, class Camera>
mlt_sample_t mlt_sample(const path_tracer_t<T>& pt, const Camera& cam, int W, int H, rng& g, std::uint64_t& rays,
                           std::uint64_t& bad) {
  const vec2 u = g.uniform2();
  mlt_sample_t s;
  s.x = std::min(W - 1, int(u.x * W)), s.y = std::min(H - 1, int(u.y * H));
  const rgb L = pt(cam.generate(T(u.x), T(u.y)), g, rays);
  if (!is_finite(L)) { ++bad; return s; }
  s.L = L, s.I = std::max(0.0, luminance(L));
  return s;
}
// [end]

template <class T>
metropolis_render_t render_metropolis(const scene_t<T>& sc, const path_options& po, std::uint64_t mutations_per_pixel,
                                      std::uint64_t seed, const metropolis_options& opt) {
  const int W = sc.settings.width, H = sc.settings.height;
  check_render_size(W, H, 1);
  if (mutations_per_pixel < 1) throw error("metropolis: the mutations per pixel must be at least 1");
  if (opt.chains < 1 || opt.chains > 1 << 20) throw error("metropolis: --chains must be in 1..2^20, got " + std::to_string(opt.chains));
  // The bootstrap keeps each sample's luminance and their running sums: 16 bytes a sample.
  if (opt.bootstrap < 1 || opt.bootstrap > (1ull << 27))
    throw error("metropolis: " + std::to_string(opt.bootstrap) + " bootstrap samples is not in 1..2^27 (fewer mutations or a smaller --bootstrap)");
  check_pss_options(opt.pss);  // before threads start
  const std::uint64_t N = std::uint64_t(W) * std::uint64_t(H);
  if (mutations_per_pixel > (1ull << 40) / N) throw error("metropolis: too many mutations");
  const std::uint64_t M = mutations_per_pixel * N;
  const int threads = std::min(resolve_threads(opt.threads), opt.chains);
  const path_tracer_t<T> pt(sc, po);
  const auto cam = sc.prepared_camera();
  stopwatch clock;
  std::atomic<std::uint64_t> rays{0}, bad{0};
  // body(i, rays, bad) for i in [0, count): the items of parallel_for; the counts are summed.
  auto run = [&](auto&& body, std::uint64_t count) {
    parallel_for(std::size_t(count), threads, [&](std::size_t i) {
      std::uint64_t r = 0, b = 0;
      body(std::uint64_t(i), r, b);
      rays += r, bad += b;
    });
  };

  // [listing mlt-bootstrap]
  // The bootstrap: b = mean of I over independent samples, and the discrete distribution of I
  // from which the chains' start states are drawn.
  std::vector<double> I(opt.bootstrap);
  run([&](std::uint64_t i, std::uint64_t& r, std::uint64_t& b) {
    rng g(seed, std::uint32_t(i), detail::bootstrap_stream);
    I[i] = mlt_sample(pt, cam, W, H, g, r, b).I;
  }, opt.bootstrap);
  std::vector<double> cdf(opt.bootstrap + 1, 0.0);
  for (std::uint64_t i = 0; i < opt.bootstrap; ++i) cdf[i + 1] = cdf[i] + I[i];
  metropolis_render_t out;
  out.b = cdf.back() / double(opt.bootstrap);
  out.bootstrap_seconds = clock.seconds();
  if (!(out.b > 0))
    throw error("metropolis: none of the " + std::to_string(opt.bootstrap) +
                " bootstrap samples carries light; the image would be black (a larger --bootstrap finds small lights)");
  // [end]

  // [listing mlt-chain]
  // Chain c: its share of the M mutations, splatted into its own film; the films are added to
  // the sum in chain order (a film waits for the ones before it).
  const std::uint64_t C = std::uint64_t(opt.chains);
  std::vector<vec3> sum(N, vec3(0));
  in_order<std::vector<vec3>> chain_films(C);
  std::vector<std::uint64_t> accepted(C, 0), proposed(C, 0), large_acc(C, 0), large_prop(C, 0);
  run([&](std::uint64_t c, std::uint64_t& r, std::uint64_t& b) {
    const std::uint64_t steps = M / C + (c < M % C ? 1 : 0);
    rng pick(seed, std::uint32_t(c), detail::select_stream);
    const double target = pick.uniform() * cdf.back();
    const std::uint64_t start = std::uint64_t(
        std::min<std::ptrdiff_t>(std::upper_bound(cdf.begin() + 1, cdf.end(), target) - cdf.begin() - 1,
                                 std::ptrdiff_t(opt.bootstrap - 1)));
    primary_sample_space u(rng(seed, std::uint32_t(start), detail::bootstrap_stream),
                           rng(seed, std::uint32_t(c), detail::chain_stream), opt.pss);
    rng g = rng::from(u);
    mlt_sample_t cur = mlt_sample(pt, cam, W, H, g, r, b);  // the bootstrap's sample again
    std::vector<vec3> film(N, vec3(0));
    auto splat = [&](const mlt_sample_t& s, double w) {
      if (w > 0 && s.I > 0) film[std::size_t(s.y) * std::size_t(W) + std::size_t(s.x)] += vec3(s.L) * (w / s.I);
    };
    for (std::uint64_t k = 0; k < steps; ++k) {
      u.start_step();
      g = rng::from(u);
      const mlt_sample_t next = mlt_sample(pt, cam, W, H, g, r, b);
      const double a = cur.I > 0 ? std::min(1.0, next.I / cur.I) : 1.0;
      splat(next, a);  // expected values: both states contribute, weighted by the acceptance
      splat(cur, 1 - a);
      const bool large = u.large_step();
      ++proposed[c], large_prop[c] += large;
      if (u.uniform() < a) {
        u.accept();
        cur = next;
        ++accepted[c], large_acc[c] += large;
      } else {
        u.reject();
      }
    }
    chain_films.put(c, std::move(film), [&](const std::vector<vec3>& f) {
      for (std::size_t i = 0; i < N; ++i) sum[i] += f[i];
    });
  }, C);
  // [end]

  if (chain_films.merged() != C)
    throw error("metropolis: internal error, " + std::to_string(C - chain_films.merged()) + " chains not merged");
  const double scale = out.b * double(N) / double(M);
  out.img = image(W, H);
  for (std::size_t i = 0; i < N; ++i) out.img.pixels[i] = rgb(sum[i] * scale);
  std::uint64_t acc = 0, prop = 0, lacc = 0, lprop = 0;
  for (std::uint64_t c = 0; c < C; ++c) acc += accepted[c], prop += proposed[c], lacc += large_acc[c], lprop += large_prop[c];
  out.mutations = prop;
  out.acceptance = prop ? double(acc) / double(prop) : 0;
  out.large_acceptance = lprop ? double(lacc) / double(lprop) : 0;
  out.small_acceptance = prop > lprop ? double(acc - lacc) / double(prop - lprop) : 0;
  out.seconds = clock.seconds();
  out.rays = rays.load(), out.nonfinite = bad.load();
  return out;
}

ZRAKA_INSTANCE(metropolis_render_t render_metropolis(const scene_t<double>&, const path_options&, std::uint64_t,
                                                    std::uint64_t, const metropolis_options&))  // compiled.hpp

}  // namespace zraka

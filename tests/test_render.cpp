#include <zraka/integrators/render.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>

using namespace zraka;

namespace {
// A noisy per-sample function with several random numbers per sample, like a path tracer's.
rgb noisy(sample_context& c) {
  c.rays += 2;
  const double a = c.random.uniform(), b = c.random.uniform();
  return rgb(float(std::sin(c.x * a) + b), float(c.y * b), float(a * b * c.sample));
}
bool same_bits(const image& a, const image& b) {
  return a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(rgb)) == 0;
}
}  // namespace

TEST_CASE("render: the same bits for 1, 2 and 3 threads and any tile size") {
  image ref(37, 23);  // sizes that are not multiples of any tile
  render_options o;
  o.threads = 1;
  o.progress = false;
  const render_stats s1 = render(ref, 5, 42, noisy, o);
  CHECK(s1.samples == 37u * 23u * 5u);
  CHECK(s1.rays == 2u * s1.samples);
  CHECK(s1.nonfinite == 0);
  for (int threads : {1, 2, 3})
    for (int tile : {1, 7, 16, 64}) {
      image img(37, 23);
      o.threads = threads;
      o.tile = tile;
      render(img, 5, 42, noisy, o);
      CHECK(same_bits(img, ref));
    }
  image other(37, 23);  // and a different seed gives a different image
  render(other, 5, 43, noisy, o);
  CHECK_FALSE(same_bits(other, ref));
}

TEST_CASE("render: NaN and infinite samples are counted per sample and left out") {
  image img(8, 4);
  render_options o;
  o.progress = false;
  o.threads = 2;
  // Pixel (0,0): samples 0 and 1 NaN, sample 2 inf, sample 3 = 1. Elsewhere every sample is 1.
  const render_stats s = render(img, 4, 1, [](sample_context& c) {
    if (c.x == 0 && c.y == 0 && c.sample < 2) return rgb(std::nanf(""));
    if (c.x == 0 && c.y == 0 && c.sample == 2) return rgb(INFINITY, 0.f, 0.f);
    return rgb(1);
  }, o);
  CHECK(s.nonfinite == 3);
  CHECK(img.count_nonfinite() == 0);
  CHECK(img.at(0, 0).x == 0.25f);  // one good sample of four: exact in binary
  CHECK(img.at(7, 3).x == 1.0f);
  CHECK(summary(img, 4, s).find("3 NaN/inf samples") != std::string::npos);
}

TEST_CASE("render: bad settings and exceptions in the sample function reach the caller") {
  image img(4, 4);
  render_options o;
  o.progress = false;
  auto one = [](sample_context&) { return rgb(1); };
  CHECK_THROWS_AS(render(img, 0, 1, one, o), error);
  o.threads = -1;
  CHECK_THROWS_AS(render(img, 1, 1, one, o), error);
  o.threads = 2;
  CHECK_THROWS_AS(render(img, 1, 1, [](sample_context& c) -> rgb {
    if (c.x == 3) throw error("boom");
    return rgb(0);
  }, o), error);
}

TEST_CASE("render: --threads beyond threads_per_core per core, and too many samples, are refused first") {
  const long long cap = max_threads();
  CHECK(cap == (long long)std::max(1u, std::thread::hardware_concurrency()) * 8);
  CHECK(resolve_threads(int(cap)) == cap);
  CHECK_THROWS_WITH_AS(resolve_threads(int(cap) + 1),
                       doctest::Contains("per core on this "), error);
  CHECK_THROWS_WITH_AS(resolve_threads(2147483647), doctest::Contains("(raise with --limit threads_per_core=N)"), error);
  image img(4, 4);
  render_options o;
  o.progress = false;
  int calls = 0;
  auto one = [&](sample_context&) { ++calls; return rgb(1); };
  const input_limits saved = limits();
  set_limit(limits(), "samples=16");
  CHECK_NOTHROW(render(img, 1, 1, one, o));
  CHECK_THROWS_WITH_AS(render(img, 2, 1, one, o),
                       "4x4 pixels at 2 spp are more samples than the limit of 16 (raise with --limit samples=N)", error);
  CHECK(calls == 16);  // the refused render did no work
  limits() = saved;
}

// links: yaml-cpp
// Metropolis light transport in primary sample space (pss.hpp, metropolis.hpp, book 6.4).
// The primary sample space: the start state is the bootstrap stream word for word, a rejected
// proposal restores every number, small steps move by sigma (and sigma sqrt(n) for a number
// left alone for n accepted steps), numbers stay in [0, 1) across the wrap at 0 and 1. The
// renderer: its mean image agrees with the `mis` path tracer region by region within 5 standard
// errors (batches with seeds of their own) on two Cornell boxes, its mean luminance is the
// bootstrap's b, it gives the same bits for 1 and 2 threads, and it refuses a black scene and
// bad options by name.
#include <zraka/app/reference.hpp>
#include <zraka/integrators/metropolis.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/sampling/pss.hpp>
#include <zraka/scene/cornell.hpp>

#include <doctest/doctest.h>

#include "region_stats.hpp"

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

using namespace zraka;
using namespace zraka_tests;

namespace {

double value_of(std::uint32_t word) { return double(word) * 0x1p-32; }
// The circular distance on [0, 1): a small step that wraps is small.
double circular(double a, double b) {
  const double d = std::abs(a - b);
  return std::min(d, 1 - d);
}

}  // namespace

TEST_CASE("pss: the start state is the start stream, word for word") {
  const rng start(7, 123, 4);
  primary_sample_space u(start, rng(7, 1, 2), {});
  rng a = start, g = rng::from(u);
  for (int d = 0; d < 50; ++d) CHECK(g.next_u32() == a.next_u32());
  // Asked again without a step, and out of order: the same numbers.
  rng b = start;
  b.skip_to(30);
  CHECK(u.number(30) == b.next_u32());
}

TEST_CASE("pss: a rejected proposal restores every number; an accepted one keeps them") {
  primary_sample_space u(rng(3), rng(4), {});
  std::vector<std::uint32_t> x0(20);
  for (std::uint32_t d = 0; d < 20; ++d) x0[d] = u.number(d);
  for (const bool large : {false, true}) {
    for (int tries = 0; tries < 50; ++tries) {  // until a step of the wanted kind comes
      u.start_step();
      if (u.large_step() == large) break;
      u.reject();
    }
    REQUIRE(u.large_step() == large);
    int moved = 0;
    for (std::uint32_t d = 0; d < 25; ++d) moved += d < 20 && u.number(d) != x0[d];  // 5 new numbers too
    CHECK(moved == 20);
    u.reject();
    for (std::uint32_t d = 0; d < 20; ++d) CHECK(u.number(d) == x0[d]);
  }
  u.start_step();
  std::vector<std::uint32_t> x1(20);
  for (std::uint32_t d = 0; d < 20; ++d) x1[d] = u.number(d);
  u.accept();
  for (std::uint32_t d = 0; d < 20; ++d) CHECK(u.number(d) == x1[d]);  // not moved again within the step
}

TEST_CASE("pss: small steps move by sigma, and by sigma sqrt(n) after n accepted steps unasked") {
  for (const double sigma : {0.01, 0.03}) {
    pss_options o;
    o.sigma = sigma;
    o.large_step_prob = 0;
    estimator one, sixteen;
    for (std::uint32_t chain = 0; chain < 400; ++chain) {
      primary_sample_space u(rng(11, chain), rng(12, chain), o);
      const double a0 = value_of(u.number(0)), b0 = value_of(u.number(1));
      u.start_step();
      const double a1 = value_of(u.number(0));
      u.accept();
      one.add(circular(a0, a1));
      // Number 1 is not asked for during 15 more accepted steps, then once: 16 steps in all.
      for (int k = 0; k < 15; ++k) {
        u.start_step();
        (void)u.number(0);
        u.accept();
      }
      u.start_step();
      sixteen.add(circular(b0, value_of(u.number(1))));
      u.accept();
    }
    // E|N(0, s^2)| = s sqrt(2 / pi); both within 10% (400 samples: se ~ 3.8%).
    const double k = std::sqrt(2 / std::numbers::pi);
    INFO("sigma " << sigma);
    CHECK(one.mean() == doctest::Approx(sigma * k).epsilon(0.1));
    CHECK(sixteen.mean() == doctest::Approx(4 * sigma * k).epsilon(0.1));
  }
}

TEST_CASE("pss: numbers stay in [0, 1) through the wrap, at sigma near 1 and start values at the ends") {
  pss_options o;
  o.sigma = 0.999;
  o.large_step_prob = 0.5;
  primary_sample_space u(rng(5), rng(6), o);
  for (int step = 0; step < 2000; ++step) {
    u.start_step();
    for (std::uint32_t d = 0; d < 8; ++d) {
      const double v = value_of(u.number(d));
      REQUIRE(v >= 0);
      REQUIRE(v < 1);
    }
    if (step % 3) u.accept();
    else u.reject();
  }
}

TEST_CASE("pss and metropolis: bad options are refused by name") {
  pss_options o;
  o.sigma = 0;
  CHECK_THROWS_WITH(primary_sample_space(rng(1), rng(2), o), doctest::Contains("sigma"));
  o.sigma = 0.01, o.large_step_prob = 1.5;
  CHECK_THROWS_WITH(primary_sample_space(rng(1), rng(2), o), doctest::Contains("large-step"));
  const scene sc = small(cornell_box<double>(cornell_variant::boxes), 8, 8);
  metropolis_options mo;
  mo.chains = 0;
  CHECK_THROWS_WITH(render_metropolis(sc, path_options{}, 1, 1, mo), doctest::Contains("--chains"));
  mo.chains = 4, mo.pss.sigma = std::nan("");
  CHECK_THROWS_WITH(render_metropolis(sc, path_options{}, 1, 1, mo), doctest::Contains("sigma"));
}

TEST_CASE("metropolis: a scene without light is refused, not rendered black") {
  scene dark = cornell_box<double>(cornell_variant::boxes);
  for (material& m : dark.materials) m.radiance = rgb(0);
  const scene sc = small(dark, 8, 8);
  metropolis_options mo;
  mo.bootstrap = 2000;
  mo.threads = 1;
  CHECK_THROWS_WITH(render_metropolis(sc, path_options{}, 1, 1, mo), doctest::Contains("carries light"));
}

TEST_CASE("metropolis: the same bits for 1 and 2 threads; the mean luminance is b") {
  const scene sc = small(cornell_box<double>(cornell_variant::glass), 12, 12);
  metropolis_options mo;
  mo.bootstrap = 4000;
  mo.chains = 8;
  path_options po;
  po.max_depth = 5;
  mo.threads = 1;
  const auto one = render_metropolis(sc, po, 8, 5, mo);
  mo.threads = 2;
  const auto two = render_metropolis(sc, po, 8, 5, mo);
  CHECK(one.img.pixels == two.img.pixels);
  CHECK(one.b == two.b);
  CHECK(one.nonfinite == 0);
  // Every splat is L / I(L) times b N / M, and the luminance of L / I is 1.
  double lum = 0;
  for (const rgb& p : one.img.pixels) lum += luminance(p);
  CHECK(lum / double(one.img.pixels.size()) == doctest::Approx(one.b).epsilon(1e-4));
  CHECK(one.acceptance > 0.05);
  CHECK(one.acceptance < 1);
}

TEST_CASE("metropolis: agrees with mis path tracing within 5 standard errors") {
  struct named {
    std::string name;
    scene sc;
  };
  const std::vector<named> scenes = {{"cornell boxes", small(cornell_box<double>(cornell_variant::boxes), 16, 16)},
                                     {"cornell glass (caustic)", small(cornell_box<double>(cornell_variant::glass), 16, 16)}};
  for (const auto& [name, sc] : scenes) {
    INFO(name);
    path_options po;
    po.max_depth = 5;
    render_options ro;
    ro.progress = false;
    metropolis_options mo;
    mo.threads = 2;
    mo.chains = 16;
    mo.bootstrap = 8 * 256;
    const region_stats mlt = batches(10, [&](std::uint64_t seed) {
      const auto r = render_metropolis(sc, po, 32, seed, mo);
      CHECK(r.nonfinite == 0);
      return r.img;
    });
    const region_stats mis = batches(10, [&](std::uint64_t seed) {
      render_stats st;
      return render_mis(sc, 32, seed + 1000, po, ro, st);
    });
    std::string report;
    const int bad = disagreements(mlt, mis, 5, report);
    INFO(report);
    CHECK(bad == 0);
  }
}

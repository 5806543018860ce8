#include <zraka/integrators/progressive.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <thread>

using namespace zraka;

namespace {
// A sample that depends only on its own random stream: uniform in [0, 1) per channel.
rgb noise(sample_context& c) { return rgb(float(c.random.uniform()), float(c.random.uniform()), 0.5f); }
}  // namespace

TEST_CASE("progressive: the passes double the samples and the result equals one render of N spp") {
  progressive_options po;
  po.max_spp = 20;  // 1, 2, 4, 8, 16, then 20: the last pass tops up
  po.seed = 7;
  po.render.progress = false;
  std::vector<int> seen;
  progressive_totals tot;
  const image prog = render_progressive(9, 7, po, noise, [&](const image&, const progressive_totals& t) {
    seen.push_back(t.spp);
  }, &tot);
  CHECK(seen == std::vector<int>{1, 2, 4, 8, 16, 20});
  CHECK(tot.spp == 20);
  CHECK(tot.stats.samples == 9u * 7u * 20u);
  image once(9, 7);
  render(once, 20, 7, noise, po.render);
  for (std::size_t i = 0; i < once.pixels.size(); ++i)  // the same samples, summed in passes:
    CHECK(glm::length(vec3(prog.pixels[i] - once.pixels[i])) < 1e-6);  // float rounding only
}

TEST_CASE("progressive: on_pass returning false stops; a time budget stops before a long pass") {
  progressive_options po;
  po.max_spp = 1 << 20;
  po.render.progress = false;
  int passes = 0;
  render_progressive(2, 2, po, noise, [&](const image&, const progressive_totals& t) { ++passes; return t.spp < 8; });
  CHECK(passes == 4);  // 1, 2, 4, 8

  po.time_budget = 0.05;  // each sample sleeps; the doubling must stop well before 2^20 spp
  progressive_totals tot;
  render_progressive(1, 1, po, [](sample_context& c) {
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    return noise(c);
  }, [](const image&, const progressive_totals&) {}, &tot);
  CHECK(tot.out_of_time);
  CHECK(tot.spp < 1024);
  CHECK(tot.seconds < 0.05 * 3);  // the skipped pass would have doubled the time; slack for load
}

TEST_CASE("progressive: seconds_to_reach interpolates between the bracketing passes") {
  convergence_log log("x", {"rmse"}, "rmse", "spp");
  log.add(1, 1.0, {0.4});
  log.add(2, 2.0, {0.2});
  log.add(4, 4.0, {0.1});
  // Between (2 s, 0.2) and (4 s, 0.1) error ~ 0.4/t, so 0.16 is reached at t = 2.5 s.
  CHECK(seconds_to_reach(log, 0.16) == doctest::Approx(2.5).epsilon(1e-12));
  CHECK(seconds_to_reach(log, 0.5) == 1.0);   // already there after the first pass
  CHECK(std::isnan(seconds_to_reach(log, 0.01)));  // never
  CHECK(seconds_to_reach(log, 0.1) == doctest::Approx(4.0).epsilon(1e-12));
}

TEST_CASE("progressive: bad settings are errors") {
  progressive_options po;
  po.max_spp = 0;
  CHECK_THROWS_AS(render_progressive(1, 1, po, noise, [](const image&, const progressive_totals&) {}), error);
  po.max_spp = 1;
  po.time_budget = -1;
  CHECK_THROWS_AS(render_progressive(1, 1, po, noise, [](const image&, const progressive_totals&) {}), error);
}

#include <zraka/sampling/pixel_sampling.hpp>

#include <doctest/doctest.h>

#include <vector>

using namespace zraka;

TEST_CASE("pixel_sampling: strata shapes") {
  CHECK(strata_for(1).nx == 1);
  CHECK(strata_for(16).nx == 4);
  CHECK(strata_for(16).ny == 4);
  CHECK(strata_for(8).nx == 2);
  CHECK(strata_for(8).ny == 4);
  CHECK(strata_for(7).nx == 1);
  CHECK(strata_for(7).ny == 7);
  CHECK_THROWS_AS(strata_for(0), error);
}

TEST_CASE("pixel_sampling: stratified positions hit every stratum exactly once, inside the pixel") {
  for (int n : {1, 2, 4, 7, 12, 16, 64, 1024}) {
    const strata s = strata_for(n);
    for (std::uint32_t pixel : {0u, 17u, 123456u}) {
      std::vector<int> count(n, 0);
      for (int k = 0; k < n; ++k) {
        rng g(99, pixel, std::uint32_t(k));
        const vec2 p = pixel_sample(pixel_pattern::stratified, k, n, g);
        REQUIRE(p.x >= 0.0);
        REQUIRE(p.x < 1.0);
        REQUIRE(p.y >= 0.0);
        REQUIRE(p.y < 1.0);
        const int i = int(p.x * s.nx), j = int(p.y * s.ny);
        ++count[j * s.nx + i];
      }
      for (int c : count) CHECK(c == 1);
    }
  }
}

TEST_CASE("pixel_sampling: regular is the cell centres, uniform stays in the pixel") {
  rng g(1);
  const vec2 c = pixel_sample(pixel_pattern::regular, 0, 1, g);
  CHECK(c == vec2(0.5, 0.5));
  const vec2 last = pixel_sample(pixel_pattern::regular, 15, 16, g);
  CHECK(last == vec2(0.875, 0.875));  // exact: (3 + 0.5) / 4
  double mean_x = 0;
  for (int k = 0; k < 4096; ++k) {
    rng gk(5, 0, std::uint32_t(k));
    const vec2 p = pixel_sample(pixel_pattern::uniform, k, 4096, gk);
    REQUIRE((p.x >= 0 && p.x < 1 && p.y >= 0 && p.y < 1));
    mean_x += p.x / 4096;
  }
  // Mean of 4096 uniforms: standard error 0.29 / 64 = 0.0045; 5 sigma.
  CHECK(mean_x == doctest::Approx(0.5).epsilon(0.045));
}

TEST_CASE("pixel_sampling: pattern names round-trip, bad names are an error") {
  for (pixel_pattern p : {pixel_pattern::regular, pixel_pattern::uniform, pixel_pattern::stratified})
    CHECK(parse_pixel_pattern(name(p)) == p);
  CHECK_THROWS_AS(parse_pixel_pattern("halton"), error);
}

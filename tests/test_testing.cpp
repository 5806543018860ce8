// Tests for testing.hpp: every check accepts a correct case and rejects a broken one (a wrong
// pdf, a biased mean, a shifted image, a wrong derivative or normal, a shape that re-hits
// itself), and its message names the measured numbers.
#include <zraka/app/testing.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/materials/microfacet.hpp>
#include <zraka/sampling/sampling.hpp>

#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <unistd.h>

using namespace zraka;
namespace zt = zraka::testing;

TEST_CASE("testing: chi-square accepts a sampler with its own pdf and rejects a wrong pdf") {
  rng g(1);
  auto sample = [&] { return sample_cosine_hemisphere(g.uniform2()); };
  const auto good = zt::directions_follow_pdf(
      sample, [](const vec3& w) { return cosine_hemisphere_pdf(w); }, 50000,
      direction_grid(10, 20));
  CHECK_MESSAGE(good.ok, good.message);
  CHECK(good.message.find("p = ") != std::string::npos);
  const auto wrong = zt::directions_follow_pdf(
      sample, [](const vec3& w) { return uniform_hemisphere_pdf(w); }, 50000,
      direction_grid(10, 20));
  CHECK_FALSE_MESSAGE(wrong.ok, wrong.message);
  // A sample where the pdf is zero (below the horizon) is named in the message.
  const auto below = zt::directions_follow_pdf([&] { return -sample(); },
      [](const vec3& w) { return cosine_hemisphere_pdf(w); }, 1000, direction_grid(10, 20));
  CHECK_FALSE(below.ok);
  CHECK(below.message.find("where the pdf is zero") != std::string::npos);
}

namespace {
// A GGX reflection sampler (visible normals, mirrored about the facet) and its pdf over
// directions, with pdf_scale and alpha_scale to make the pdf wrong on purpose. Directions below
// the horizon are rejected and have pdf 0, as a BRDF's would.
struct ggx_reflection {
  ggx_t<double> d;
  vec3 wo;
  double pdf_scale = 1, alpha_scale = 1;
  std::optional<vec3> sample(rng& g) const {
    const vec3 h = d.sample_visible(wo, g.uniform2());
    const vec3 wi = 2 * glm::dot(wo, h) * h - wo;
    if (!(wi.z > 0)) return std::nullopt;
    return wi;
  }
  double pdf(const vec3& wi) const {
    if (!(wi.z > 0)) return 0;
    const vec3 h = glm::normalize(wo + wi);
    const ggx_t<double> p(d.ax * alpha_scale);
    return pdf_scale * p.visible_pdf(wo, h) / (4 * std::abs(glm::dot(wo, h)));
  }
};
vec3 incident(double degrees) {
  const double t = degrees * pi<double> / 180;
  return {std::sin(t), 0, std::cos(t)};
}
}  // namespace

TEST_CASE("testing: a correct GGX sampler passes from alpha 0.001 to 1, normal to grazing; a 1% wrong pdf fails") {
  // The grid is the plain one an instructor would write; the adaptive quadrature of each bin
  // (expected_counts_adaptive) resolves lobes down to 1e-6 in cos theta. 20 tests: Sidak level.
  const double level = sidak_level(0.01, 20);
  const long n = 100000;
  const grid2 grid = direction_grid(16, 32);
  for (const double alpha : {0.001, 0.01, 0.1, 0.5, 1.0})
    for (const double deg : {0.0, 45.0, 80.0, 89.0}) {
      const ggx_reflection f{ggx_t<double>(alpha), incident(deg)};
      rng g(std::uint64_t(alpha * 1e4 + deg));
      const auto r = zt::directions_follow_pdf([&] { return f.sample(g); }, [&](const vec3& w) { return f.pdf(w); },
                                               n, grid, level);
      CHECK_MESSAGE(r.ok, "alpha " << alpha << ", " << deg << " deg: " << r.message);
    }
  // The pdf 1 % too large or too small everywhere, or its lobe 1 % narrower: each fails. At
  // alpha = 1 half of the samples go below the horizon and 1 % of the pdf's mass is 0.5 % of the
  // draws: a million of them make that 8 standard deviations of the rejected count.
  auto run = [&](double alpha, double deg, double pdf_scale, double alpha_scale, long draws, const grid2& bins) {
    const ggx_reflection f{ggx_t<double>(alpha), incident(deg), pdf_scale, alpha_scale};
    rng g(77);
    return zt::directions_follow_pdf([&] { return f.sample(g); }, [&](const vec3& w) { return f.pdf(w); }, draws,
                                     bins, level);
  };
  for (const double alpha : {0.001, 0.1, 1.0}) {
    const long draws = alpha == 1 ? 1000000 : n;
    const auto big = run(alpha, 30, 1.01, 1, draws, grid);
    CHECK_FALSE_MESSAGE(big.ok, "alpha " << alpha << ": " << big.message);
    // All of the narrow lobe is above the horizon: its integral is 1.01.
    if (alpha == 0.001)
      CHECK_MESSAGE(big.message.find("integrates to 1.01 over the grid, more than 1") != std::string::npos, big.message);
    const auto small = run(alpha, 30, 0.99, 1, draws, grid);
    CHECK_FALSE_MESSAGE(small.ok, "alpha " << alpha << ": " << small.message);
  }
  for (const double alpha : {0.1, 1.0}) {
    const auto narrow = run(alpha, 30, 1, 0.99, 1000000, grid);
    CHECK_FALSE_MESSAGE(narrow.ok, "alpha " << alpha << ": " << narrow.message);
  }
  // A shape error inside one bin is invisible to the test: at alpha = 0.001 the whole lobe is in
  // one bin of the grid above. A grid on the lobe sees it (at normal incidence the lobe is
  // 2 alpha^2 wide in 1 - cos theta; what lies beyond 50 alpha^2, 4 % of the mass, is the extra bin).
  const grid2 cap = direction_grid(16, 4, 1 - 50 * 0.001 * 0.001);
  const auto right = run(0.001, 0, 1, 1, n, cap);
  CHECK_MESSAGE(right.ok, right.message);
  const auto narrow = run(0.001, 0, 1, 0.99, 1000000, cap);
  CHECK_FALSE_MESSAGE(narrow.ok, narrow.message);
}

TEST_CASE("testing: a sampler that returns nothing is named as such, not as a zero pdf") {
  rng g(5);
  const auto none = zt::directions_follow_pdf([&]() -> std::optional<vec3> { return std::nullopt; },
                                              [](const vec3& w) { return cosine_hemisphere_pdf(w); }, 1000,
                                              direction_grid(10, 20));
  CHECK_FALSE(none.ok);
  CHECK_MESSAGE(none.message.find("returned no sample in 1000 draws") != std::string::npos, none.message);
  CHECK_MESSAGE(none.message.find("pdf is zero") == std::string::npos, none.message);
  // A zero vector is a rejection too.
  const auto zero = zt::directions_follow_pdf([&] { return vec3(0); },
                                              [](const vec3& w) { return cosine_hemisphere_pdf(w); }, 1000,
                                              direction_grid(10, 20));
  CHECK_FALSE(zero.ok);
  CHECK(zero.message.find("returned no sample") != std::string::npos);
}

TEST_CASE("testing: a 2D sampler against its density") {
  rng g(2);
  const grid2 grid{8, 1, 0, 2, 0, 1};
  auto sample = [&] { return std::optional<vec2>(vec2(sample_linear(g.uniform()), 0.5)); };
  const auto good = zt::samples_follow_density(sample, [](double x, double) { return linear_pdf(x); },
                                               20000, grid);
  CHECK_MESSAGE(good.ok, good.message);
  const auto wrong = zt::samples_follow_density(sample, [](double, double) { return 0.5; }, 20000, grid);
  CHECK_FALSE_MESSAGE(wrong.ok, wrong.message);
}

TEST_CASE("testing: the integral of a pdf over the sphere") {
  // Midpoint rule on 100 x 4 bins of 8 x 8 points: the cosine lobe is linear in cos theta, so
  // the rule is exact up to rounding (1e-12).
  CHECK(zt::pdf_integral_over_directions([](const vec3& w) { return cosine_hemisphere_pdf(w); },
                                         100, 4) == doctest::Approx(1).epsilon(1e-12));
  CHECK(zt::pdf_integral_over_directions([](const vec3&) { return uniform_sphere_pdf<double>(); },
                                         10, 4) == doctest::Approx(1).epsilon(1e-12));
  // A pdf of the wrong constant integrates to that factor.
  CHECK(zt::pdf_integral_over_directions([](const vec3&) { return 1.0 / (2 * pi<double>); }, 10,
                                         4) == doctest::Approx(2).epsilon(1e-12));
}

TEST_CASE("testing: mean within k standard errors") {
  rng g(3);
  const auto good = zt::mean_within([&] { return g.uniform(); }, 100000, 0.5);
  CHECK_MESSAGE(good.ok, good.message);
  // A bias of 0.01 is 11 standard errors (sigma = 0.289, n = 1e5, se = 9.1e-4).
  const auto biased = zt::mean_within([&] { return g.uniform() + 0.01; }, 100000, 0.5);
  CHECK_FALSE_MESSAGE(biased.ok, biased.message);
  CHECK(biased.message.find("standard errors") != std::string::npos);
  // Zero variance: exact to a few roundings, else rejected.
  CHECK(zt::mean_within([] { return 0.25; }, 10, 0.25).ok);
  CHECK_FALSE(zt::mean_within([] { return 0.25; }, 10, 0.2500001).ok);
  // NaN samples, or too few, never pass.
  CHECK_FALSE(zt::mean_within([] { return std::nan(""); }, 10, 0.0).ok);
  CHECK_FALSE(zt::mean_within([] { return 1.0; }, 1, 1.0).ok);
}

namespace {
image gradient(int w, int h, int shift = 0) {
  image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      img.at(x, y) = rgb(float((x + shift) % w) / float(w), float(y) / float(h), 0.25f);
  return img;
}
}  // namespace

TEST_CASE("testing: image comparison") {
  const image ref = gradient(32, 16);
  const zt::image_tolerance tol;  // RMSE 0.01, channel mean 0.005, no max limit
  CHECK(zt::images_match(ref, ref, tol).ok);
  // Shifted by 3 pixels: the means stay (a permutation of columns) but RMSE is large.
  const auto shifted = zt::images_match(gradient(32, 16, 3), ref, tol);
  CHECK_FALSE_MESSAGE(shifted.ok, shifted.message);
  // Brighter by 0.01 everywhere: RMSE 0.0082 passes, the channel mean shift 0.01 does not.
  image brighter = ref;
  for (rgb& p : brighter.pixels) p += rgb(0.01f);
  const auto bright = zt::images_match(brighter, ref, tol);
  CHECK_FALSE_MESSAGE(bright.ok, bright.message);
  // One hot pixel: only max_abs catches it.
  // One hot pixel: only max_abs catches it (on 64 x 32 pixels, +0.3 in one pixel is an RMSE
  // of 0.3 / sqrt(2048) = 0.0066).
  const image big = gradient(64, 32);
  image hot = big;
  hot.at(5, 5) += rgb(0.3f);
  CHECK(zt::images_match(hot, big, tol).ok);
  CHECK_FALSE(zt::images_match(hot, big, {0.01, 0.005, 0.1}).ok);
  // Size and NaN.
  CHECK_FALSE(zt::images_match(gradient(16, 16), ref, tol).ok);
  image nan_img = ref;
  nan_img.at(0, 0).x = std::nanf("");
  CHECK_FALSE(zt::images_match(nan_img, ref, tol).ok);
}

TEST_CASE("testing: image comparison against PFM and PNG files") {
  const image ref = gradient(24, 12);
  const std::filesystem::path pfm = "test_testing_ref.pfm", png = "test_testing_ref.png";
  write_pfm(ref, pfm);
  write_png(ref, png);
  const zt::image_tolerance exact{1e-7, 1e-7, 1e-7};  // the same image round-trips exactly
  const auto a = zt::image_matches_file(ref, pfm, exact);
  CHECK_MESSAGE(a.ok, a.message);
  const auto b = zt::image_matches_file(ref, png, exact);  // compared as 8-bit display values
  CHECK_MESSAGE(b.ok, b.message);
  CHECK_FALSE(zt::image_matches_file(gradient(24, 12, 2), png, {}).ok);
  const auto missing = zt::image_matches_file(ref, "no_such_file.png", {});
  CHECK_FALSE(missing.ok);
  CHECK(missing.message.find("no_such_file") != std::string::npos);
  std::filesystem::remove(pfm);
  std::filesystem::remove(png);
}

TEST_CASE_TEMPLATE("testing: derivatives by central differences", T, float, double) {
  // Tolerance: the central difference's error is about cbrt(eps)^2 relative, 4e-11 in double
  // and 1.5e-5 in float, but in float at x = 1000 sin's argument is only known to eps |x|,
  // which measures 6e-4; 1e-3 still rejects a 1% error.
  const double tol = 1e-3;
  const std::vector<T> xs = {T(-3), T(-0.5), T(0), T(0.7), T(2), T(1000), T(-12345.5)};
  auto f = [](T x) { return std::sin(x) + x * x / T(2); };
  auto df = [](T x) { return std::cos(x) + x; };
  const auto good = zt::derivative_matches(f, df, xs, tol);
  CHECK_MESSAGE(good.ok, good.message);
  const auto wrong = zt::derivative_matches(f, [&](T x) { return df(x) * T(1.01); }, xs, tol);
  CHECK_FALSE_MESSAGE(wrong.ok, wrong.message);
  // A curve in space (a helix) and its tangent, at parameters of order one: the step is
  // relative to max(1, |x|), too coarse for a function that turns within |x| cbrt(eps).
  const std::vector<T> ss = {T(-3), T(-0.5), T(0), T(0.7), T(2)};
  auto curve = [](T s) { return vec3_t<T>(std::cos(s), std::sin(s), s / T(3)); };
  auto tangent = [](T s) { return vec3_t<T>(-std::sin(s), std::cos(s), T(1) / T(3)); };
  CHECK(zt::derivative_matches(curve, tangent, ss, tol).ok);
  CHECK_FALSE(zt::derivative_matches(curve, [&](T s) { return -tangent(s); }, ss, tol).ok);
  // A NaN derivative is never accepted.
  CHECK_FALSE(zt::derivative_matches(f, [](T) { return std::numeric_limits<T>::quiet_NaN(); }, xs, tol).ok);
}

namespace {
// Rays from a random point on a shell around the sphere towards a random point of the sphere.
template <class T> auto aim_at_sphere(const sphere_t<T>& s) {
  return [s](rng& g) {
    const vec3 from = vec3(s.center) + double(s.radius) * 3.0 * sample_uniform_sphere(g.uniform2());
    const vec3 to = vec3(s.center) + 0.9 * double(s.radius) * sample_uniform_sphere(g.uniform2());
    return ray_t<T>(vec3_t<T>(from), vec3_t<T>(to - from));
  };
}
}  // namespace

TEST_CASE_TEMPLATE("testing: surface normals by finite differences", T, float, double) {
  for (const T scale : {T(1e-3), T(1), T(1e3)}) {
    const sphere_t<T> s{vec3_t<T>(T(2) * scale, T(-1) * scale, T(0.5) * scale), scale};
    auto isect = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) { return intersect(s, r, t0, t1, h); };
    // Tolerance 1 degree: the four neighbours are cbrt(eps) radii apart, so curvature tilts the
    // finite-difference normal by about cbrt(eps)^2 radians, and rounding by eps/cbrt(eps).
    const auto good = zt::normal_matches_surface(isect, aim_at_sphere(s), 200, scale, 1.0);
    CHECK_MESSAGE(good.ok, good.message);
    // A wrong normal: measured from a point beside the centre.
    auto wrong = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) {
      if (!intersect(s, r, t0, t1, h)) return false;
      h.normal = glm::normalize(h.p - s.center - vec3_t<T>(T(0.3) * scale, 0, 0));
      return true;
    };
    const auto bad = zt::normal_matches_surface(wrong, aim_at_sphere(s), 200, scale, 1.0);
    CHECK_FALSE_MESSAGE(bad.ok, bad.message);
    // A normal that is not unit length.
    auto longer = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) {
      if (!intersect(s, r, t0, t1, h)) return false;
      h.normal *= T(2);
      return true;
    };
    CHECK_FALSE(zt::normal_matches_surface(longer, aim_at_sphere(s), 50, scale, 1.0).ok);
  }
}

TEST_CASE_TEMPLATE("testing: the reintersection check across scales", T, float, double) {
  std::vector<zt::result> good, no_error, no_tmin;
  for (const double e : {-4.0, -1.0, 0.0, 2.0, 4.0}) {
    const T scale = T(std::pow(10.0, e));
    const sphere_t<T> s{vec3_t<T>(T(3), T(-2), T(1)) * scale * T(7), scale};
    auto isect = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) { return intersect(s, r, t0, t1, h); };
    good.push_back(zt::no_self_hits<T>(isect, aim_at_sphere(s), 500));
    // Broken 1: the shape claims its hit points are exact, so spawn_ray does not move them.
    auto exact = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) {
      if (!intersect(s, r, t0, t1, h)) return false;
      h.p_error = vec3_t<T>(0);
      return true;
    };
    no_error.push_back(zt::no_self_hits<T>(exact, aim_at_sphere(s), 500));
    // Broken 2: t_min is ignored, so a hit a rounding behind the origin counts.
    auto any_t = [&](const ray_t<T>& r, T, T t1, hit_t<T>& h) {
      return intersect(s, r, -infinity<T>, t1, h);
    };
    no_tmin.push_back(zt::no_self_hits<T>(any_t, aim_at_sphere(s), 500));
  }
  const auto all_good = zt::all_of(good);
  CHECK_MESSAGE(all_good.ok, all_good.message);
  const auto r1 = zt::all_of(no_error), r2 = zt::all_of(no_tmin);
  CHECK_FALSE_MESSAGE(r1.ok, r1.message);
  CHECK_FALSE_MESSAGE(r2.ok, r2.message);
  // Every scale catches the broken t_min (the origin sits on the surface, half the rays re-hit).
  for (const auto& r : no_tmin) CHECK_FALSE_MESSAGE(r.ok, r.message);
  // across_scales names the scale of each line.
  const auto scaled = zt::across_scales(std::vector<T>{T(1), T(100)}, [](T s) {
    return zt::result{s < T(10), "measured"};
  });
  CHECK_FALSE(scaled.ok);
  CHECK(scaled.message == "ok: scale 1: measured\nFAILED: scale 100: measured");
  // An aim that misses is reported, not silently passed.
  const sphere_t<T> s{vec3_t<T>(0), T(1)};
  auto isect = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) { return intersect(s, r, t0, t1, h); };
  const auto away = zt::no_self_hits<T>(isect, [](rng&) { return ray_t<T>(vec3_t<T>(0, 0, 5), vec3_t<T>(0, 0, 1)); }, 50);
  CHECK_FALSE(away.ok);
  CHECK(away.message.find("check aim()") != std::string::npos);
}

TEST_CASE("testing: a reference PNG is a regular file, and its claimed size is checked before decoding") {
  namespace fs = std::filesystem;
  const fs::path p = fs::temp_directory_path() / ("zraka-test-testing-claims-" + std::to_string(::getpid()) + ".png");
  // The 8-byte signature and an IHDR chunk that claims 8192 x 8192 RGB: 33 bytes, 200 MB decoded.
  std::string png = "\x89PNG\r\n\x1a\n";
  png += std::string("\0\0\0\x0d", 4) + "IHDR" + std::string("\0\0\x20\0\0\0\x20\0\x08\x02\0\0\0", 13) + "CRC!";
  std::ofstream(p, std::ios::binary) << png;
  CHECK_THROWS_WITH_AS(zt::read_png_display(p),
                       ("cannot read PNG " + p.string() + ": the image size 8192x8192 in pixels is 67108864, more than the limit of 16777216 "
                                     "(raise with --limit pixels=N)").c_str(),
                       error);
  fs::remove(p);
  CHECK_THROWS_WITH_AS(zt::read_png_display("/dev/zero"), "/dev/zero: is a character device; only regular files are read",
                       error);
}

TEST_CASE("testing: noise_floor measures the seed-to-seed difference and passes a correct render") {
  // A "render" of pure noise: 0.5 + U(-a, a) per channel, sigma = a / sqrt(3). Two independent
  // renders differ by sqrt(2) sigma in RMSE.
  const double a = 0.1;
  auto render = [&](std::uint64_t seed, double shift = 0) {
    zraka::image img(64, 64);
    zraka::rng g(seed);
    for (auto& p : img.pixels)
      for (int c = 0; c < 3; ++c) p[c] = float(0.5 + shift + a * (2 * g.uniform() - 1));
    return img;
  };
  const auto floor = zt::noise_floor([&](std::uint64_t s) { return render(s); }, 4, 2.0);
  INFO(floor.message);
  const double expected = std::sqrt(2.0) * a / std::sqrt(3.0);
  CHECK(floor.seeds == 4);
  CHECK(std::abs(floor.floor.rmse - expected) < 0.03 * expected);  // 12,288 values: ~1% spread
  CHECK(floor.tolerance.rmse == doctest::Approx(2 * floor.floor.rmse));
  CHECK(floor.tolerance.channel_mean == doctest::Approx(2 * floor.floor.channel_mean));
  CHECK(floor.floor.max_abs <= 2 * a);
  CHECK(zt::images_match(render(99), render(1), floor.tolerance).ok);  // a new seed passes
  // A bias of ten times the channel-mean floor fails.
  CHECK_FALSE(zt::images_match(render(99, 10 * floor.floor.channel_mean + 0.01), render(1), floor.tolerance).ok);
  // A noiseless render: a zero floor, which only the same image meets.
  const auto exact = zt::noise_floor([&](std::uint64_t) { return render(5); }, 2);
  CHECK(exact.floor.rmse == 0);
  CHECK(zt::images_match(render(5), render(5), exact.tolerance).ok);
  CHECK_THROWS_AS(zt::noise_floor([&](std::uint64_t s) { return render(s); }, 1), zraka::error);
  CHECK_THROWS_AS(zt::noise_floor([&](std::uint64_t s) { return render(s); }, 4, 0.5), zraka::error);
}

#include <zraka/integrators.hpp>
#include <zraka/path.hpp>

#include <doctest/doctest.h>

using namespace zraka;

TEST_CASE("path: a convex Lambertian ball under a uniform sky returns albedo x sky exactly") {
  // Every bounce direction leaves the convex ball and sees the sky: each path is a * L_sky.
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::lambertian(rgb(0.25f, 0.5f, 0.75f))));
  sc.background = rgb(2);
  for (int i = 0; i < 200; ++i) {
    rng g(1, 0, std::uint32_t(i));
    std::uint64_t rays = 0;
    const rgb L = path_radiance(sc, ray({0.1, 0.2, 5}, {0, 0, -1}), g, path_options{}, rays);
    CHECK(L.x == doctest::Approx(0.5).epsilon(1e-6));  // float products of binary fractions
    CHECK(L.z == doctest::Approx(1.5).epsilon(1e-6));
    CHECK(rays == 2);
  }
}

TEST_CASE("path: next-event estimation and naive path tracing agree on the mean") {
  scene sc;
  const int grey = sc.add_material(material::lambertian(rgb(0.6f)));
  const int lamp = sc.add_material(material::emitter(rgb(10)));
  sc.add(quad{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, grey);        // floor, up
  sc.add(sphere{{0, 0.5, 0}, 0.5}, grey);
  sc.add(quad{{-0.5, 2, -0.5}, {1, 0, 0}, {0, 0, 1}}, lamp);    // light, down
  const ray cam({0.7, 0.8, 2.5}, vec3(0.9, 0.0, 0.3) - vec3(0.7, 0.8, 2.5));  // looks at the floor
  auto estimate = [&](bool nee, int n, double& se) {
    path_options o;
    o.next_event = nee;
    o.max_depth = 4;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      rng g(nee ? 3 : 4, 0, std::uint32_t(i));
      std::uint64_t rays = 0;
      const double v = path_radiance(sc, cam, g, o, rays).x;
      REQUIRE(std::isfinite(v));
      sum += v;
      sum2 += v * v;
    }
    const double mean = sum / n;
    se = std::sqrt((sum2 / n - mean * mean) / n);
    return mean;
  };
  double se_nee = 0, se_naive = 0;
  const double nee = estimate(true, 20000, se_nee), naive = estimate(false, 200000, se_naive);
  INFO("NEE " << nee << " +- " << se_nee << ", naive " << naive << " +- " << se_naive);
  CHECK(nee > 0.05);
  // 5 combined standard errors: the two are independent unbiased estimates of one value.
  CHECK(std::abs(nee - naive) < 5 * std::sqrt(se_nee * se_nee + se_naive * se_naive));
  CHECK(se_nee < se_naive * std::sqrt(10.0));  // NEE with 10x fewer samples is still less noisy
}

TEST_CASE("path: path_radiance (next_event on) and the nee integrator estimate the same value") {
  // path.hpp's compact tracer and integrators.hpp's nee share the algorithm; their means at one
  // floor point under a quad light must agree within 5 combined standard errors.
  scene sc;
  const int grey = sc.add_material(material::lambertian(rgb(0.6f)));
  sc.add(quad{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, grey);
  sc.add(quad{{-0.5, 2, -0.5}, {1, 0, 0}, {0, 0, 1}}, sc.add_material(material::emitter(rgb(10))));
  const ray cam({0.7, 0.8, 2.5}, vec3(0.3, 0.0, 0.3) - vec3(0.7, 0.8, 2.5));
  integrator_options io;
  io.method = integrator::nee;
  io.max_depth = 4;
  const path_tracer tracer(sc, io);
  path_options po;
  po.max_depth = 4;
  double s[2] = {0, 0}, s2[2] = {0, 0};
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    std::uint64_t rays = 0;
    rng g0(1, 0, std::uint32_t(i)), g1(2, 0, std::uint32_t(i));
    const double a = path_radiance(sc, cam, g0, po, rays).x, b = tracer(cam, g1, rays).x;
    s[0] += a, s2[0] += a * a, s[1] += b, s2[1] += b * b;
  }
  const double m0 = s[0] / n, m1 = s[1] / n;
  const double se = std::sqrt((s2[0] / n - m0 * m0) / n + (s2[1] / n - m1 * m1) / n);
  INFO("path_radiance " << m0 << ", nee " << m1 << ", combined se " << se);
  CHECK(std::abs(m0 - m1) < 5 * se);
}

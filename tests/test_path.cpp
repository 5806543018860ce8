#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/scene/cornell.hpp>

#include <doctest/doctest.h>

#include <cmath>

using namespace zraka;

namespace {

// Mean and standard error of n independent path samples (the sum of the channels) along rays
// made by ray_of(i, g).
struct mean_se {
  double mean = 0, se = 0;
};
template <class T, class RayOf>
mean_se estimate(const scene_t<T>& sc, path_options o, int n, std::uint64_t seed, RayOf ray_of,
                 std::uint64_t* rays_out = nullptr) {
  const path_tracer_t<T> tracer(sc, o);
  double sum = 0, sum2 = 0;
  std::uint64_t rays = 0;
  for (int i = 0; i < n; ++i) {
    rng g(seed, 0, std::uint32_t(i));
    const ray_t<T> r = ray_of(g);
    const rgb L = tracer(r, g, rays);
    const double v = double(L.x) + L.y + L.z;
    REQUIRE(std::isfinite(v));
    sum += v, sum2 += v * v;
  }
  if (rays_out) *rays_out = rays;
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

template <class T> scene_t<T> furnace(float albedo, float Le) {
  scene_t<T> sc;
  material m = material::lambertian(rgb(albedo));
  m.radiance = rgb(Le);
  m.two_sided = true;  // the camera is inside
  sc.add(sphere_t<T>{vec3_t<T>(0), T(1)}, sc.add_material(m));
  return sc;
}

// Rays from a fixed point inside the unit sphere, in uniformly random directions.
template <class T> auto inside_rays() {
  return [](rng& g) { return ray_t<T>(vec3_t<T>(0.2, -0.1, 0.3), sample_uniform_sphere(vec2_t<T>(g.uniform2()))); };
}

// Camera rays through random points of a small image of the scene.
template <class T> auto camera_rays(const scene_t<T>& sc) {
  return [cam = sc.prepared_camera()](rng& g) { return cam.generate(T(g.uniform()), T(g.uniform())); };
}

const integrator all_methods[] = {integrator::naive, integrator::nee, integrator::mis};

}  // namespace

TEST_CASE("path: a convex Lambertian ball under a uniform sky returns albedo x sky exactly") {
  // Every bounce direction leaves the convex ball and sees the sky: each path is a * L_sky.
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::lambertian(rgb(0.25f, 0.5f, 0.75f))));
  sc.background = rgb(2);
  for (integrator m : all_methods) {
    path_options o;
    o.method = m;
    const path_tracer tracer(sc, o);
    for (int i = 0; i < 200; ++i) {
      rng g(1, 0, std::uint32_t(i));
      std::uint64_t rays = 0;
      const rgb L = tracer(ray({0.1, 0.2, 5}, {0, 0, -1}), g, rays);
      CHECK(L.x == doctest::Approx(0.5).epsilon(1e-6));  // float products of binary fractions
      CHECK(L.z == doctest::Approx(1.5).epsilon(1e-6));
      CHECK(rays == 2);  // no light to sample: no shadow ray
    }
  }
}

TEST_CASE("path: naive refuses point lights by name; nee and mis see them") {
  scene sc;
  sc.add(quad{{-5, 0, 5}, {10, 0, 0}, {0, 0, -10}}, sc.add_material(material::lambertian(rgb(0.5f))));
  sc.add(point_light_t<double>{{0, 2, 0}, rgb(8)});
  path_options o;
  o.method = integrator::naive;
  CHECK_THROWS_WITH_AS(path_tracer(sc, o), doctest::Contains("point light"), error);
  // E = I / d^2 = 2 at the origin, L = rho/pi E = 1/pi; depth 0 bounces after the floor: direct only.
  for (integrator m : {integrator::nee, integrator::mis}) {
    o.method = m;
    o.max_depth = 1;
    const path_tracer tracer(sc, o);
    rng g(2);
    std::uint64_t rays = 0;
    const rgb L = tracer(ray({0, 1, 1}, vec3(0, -1, -1)), g, rays);
    CHECK(L.x == doctest::Approx(1.0 / pi<double>).epsilon(1e-6));
  }
}

TEST_CASE_TEMPLATE("path: white furnace, camera inside a glowing sphere, gives Le/(1-a)", T, float, double) {
  // Every bounce sees Le, weighted a^k: L = Le sum a^k = Le/(1-a) = 2 for a = 1/2, Le = 1; with
  // 40 bounces the truncated tail a^41 is 5e-13, far below the noise.
  const auto sc = furnace<T>(0.5f, 1.0f);
  for (integrator m : all_methods) {
    path_options o;
    o.method = m;
    o.max_depth = 40;
    const mean_se e = estimate(sc, o, 20000, 11, inside_rays<T>());
    INFO(name(m) << ": " << e.mean / 3 << " +- " << e.se / 3);
    // 5 standard errors (a 1 in 2 million chance for a correct estimator), and within 1% as a
    // plain bound in case the standard error itself were wrongly tiny.
    CHECK(std::abs(e.mean / 3 - 2.0) < 5 * e.se / 3 + 1e-6);
    CHECK(std::abs(e.mean / 3 - 2.0) < 0.02);
  }
}

TEST_CASE("path: furnace with the depth cut at D bounces gives Le (1 - a^(D+1)) / (1 - a)") {
  // No Russian roulette (rr_depth beyond the depth): the naive path then has no randomness left
  // in a furnace (every bounce finds Le), so the result is exact to float rounding.
  const auto sc = furnace<double>(0.8f, 1.0f);
  for (int D : {0, 1, 2, 5}) {
    path_options o;
    o.method = integrator::naive;
    o.max_depth = D;
    o.rr_depth = 100;
    const mean_se e = estimate(sc, o, 200, 3, inside_rays<double>());
    const double expected = (1 - std::pow(0.8, D + 1)) / (1 - 0.8);
    CHECK(e.mean / 3 == doctest::Approx(expected).epsilon(1e-5));  // float sums of <= 6 terms
    CHECK(e.se < 1e-6);
  }
}

TEST_CASE("path: a floor under a spherical light has radiance rho Le (r/d)^2") {
  // A sphere of radius r whose centre is d above the point sees it fully above the horizon:
  // irradiance E = pi Le (r/d)^2, so a Lambertian floor reflects L = rho/pi E = rho Le r^2/d^2.
  // The light is black (emitters do not reflect), so there is no other light path.
  scene sc;
  const float rho = 0.6f, Le = 5.0f;
  const double r = 0.5, d = 2.0;
  sc.add(quad{{-50, 0, 50}, {100, 0, 0}, {0, 0, -100}}, sc.add_material(material::lambertian(rgb(rho))));
  sc.add(sphere{{0, d, 0}, r}, sc.add_material(material::emitter(rgb(Le))));
  const double expected = 3 * rho * Le * r * r / (d * d);  // summed over the 3 channels
  auto at_origin = [](rng&) { return ray({0.3, 1.0, 1.0}, vec3(0, 0, 0) - vec3(0.3, 1.0, 1.0)); };
  for (integrator m : all_methods) {
    path_options o;
    o.method = m;
    const mean_se e = estimate(sc, o, m == integrator::naive ? 100000 : 20000, 5, at_origin);
    INFO(name(m) << ": " << e.mean << " +- " << e.se << ", expected " << expected);
    CHECK(std::abs(e.mean - expected) < 5 * e.se + 1e-9);  // 5 standard errors
  }
  // Light sampling of a sphere covers exactly its cone: every sample hits, NEE alone has no
  // variance left but the cosine's over the small cone (here under 1%).
  path_options o;
  o.method = integrator::nee;
  const mean_se e = estimate(sc, o, 2000, 6, at_origin);
  CHECK(e.mean == doctest::Approx(expected).epsilon(0.01));
}

TEST_CASE("path: naive, nee and mis agree on the mean in the Cornell boxes") {
  // Each estimates the mean image radiance (random pixels) independently; their differences must
  // lie within 5 combined standard errors. (Most of the spread here is from pixel to pixel: the
  // light itself is in view. The noise of the integrators alone is compared below.)
  for (cornell_variant v : {cornell_variant::boxes, cornell_variant::spheres}) {
    const scene sc = cornell_box<double>(v);
    mean_se e[3];
    for (int i = 0; i < 3; ++i) {
      path_options o;
      o.method = all_methods[i];
      o.max_depth = 6;
      e[i] = estimate(sc, o, i == 0 ? 100000 : 40000, 20 + std::uint64_t(i), camera_rays(sc));
      MESSAGE(std::string(name(v)) << " " << std::string(name(all_methods[i])) << ": " << e[i].mean << " +- " << e[i].se);
    }
    for (int i = 0; i < 3; ++i)
      for (int j = i + 1; j < 3; ++j)
        CHECK(std::abs(e[i].mean - e[j].mean) < 5 * std::hypot(e[i].se, e[j].se));
  }
}

TEST_CASE("path: at one pixel of the Cornell box, nee and mis are far less noisy than naive") {
  // The floor in front of the tall box: the per-sample standard deviation, se sqrt(n).
  const scene sc = cornell_box<double>(cornell_variant::boxes);
  const auto cam = sc.prepared_camera();
  auto floor_pixel = [&](rng&) { return cam.generate(0.4, 0.85); };
  double sd[3];
  for (int i = 0; i < 3; ++i) {
    path_options o;
    o.method = all_methods[i];
    sd[i] = estimate(sc, o, 20000, 30 + std::uint64_t(i), floor_pixel).se * std::sqrt(20000.0);
    MESSAGE(std::string(name(all_methods[i])) << ": standard deviation per sample " << sd[i]);
  }
  CHECK(sd[1] < sd[0] / 2);  // measured: about a quarter (variance 16x lower)
  CHECK(sd[2] < sd[0] / 2);
}

TEST_CASE("path: the power heuristic's two weights sum to one, also at extremes") {
  for (double a : {1e-300, 1e-3, 1.0, 7.0, 1e150, 1e300})
    for (double b : {0.0, 1e-300, 0.5, 1.0, 1e300}) {
      const double w = power_heuristic(a, b) + power_heuristic(b, a);
      if (b > 0) CHECK(w == doctest::Approx(1.0).epsilon(1e-12));  // a few roundings
      CHECK(std::isfinite(power_heuristic(a, b)));
    }
  CHECK(power_heuristic(1.0, 0.0) == 1.0);
  CHECK(power_heuristic(0.0, 1.0) == 0.0);
  CHECK(power_heuristic(infinity<double>, 1.0) == 1.0);
}

TEST_CASE("path: no NaN or infinite samples, and rays are counted") {
  for (cornell_variant v : {cornell_variant::boxes, cornell_variant::glass, cornell_variant::spheres})
    for (integrator m : all_methods) {
      const scene sc = cornell_box<double>(v);
      path_options o;
      o.method = m;
      const path_tracer tracer(sc, o);
      const auto cam = sc.prepared_camera();
      image img(16, 16);
      render_options ro;
      ro.progress = false;
      const render_stats s = render(img, 4, 1, [&](sample_context& c) {
        return tracer(cam.generate((c.x + c.random.uniform()) / 16, (c.y + c.random.uniform()) / 16), c.random, c.rays);
      }, ro);
      CHECK(s.nonfinite == 0);
      CHECK(img.count_nonfinite() == 0);
      CHECK(s.samples == 16 * 16 * 4);
      CHECK(s.rays >= s.samples);  // at least the camera ray of each sample
    }
}

TEST_CASE("path: the image is the same bits on 1 and 2 threads and for any tile size") {
  const scene sc = cornell_box<double>(cornell_variant::glass);
  const path_tracer tracer(sc, path_options{});
  const auto cam = sc.prepared_camera();
  auto draw = [&](int threads, int tile) {
    image img(24, 24);
    render_options ro;
    ro.threads = threads, ro.tile = tile, ro.progress = false;
    render(img, 3, 42, [&](sample_context& c) {
      return tracer(cam.generate((c.x + c.random.uniform()) / 24, (c.y + c.random.uniform()) / 24), c.random, c.rays);
    }, ro);
    return img.pixels;
  };
  const auto one = draw(1, 16);
  CHECK(one == draw(2, 16));
  CHECK(one == draw(2, 5));
}

TEST_CASE("path: bad options and names are errors") {
  CHECK(parse_integrator("mis") == integrator::mis);
  CHECK_THROWS_AS(parse_integrator("bidirectional"), error);
  const scene sc = cornell_box<double>();
  path_options o;
  o.max_depth = -1;
  CHECK_THROWS_AS(path_tracer(sc, o), error);
}

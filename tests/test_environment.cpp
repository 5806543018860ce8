// links: yaml-cpp
// The environment light (environment.hpp, lights.hpp, path.hpp): the map's sampler follows its
// pdf (chi-square), the pdf integrates to one over the sphere, lookups hit texel centres, bad
// maps are refused by name; a Lambertian ball under a constant sky has radiance rho L (furnace)
// with every method; naive, nee and mis agree under a non-uniform map; nee finds a tiny sun.
#include <zraka/app/chi_square.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/lights/environment_file.hpp>

#include <doctest/doctest.h>
#if !ZRAKA_COMPILED_DEFINITIONS  // else image_io.hpp has stb_image_write, for writing .hdr files too
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#endif

#include <cmath>
#include <unistd.h>

using namespace zraka;
namespace fs = std::filesystem;

namespace {

constexpr int chi_tests = 2;  // chi-square tests in this file (Sidak)

// A sky: brighter towards the zenith, a black ground below the horizon, a sun of sun_value
// over sun_size x sun_size texels at (sun_x, sun_y).
image sky_image(int w, int h, float sun_value, int sun_size, int sun_x, int sun_y, float sky = 1.0f) {
  image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float up = 1.0f - (y + 0.5f) / h;  // 1 at the zenith
      img.at(x, y) = y < h / 2 ? sky * rgb(0.3f + up, 0.5f + up, 1.0f + up) * (1.0f + 0.5f * std::sin(0.3f * x)) : rgb(0);
    }
  for (int y = sun_y; y < sun_y + sun_size; ++y)
    for (int x = sun_x; x < sun_x + sun_size; ++x) img.at(x, y) = rgb(sun_value, sun_value * 0.9f, sun_value * 0.7f);
  return img;
}

struct temp_dir {
  fs::path path = fs::temp_directory_path() / ("zraka-test-env-" + std::to_string(::getpid()));
  temp_dir() { fs::create_directories(path); }
  ~temp_dir() { fs::remove_all(path); }
};

struct mean_se {
  double mean = 0, se = 0;
};
template <class RayOf>
mean_se estimate(const scene& sc, path_options o, int n, std::uint64_t seed, RayOf ray_of) {
  const path_tracer tracer(sc, o);
  double sum = 0, sum2 = 0;
  std::uint64_t rays = 0;
  for (int i = 0; i < n; ++i) {
    rng g(seed, 0, std::uint32_t(i));
    const ray r = ray_of(g);
    const rgb L = tracer(r, g, rays);
    const double v = double(L.x) + L.y + L.z;
    REQUIRE(std::isfinite(v));
    sum += v, sum2 += v * v;
  }
  const double mean = sum / n;
  return {mean, std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n)};
}

const integrator all_methods[] = {integrator::naive, integrator::nee, integrator::mis};

}  // namespace

TEST_CASE("environment: the map's sampler follows its pdf (chi-square), also rotated") {
  // Binned over the map's own (u, v), two bins per texel: the density there, p(omega) times
  // d(omega)/(du dv) = 2 pi^2 sin theta, is constant in each bin, so the expected counts are
  // exact (bins in cos theta would cut the sun's texels, and their quadrature error would be
  // larger than the noise of 10^6 samples).
  for (double rotate : {0.0, 30.0}) {
    const environment_map env = environment_map::from_image(sky_image(64, 32, 300, 2, 40, 6), "sky", 1.0f, rotate);
    rng g(3 + std::uint64_t(rotate), 0, 0);
    const auto r = chi_square_2d(
        [&]() -> std::optional<vec2> {
          double pdf = 0;
          const vec3 w = env.sample(vec2(g.uniform2()), pdf);
          if (!(pdf > 0)) return std::nullopt;
          REQUIRE(pdf == doctest::Approx(env.pdf(w)).epsilon(1e-6));
          return environment_map::to_uv(env.to_local(w));
        },
        [&](double u, double v) {
          const double theta = pi<double> * v, phi = 2 * pi<double> * u;
          const vec3 l(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
          return env.pdf(env.to_world(l)) * 2 * pi<double> * pi<double> * std::sin(theta);
        },
        1000000, grid2{128, 64, 0, 1, 0, 1}, 4);
    MESSAGE("rotate " << rotate << ": X^2 = " << r.statistic << ", dof " << r.dof << ", p = " << r.p_value);
    CHECK(r.impossible == 0);
    CHECK(r.p_value > sidak_level(0.01, chi_tests));
  }
}

TEST_CASE("environment: the pdf integrates to one over the sphere; zero below the black ground") {
  const environment_map env = environment_map::from_image(sky_image(64, 32, 300, 2, 40, 6), "sky", 1.0f, 10.0);
  const int nc = 1000, np = 2000;
  double integral = 0;
  for (int j = 0; j < nc; ++j)
    for (int i = 0; i < np; ++i)
      integral += env.pdf(direction_from_coords(-1 + 2 * (j + 0.5) / nc, 2 * pi<double> * (i + 0.5) / np));
  integral *= 4 * pi<double> / (double(nc) * np);
  MESSAGE("integral of the pdf over the sphere: " << integral);
  CHECK(integral == doctest::Approx(1).epsilon(2e-3));
  CHECK(env.pdf(vec3(0, -1, 0)) == 0);      // the nadir: black ground, and a pole
  CHECK(env.pdf(vec3(0.6, -0.8, 0)) == 0);  // the ground, away from the horizon's bilinear band
  CHECK(env.pdf(vec3(0, 1, 0)) == 0);       // the zenith: a pole (sin theta = 0)
  // A constant sky is sampled uniformly.
  const environment_map c = environment_map::constant(rgb(2));
  double p = 0;
  const vec3 w = c.sample(vec2(0.3, 0.7), p);
  CHECK(p == doctest::Approx(1 / (4 * pi<double>)));
  CHECK(c.pdf(w) == p);
  CHECK(c.radiance(w) == rgb(2));
  CHECK(c.integral() == doctest::Approx(8 * pi<double>));
}

TEST_CASE("environment: lookups at texel centres give the texel; rotation turns the map about +y") {
  image img(8, 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) img.at(x, y) = rgb(float(x), float(y), 1);
  const environment_map env = environment_map::from_image(img, "grid", 2.0f);
  auto centre = [](int x, int y, double rot_deg) {
    const double phi = 2 * pi<double> * (x + 0.5) / 8 + rot_deg * pi<double> / 180, theta = pi<double> * (y + 0.5) / 4;
    return vec3(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
  };
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 8; ++x) {
      const rgb L = env.radiance(centre(x, y, 0));
      CHECK(L.x == doctest::Approx(2.0 * x).epsilon(1e-5));
      CHECK(L.y == doctest::Approx(2.0 * y).epsilon(1e-5));
    }
  // phi = 0 looks along -z; +x is a quarter turn on.
  CHECK(env.radiance(vec3(0, 0, -1)).x == doctest::Approx(7.0));  // between texel 7 and 0: wraps, (14 + 0)/2
  const environment_map turned = environment_map::from_image(img, "grid", 2.0f, 90.0);
  // A right-handed turn about +y (from +z towards +x) takes phi to phi - angle.
  CHECK(turned.radiance(centre(3, 1, -90)).x == doctest::Approx(6.0).epsilon(1e-5));
}

TEST_CASE("environment: bad maps are refused, naming the file") {
  image img(4, 2, rgb(1));
  img.at(1, 1) = rgb(std::nanf(""), 0, 0);
  CHECK_THROWS_WITH(environment_map::from_image(img, "a.hdr"), doctest::Contains("a.hdr: pixel (1, 1)"));
  img.at(1, 1) = rgb(-1, 0, 0);
  CHECK_THROWS_WITH(environment_map::from_image(img, "b.hdr"), doctest::Contains("negative"));
  CHECK_THROWS_WITH(environment_map::from_image(image(), "c.hdr"), doctest::Contains("c.hdr: the environment map is empty"));
  CHECK_THROWS_WITH(environment_map::constant(rgb(1, std::nanf(""), 0)), doctest::Contains("not finite"));
  CHECK_THROWS_WITH(load_environment("/no/such/sky.hdr"), doctest::Contains("/no/such/sky.hdr"));
  temp_dir t;
  const fs::path junk = t.path / "junk.hdr";
  std::ofstream(junk) << "this is not a radiance file\n";
  CHECK_THROWS_WITH(load_environment(junk), doctest::Contains("junk.hdr: not a Radiance HDR file"));
  const fs::path cut = t.path / "cut.hdr";
  std::ofstream(cut) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 2000000 +X 2000000\n";
  CHECK_THROWS_WITH(load_environment(cut), doctest::Contains("cut.hdr"));
  std::ofstream(t.path / "sky.png") << "x";
  CHECK_THROWS_WITH(load_environment(t.path / "sky.png"), doctest::Contains("unknown environment map type '.png'"));
}

TEST_CASE("environment: a Radiance .hdr file written by stb reads back (RGBE: to 1/128 of the largest channel)") {
  temp_dir t;
  const image img = sky_image(32, 16, 50, 1, 5, 3);
  const fs::path p = t.path / "sky.hdr";
  REQUIRE(stbi_write_hdr(p.string().c_str(), img.width, img.height, 3, &img.pixels[0].x));
  const environment_map env = load_environment(p, 1.0f);
  const image back = read_hdr_image(p);
  REQUIRE(back.width == 32);
  REQUIRE(back.height == 16);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)  // RGBE: 8 bits of mantissa under the largest channel's exponent
      CHECK(std::abs(back.pixels[i][c] - img.pixels[i][c]) <= max_component(img.pixels[i]) / 128 + 1e-6f);
  CHECK(env.width() == 32);
}

TEST_CASE("environment: a Lambertian ball under a constant sky has radiance rho L with every method") {
  // Closed form: every direction leaves the convex ball and sees L, so L_o = rho L.
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::lambertian(rgb(0.25f, 0.5f, 0.75f))));
  sc.environment = std::make_shared<environment_map>(environment_map::constant(rgb(2)));
  const double expected = 2 * (0.25 + 0.5 + 0.75);
  for (integrator m : all_methods) {
    path_options o;
    o.method = m;
    const mean_se e = estimate(sc, o, 20000, 5, [](rng& g) {
      const vec2 d = sample_disk_concentric(vec2(g.uniform2())) * 0.99;
      return ray({d.x, d.y, 5}, {0, 0, -1});
    });
    MESSAGE(std::string(name(m)) << ": " << e.mean << " +- " << e.se << " (expected " << expected << ")");
    if (m == integrator::naive) CHECK(e.se < 1e-6);  // each path is rho L exactly
    CHECK(std::abs(e.mean - expected) < 5 * e.se + 1e-5);
  }
}

TEST_CASE("environment: naive, nee and mis agree on a scene lit only by a non-uniform map") {
  scene sc;
  sc.add(quad{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, sc.add_material(material::lambertian(rgb(0.6f))));
  sc.add(sphere{{0, 1, 0}, 1}, sc.add_material(material::lambertian(rgb(0.8f, 0.4f, 0.2f))));
  sc.environment = std::make_shared<environment_map>(
      environment_map::from_image(sky_image(64, 32, 40, 3, 20, 5), "sky", 1.0f, 25.0));
  sc.camera.position = {0, 2, 6};
  sc.camera.look_at = {0, 0.8, 0};
  const auto cam = sc.prepared_camera();
  mean_se e[3];
  for (int i = 0; i < 3; ++i) {
    path_options o;
    o.method = all_methods[i];
    o.max_depth = 5;
    e[i] = estimate(sc, o, 40000, 40 + std::uint64_t(i), [&](rng& g) { return cam.generate(g.uniform(), g.uniform()); });
    MESSAGE(std::string(name(all_methods[i])) << ": " << e[i].mean << " +- " << e[i].se);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j) CHECK(std::abs(e[i].mean - e[j].mean) < 5 * std::hypot(e[i].se, e[j].se));
}

TEST_CASE("environment: nee finds a tiny bright sun that naive rarely hits") {
  // One texel of 128 x 64 holds nearly all the power: a point on the floor sees it through a
  // solid angle of about 1e-3 sr.
  scene sc;
  sc.add(quad{{-50, 0, 50}, {100, 0, 0}, {0, 0, -100}}, sc.add_material(material::lambertian(rgb(0.5f))));
  sc.environment = std::make_shared<environment_map>(
      environment_map::from_image(sky_image(128, 64, 2e4f, 1, 70, 12, 0.02f), "sun", 1.0f));
  auto floor_point = [](rng&) { return ray({0, 1, 0}, {0, -1, 0}); };
  double sd[3], mean[3];
  for (int i = 0; i < 3; ++i) {
    path_options o;
    o.method = all_methods[i];
    o.max_depth = 1;
    const mean_se e = estimate(sc, o, 20000, 60 + std::uint64_t(i), floor_point);
    sd[i] = e.se * std::sqrt(20000.0);
    mean[i] = e.mean;
    MESSAGE(std::string(name(all_methods[i])) << ": mean " << e.mean << " +- " << e.se << ", standard deviation per sample " << sd[i]);
  }
  CHECK(sd[1] < sd[0] / 10);
  CHECK(sd[2] < sd[0] / 10);
  CHECK(std::abs(mean[1] - mean[2]) < 5 * std::hypot(sd[1], sd[2]) / std::sqrt(20000.0));
}

TEST_CASE("environment: one light of the light set, chosen by power; its sample's pdf is pdf()") {
  scene sc;
  const int lamp = sc.add_material(material::emitter(rgb(1)));
  sc.add(quad{{0, 2, 0}, {1, 0, 0}, {0, 0, 1}}, lamp);  // area 1, power pi
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::lambertian(rgb(0.5f))));
  sc.environment = std::make_shared<environment_map>(environment_map::constant(rgb(0.5f)));
  const light_set ls(sc);
  REQUIRE(ls.size() == 2);
  REQUIRE(ls.environment_index() == 1);
  CHECK(ls.describe() == "lights: 2 (1 quad, 1 constant environment), chosen by power");
  // The bounds: the sphere and the quad, a box from (-1,-1,-1) to (1,2,1): radius sqrt(4+9+4)/2.
  const double R = std::sqrt(17.0) / 2;
  CHECK(ls.scene_radius() == doctest::Approx(R).epsilon(1e-3));
  const double env_power = pi<double> * R * R * 4 * pi<double> * 0.5;
  CHECK(ls.selection_pdf(1) == doctest::Approx(env_power / (env_power + pi<double>)).epsilon(1e-3));
  hit h;
  h.p = {0, 1, 0};
  h.normal = {0, 1, 0};
  for (int k = 0; k < 100; ++k) {
    rng g(9, 0, std::uint32_t(k));
    const auto s = ls.sample(h, 0.99, vec2(g.uniform2()));  // u_select near 1: the environment
    REQUIRE(s);
    CHECK(s->light == 1);
    CHECK(s->pdf == doctest::Approx(ls.environment_pdf(s->wi)));
    CHECK(std::isinf(s->shadow.t_max));
    CHECK(s->Le == rgb(0.5f));
  }
  // A black environment is no light; the Whitted tracer sees the map as its background.
  scene dark;
  dark.add(sphere{{0, 0, 0}, 1}, dark.add_material(material::lambertian(rgb(0.5f))));
  dark.environment = std::make_shared<environment_map>(environment_map::constant(rgb(0)));
  CHECK(light_set(dark).empty());
  const light_set lw(sc);
  rng g(1, 0, 0);
  std::uint64_t rays = 0;
  CHECK(whitted_radiance(sc, lw, ray({5, 5, 5}, {0, 1, 0}), g, whitted_options{}, rays) == rgb(0.5f));
}

TEST_CASE("environment: the realtime packer takes it (its tables: test_gpu_scene; its images: test_realtime)") {
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::lambertian(rgb(0.5f))));
  sc.environment = std::make_shared<environment_map>(environment_map::constant(rgb(1)));
  const gpu_scene g = pack_scene(sc, 16, 16, path_options{});
  CHECK(g.environment.present == 1);
  CHECK(g.features.environment);
}

TEST_CASE("environment: scene files give a map or a colour; the resolved scene loads again") {
  temp_dir t;
  const image img = sky_image(16, 8, 10, 1, 3, 2);
  REQUIRE(stbi_write_hdr((t.path / "s.hdr").string().c_str(), 16, 8, 3, &img.pixels[0].x));
  const fs::path yaml = t.path / "s.yaml";
  std::ofstream(yaml) << "environment: {file: s.hdr, scale: 2, rotate: 45}\nobjects: [{type: sphere}]\n";
  const loaded_scene ls = load_scene_file(yaml);
  REQUIRE(ls.sc.environment);
  CHECK(ls.sc.environment->width() == 16);
  CHECK(ls.sc.environment->rotate_degrees() == 45);
  CHECK(ls.resolved.find("environment") != std::string::npos);
  CHECK(ls.resolved.find("background") == std::string::npos);
  const loaded_scene c = parse_scene("environment: {color: [1, 2, 3], scale: 0.5}\nobjects: [{type: sphere}]\n", "c.yaml");
  REQUIRE(c.sc.environment);
  CHECK(c.sc.environment->is_constant());
  CHECK(c.sc.environment->radiance(vec3(0, 1, 0)) == rgb(0.5f, 1, 1.5f));
  const loaded_scene again = parse_scene(c.resolved, "again.yaml");
  CHECK(again.sc.environment->radiance(vec3(1, 0, 0)) == rgb(0.5f, 1, 1.5f));
}

TEST_CASE_TEMPLATE("environment: in float and double, a sample's pdf is pdf() and u near 1 is safe", T, float, double) {
  const environment_map env = environment_map::from_image(sky_image(64, 32, 300, 2, 40, 6), "sky", 1.0f, 30.0);
  rng g(21, 0, 0);
  for (int k = 0; k < 2000; ++k) {
    T pdf = T(0);
    const vec3_t<T> w = env.sample(vec2_t<T>(g.uniform2()), pdf);
    if (!(pdf > T(0))) continue;
    REQUIRE(std::abs(double(glm::length(w)) - 1) < 1e-5);
    CHECK(double(pdf) == doctest::Approx(double(env.pdf(w))).epsilon(1e-3));
  }
  for (T u : {T(0), one_minus_epsilon<T>, T(1)}) {
    T pdf = T(-1);
    const vec3_t<T> w = env.sample(vec2_t<T>(u, u), pdf);
    CHECK(pdf >= T(0));
    CHECK(is_finite(w));
  }
}

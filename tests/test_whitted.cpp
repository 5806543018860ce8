// links: yaml-cpp
// The Whitted tracer: pixel values against the closed-form Phong value under a point light;
// the same bits on any number of threads; shadows from occluders at any distance; total
// internal reflection inside glass and energy conservation of Fresnel splitting; a scene file
// rendered end to end.
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/scene/default_scene.hpp>

#include <doctest/doctest.h>

using namespace zraka;

namespace {
// One sphere, one point light, nothing else: every pixel has a closed form.
scene lit_sphere(const material& m) {
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(m));
  sc.add(point_light_t<double>{{2, 3, 4}, rgb(30, 20, 10)});
  sc.camera.position = {0, 0, 4};
  sc.camera.look_at = {0, 0, 0};
  sc.settings.width = 24;
  sc.settings.height = 24;
  sc.settings.spp = 1;  // the pixel centre
  return sc;
}
}  // namespace

TEST_CASE("whitted: a lit sphere's pixels equal the closed-form Phong value") {
  const material lambert = material::lambertian(rgb(0.5f, 0.25f, 0.75f));
  const material plastic = material::phong(rgb(0.3f, 0.2f, 0.1f), rgb(0.4f), 20);
  for (const material& m : {lambert, plastic}) {
    for (const local_model model : {local_model::phong, local_model::blinn_phong}) {
      const scene sc = lit_sphere(m);
      image img(sc.settings.width, sc.settings.height);
      render_whitted(sc, img, whitted_options{8, 1e-3f, model}, render_options{1, 16, false});
      const auto cam = sc.prepared_camera();
      int lit = 0;
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          const ray r = cam.generate((x + 0.5) / img.width, (y + 0.5) / img.height);
          // Closed form: the ray meets the unit sphere at t = -b - sqrt(b^2 - c).
          const double b = glm::dot(r.origin, r.direction), c = glm::dot(r.origin, r.origin) - 1;
          vec3 want(0);
          if (b * b - c > 0) {
            const vec3 p = r.at(-b - std::sqrt(b * b - c)), n = p;
            const vec3 to = vec3(2, 3, 4) - p;
            const vec3 l = glm::normalize(to), v = -r.direction;
            const auto* ph = m.get<material_kinds::phong>();  // else a lambertian: phong's default exponent, ks 0
            const double nl = glm::dot(n, l), s = ph ? ph->shininess : material_kinds::phong{}.shininess;
            if (nl > 0) {
              const double spec = model == local_model::phong
                                      ? (s + 2) / (2 * pi<double>) * std::pow(std::max(0.0, glm::dot(v, 2 * nl * n - l)), s)
                                      : (s + 8) / (8 * pi<double>) * std::pow(std::max(0.0, glm::dot(n, glm::normalize(l + v))), s);
              const vec3 kd = ph ? vec3(ph->kd) : vec3(m.get<material_kinds::lambertian>()->albedo.a);
              const vec3 ks = ph ? vec3(ph->ks) : vec3(0);
              want = (kd / pi<double> + ks * spec) * nl * vec3(30, 20, 10) / glm::dot(to, to);
              ++lit;
            }
          }
          const vec3 got(img.at(x, y));
          for (int k = 0; k < 3; ++k)  // float colours: a few float roundings of values <= 1
            CHECK(got[k] == doctest::Approx(want[k]).epsilon(1e-5).scale(1e-6));
        }
      CHECK(lit > 100);
    }
  }
}

TEST_CASE("whitted: the same bits on 1, 2 and 3 threads") {
  loaded_scene ls = load_scene_file("scenes/default.yaml");  // area light, fuzzy metal, glass: random
  ls.sc.settings.width = 40;
  ls.sc.settings.height = 24;
  ls.sc.settings.spp = 3;
  whitted_options opt;
  image a(40, 24), b(40, 24), c(40, 24);
  render_whitted(ls.sc, a, opt, render_options{1, 16, false});
  render_whitted(ls.sc, b, opt, render_options{2, 7, false});
  render_whitted(ls.sc, c, opt, render_options{3, 5, false});
  CHECK(a.pixels == b.pixels);
  CHECK(a.pixels == c.pixels);
  ls.sc.settings.seed = 2;  // another seed, another image
  render_whitted(ls.sc, c, opt, render_options{2, 16, false});
  CHECK(a.pixels != c.pixels);
}

TEST_CASE("whitted: occluders cast shadows however far they are from the shaded point") {
  // The thesis's code tested shadow rays only up to t = 1 (and from the wrong end). Here a point
  // on the floor under a light 100 units up is shadowed by a ball at heights 0.01 .. 90.
  for (const double height : {0.01, 0.5, 2.0, 30.0, 90.0}) {
    scene sc;
    const int grey = sc.add_material(material::lambertian(rgb(0.5f)));
    sc.add(plane::from_point_normal({0, 0, 0}, {0, 1, 0}), grey);
    sc.add(point_light_t<double>{{0, 100, 0}, rgb(1e4f)});
    // A camera ray onto the floor at (0.001, 0, 0.002), from the side: it passes the occluder.
    const ray down({3.001, 5, 0.002}, {-3, -5, 0});
    std::uint64_t rays = 0;
    rng g(1);
    const rgb lit = whitted_radiance(sc, light_set(sc), down, g, whitted_options{}, rays);
    CHECK(lit.x == doctest::Approx(0.5 / pi<double> * 1e4 / 1e4).epsilon(1e-5));  // rho/pi I/d^2
    const double r = std::min(0.004, height / 2);
    sc.add(sphere{{0, height, 0}, r}, grey);  // between floor and light, off the camera ray's path
    const rgb shadowed = whitted_radiance(sc, light_set(sc), down, g, whitted_options{}, rays);
    INFO("occluder at height " << height);
    CHECK(shadowed == rgb(0));
  }
  // An object beyond the light casts no shadow.
  scene sc;
  const int grey = sc.add_material(material::lambertian(rgb(0.5f)));
  sc.add(plane::from_point_normal({0, 0, 0}, {0, 1, 0}), grey);
  sc.add(point_light_t<double>{{0, 10, 0}, rgb(100)});
  sc.add(sphere{{0, 11, 0}, 0.5}, grey);
  std::uint64_t rays = 0;
  rng g(1);
  CHECK(whitted_radiance(sc, light_set(sc), ray({0.001, 5, 0.002}, {0, -1, 0}), g, whitted_options{}, rays).x > 0);
}

TEST_CASE("whitted: total internal reflection traps light in glass; Fresnel splitting conserves energy") {
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::dielectric(1.5)));
  sc.background = rgb(1);
  std::uint64_t rays = 0;
  rng g(1);
  whitted_options opt;
  opt.max_depth = 60;
  opt.min_weight = 0;
  // From inside, along a chord 0.9 from the centre: sin(theta) = 0.9 > 1/1.5 at every hit, and
  // every chord of that ray has the same angle: light never gets out.
  CHECK(whitted_radiance(sc, light_set(sc), ray({0.9, 0, 0}, {0, 1, 0}), g, opt, rays) == rgb(0));
  // 0.5 from the centre: below the critical angle. With depth 1 the first exit carries 1 - R.
  opt.max_depth = 1;
  const double R = fresnel_dielectric(std::sqrt(1 - 0.25), 1.5);
  CHECK(whitted_radiance(sc, light_set(sc), ray({0.5, 0, 0}, {0, 1, 0}), g, opt, rays).x == doctest::Approx(1 - R).epsilon(1e-6));
  // From outside, under a uniform sky of 1, everything that enters leaves again: radiance 1 for
  // any ray (up to the branches cut at min_weight 1e-4 and depth 40: tolerance 1e-3).
  opt.max_depth = 40;
  opt.min_weight = 1e-4f;
  for (int i = 0; i < 200; ++i) {
    const vec3 o = 3.0 * sample_uniform_sphere(g.uniform2());
    const vec3 target = 0.99 * sample_unit_ball(vec3(g.uniform(), g.uniform(), g.uniform()));
    const rgb L = whitted_radiance(sc, light_set(sc), ray(o, target - o), g, opt, rays);
    CHECK(L.x == doctest::Approx(1).epsilon(1e-3));
  }
}

TEST_CASE("whitted: a mirror shows the light's colour; depth 1 stops at the mirror's reflection") {
  scene sc;
  const int mirror = sc.add_material(material::mirror(rgb(0.5f)));
  const int lamp = sc.add_material(material::emitter(rgb(4)));
  sc.add(quad{{-1, 0, 1}, {2, 0, 0}, {0, 0, -2}}, mirror);  // y = 0, facing up
  sc.add(quad{{-1, 3, -1}, {2, 0, 0}, {0, 0, 2}}, lamp);    // y = 3, facing down
  std::uint64_t rays = 0;
  rng g(1);
  whitted_options opt;
  opt.max_depth = 1;
  CHECK(whitted_radiance(sc, light_set(sc), ray({0, 1, 0.5}, {0, -1, -0.1}), g, opt, rays) == rgb(2));  // 0.5 x 4
  opt.max_depth = 0;  // no reflection allowed: the mirror is black
  CHECK(whitted_radiance(sc, light_set(sc), ray({0, 1, 0.5}, {0, -1, -0.1}), g, opt, rays) == rgb(0));
}

TEST_CASE("whitted: the default scene built in C++ is scenes/default.yaml, bit for bit") {
  scene cpp = default_scene();
  loaded_scene yaml = load_scene_file("scenes/default.yaml");
  CHECK(cpp.spheres.size() == yaml.sc.spheres.size());
  CHECK(cpp.planes.size() == yaml.sc.planes.size());
  CHECK(cpp.quads.size() == yaml.sc.quads.size());
  CHECK(cpp.lights.size() == yaml.sc.lights.size());  // point lights (lights/point.hpp)
  REQUIRE(cpp.meshes.size() == yaml.sc.meshes.size());
  CHECK(cpp.meshes[0].shape.triangle_count() == yaml.sc.meshes[0].shape.triangle_count());
  CHECK(cpp.settings.width == yaml.sc.settings.width);
  CHECK(cpp.settings.spp == yaml.sc.settings.spp);
  CHECK(cpp.ambient == yaml.sc.ambient);
  CHECK(cpp.background == yaml.sc.background);
  for (scene* sc : {&cpp, &yaml.sc}) sc->settings.width = 80, sc->settings.height = 48, sc->settings.spp = 2;
  image a(80, 48), b(80, 48);
  render_whitted(cpp, a, whitted_options{}, render_options{2, 16, false});
  render_whitted(yaml.sc, b, whitted_options{}, render_options{2, 16, false});
  double sum = 0;
  for (const rgb& p : a.pixels) sum += double(p.x + p.y + p.z);
  CHECK(sum > 0);
  CHECK(a.pixels == b.pixels);
}

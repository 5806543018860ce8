#include <zraka/materials/material.hpp>

#include <doctest/doctest.h>

using namespace zraka;

namespace {
hit_t<double> floor_hit(bool front = true) {  // a hit on the plane y = 0, normal +y
  hit_t<double> h;
  h.t = 1;
  h.p = vec3(0.25, 0, 0.25);
  h.normal = vec3(0, 1, 0);
  h.front_face = front;
  return h;
}
vec3 incoming(double theta_deg) {  // a ray direction hitting the floor from above at theta
  const double t = theta_deg * pi<double> / 180;
  return {std::sin(t), -std::cos(t), 0};
}
}  // namespace

TEST_CASE("material: Lambertian weight is the albedo, directions in the facing hemisphere") {
  const material m = material::lambertian(rgb(0.25f, 0.5f, 0.75f));
  for (bool front : {true, false}) {
    hit_t<double> h = floor_hit(front);
    for (double theta : {0.0, 45.0, 89.9999}) {
      const vec3 d = front ? incoming(theta) : -incoming(theta);
      for (int i = 0; i < 1000; ++i) {
        rng g(7, 0, std::uint32_t(i));
        const auto s = scatter(m, d, h, g);
        REQUIRE(s);
        CHECK(s->weight == rgb(0.25f, 0.5f, 0.75f));  // exact: the cosine and pi cancel in closed form
        CHECK(glm::dot(s->direction, h.facing_normal()) > 0);
        CHECK(s->pdf > 0);
        CHECK_FALSE(s->specular);
        // brdf_cos / pdf reproduces the weight (light sampling and BSDF sampling agree).
        const rgb w = brdf_cos(m, h, -d, s->direction) / float(scatter_pdf(m, h, -d, s->direction));
        CHECK(w.y == doctest::Approx(0.5).epsilon(1e-5));  // float rounding of f cos / p
      }
    }
  }
}

TEST_CASE("material: fuzzy metal is a mirror at fuzz 0, loses energy (never gains) when fuzzy") {
  hit_t<double> h = floor_hit();
  rng g(3);
  const auto s = scatter(material::mirror(rgb(0.9f)), incoming(30), h, g);
  REQUIRE(s);
  CHECK(s->specular);
  CHECK(s->direction.x == doctest::Approx(std::sin(30 * pi<double> / 180)).epsilon(1e-12));
  CHECK(s->direction.y == doctest::Approx(std::cos(30 * pi<double> / 180)).epsilon(1e-12));
  CHECK(s->weight == rgb(0.9f));
  // fuzz 1 at grazing incidence: many directions land below the surface and are absorbed.
  const material fuzzy = material::fuzzy_metal(rgb(1.0f), 1.0);
  int absorbed = 0;
  double energy = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    rng gi(5, 0, std::uint32_t(i));
    const auto si = scatter(fuzzy, incoming(89.999), h, gi);
    if (!si) { ++absorbed; continue; }
    REQUIRE(is_finite(si->direction));
    CHECK(glm::dot(si->direction, h.normal) > 0);
    CHECK(glm::length(si->direction) == doctest::Approx(1).epsilon(1e-12));
    energy += si->weight.x / n;
  }
  CHECK(absorbed > n / 10);  // about half the ball lies below a grazing mirror direction
  CHECK(energy < 1.0);
}

TEST_CASE("material: glass reflects about R0 at normal incidence and totally beyond the critical angle") {
  const material glass = material::dielectric(1.5);
  hit_t<double> h = floor_hit();
  const int n = 20000;
  int reflected = 0;
  for (int i = 0; i < n; ++i) {
    rng g(11, 0, std::uint32_t(i));
    const auto s = scatter(glass, incoming(0), h, g);
    REQUIRE(s);
    CHECK(s->weight == rgb(1));
    if (s->direction.y > 0) ++reflected;
  }
  // R0 = (0.5/2.5)^2 = 0.04; standard error sqrt(0.04 * 0.96 / 20000) = 0.0014; 5 sigma.
  CHECK(double(reflected) / n == doctest::Approx(0.04).epsilon(0.175));
  // From inside (back face), 45 degrees > 41.8: every sample reflects, directions finite and unit.
  hit_t<double> inside = floor_hit(false);
  for (double theta : {45.0, 60.0, 89.9999, 90.0}) {
    for (int i = 0; i < 200; ++i) {
      rng g(13, 0, std::uint32_t(i));
      const auto s = scatter(glass, -incoming(theta), inside, g);
      REQUIRE(s);
      CHECK(is_finite(s->direction));
      CHECK(s->direction.y <= 0);  // stays inside (below the plane, on the back side)
    }
  }
  // Grazing entry from outside: no NaN, always a unit direction.
  for (int i = 0; i < 200; ++i) {
    rng g(17, 0, std::uint32_t(i));
    const auto s = scatter(glass, incoming(90), h, g);
    REQUIRE(s);
    CHECK(glm::length(s->direction) == doctest::Approx(1).epsilon(1e-12));
  }
}

TEST_CASE("material: phong (Lambert + normalised lobe) reflects at most kd + ks (white furnace)") {
  const material m = material::phong(rgb(0.5f), rgb(0.5f), 32);
  hit_t<double> h = floor_hit();
  for (double theta : {0.0, 60.0, 89.99}) {
    const int n = 20000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      rng g(19, 0, std::uint32_t(i));
      const auto s = scatter(m, incoming(theta), h, g);
      if (!s) continue;  // absorbed (the lobe sampled below the surface) counts as 0
      REQUIRE(is_finite(s->weight));
      sum += s->weight.x;
      sum2 += double(s->weight.x) * s->weight.x;
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    INFO("theta " << theta << ": albedo " << mean << " +- " << se);
    CHECK(mean <= 1.0 + 5 * se);  // energy conservation, with 5 standard errors of slack
    if (theta == 0.0) CHECK(mean == doctest::Approx(1.0).epsilon(5 * se + 1e-3));  // kd + ks exactly
  }
}

TEST_CASE("material: emitters shine from the front only and do not scatter") {
  const material light = material::emitter(rgb(4));
  rng g(1);
  CHECK(emitted(light, floor_hit(true)) == rgb(4));
  CHECK(emitted(light, floor_hit(false)) == rgb(0));
  CHECK(emitted(material::lambertian(rgb(1)), floor_hit()) == rgb(0));
  CHECK_FALSE(scatter(light, incoming(10), floor_hit(), g));
  CHECK(brdf_cos(light, floor_hit(), vec3(0, 1, 0), vec3(0, 1, 0)) == rgb(0));
  CHECK(is_specular(material::dielectric(1.5)));
  CHECK_FALSE(is_specular(material::lambertian(rgb(1))));
}

TEST_CASE("material: two-sided emitters and glowing surfaces shine from both faces") {
  const material lamp = material::emitter(rgb(2), true);
  CHECK(emitted(lamp, floor_hit(true)) == rgb(2));
  CHECK(emitted(lamp, floor_hit(false)) == rgb(2));
  material glow = material::lambertian(rgb(0.5f));  // a furnace wall: reflects and glows
  glow.radiance = rgb(1);
  CHECK(emits(glow));
  CHECK_FALSE(emits(material::lambertian(rgb(1))));
  CHECK(emitted(glow, floor_hit(true)) == rgb(1));
  CHECK(emitted(glow, floor_hit(false)) == rgb(0));  // one-sided unless two_sided is set
  glow.two_sided = true;
  CHECK(emitted(glow, floor_hit(false)) == rgb(1));
  rng g(3);
  CHECK(scatter(glow, -incoming(20), floor_hit(false), g));  // and it still reflects, from either side
}

TEST_CASE("material: hollow glass (IOR ratio below 1) reflects totally beyond its critical angle") {
  // An air bubble in glass: n_inside / n_outside = 1/1.5. A ray entering it from the glass at
  // 60 degrees (sin 60 * 1.5 = 1.3 > 1) cannot refract: it is reflected every time.
  const material bubble = material::dielectric(1 / 1.5);
  rng g(4);
  for (int i = 0; i < 100; ++i) {
    const auto s = scatter(bubble, incoming(60), floor_hit(true), g);
    REQUIRE(s);
    CHECK(s->direction.y > 0);  // back up: reflected
  }
  int refracted = 0;  // at 10 degrees most of it goes in
  for (int i = 0; i < 1000; ++i) refracted += scatter(bubble, incoming(10), floor_hit(true), g)->direction.y < 0;
  CHECK(refracted > 900);
  CHECK_THROWS_AS(material::dielectric(0), error);
  CHECK_THROWS_AS(material::dielectric(-1.5), error);
  CHECK_THROWS_AS(material::emitter(rgb(-1)), error);
}

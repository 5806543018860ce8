// links: yaml-cpp
// A course's own light (lights/custom_light.hpp) through the one door (scene_registry::add_light):
// a spot light with a cone and a smooth falloff, written here as a course would write it,
// registered by name, loaded from YAML, rendered by the path tracer (nee and mis) and Whitted against the
// closed form of the irradiance on a floor (its centre, inside the cone, in the falloff, past the
// cut-off), its emission sampled with the right flux (BDPT and photon mapping start there),
// and refused by name by the OpenCL kernel's packing.
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/lights/custom_light.hpp>

#include <doctest/doctest.h>

#include "expected_errors.hpp"

#include <cmath>
#include <memory>
#include <string>

using namespace zraka;
using zraka_test::error_of;

namespace {

// The course's spot light: intensity I0 inside the inner cone, none outside the outer one, and
// a smoothstep in cos theta between them. Emission is sampled uniformly in the outer cone.
struct spot_light final : custom_light {
  vec3 at, axis;
  rgb I0;
  double cos_inner, cos_outer;
  spot_light(vec3 p, vec3 a, rgb i, double inner_deg, double outer_deg)
      : at(p), axis(glm::normalize(a)), I0(i), cos_inner(std::cos(inner_deg * pi<double> / 180)),
        cos_outer(std::cos(outer_deg * pi<double> / 180)) {}
  std::string name() const override { return "spot"; }
  vec3 position() const override { return at; }
  double falloff(double c) const {
    if (c >= cos_inner) return 1;
    if (c <= cos_outer) return 0;
    const double t = (c - cos_outer) / (cos_inner - cos_outer);
    return t * t * (3 - 2 * t);
  }
  rgb intensity(const vec3& w) const override { return I0 * float(falloff(glm::dot(w, axis))); }
  // 2 pi I0 [(1 - cos_inner) + (cos_inner - cos_outer) / 2]: the smoothstep's mean is 1/2.
  double power() const override {
    const double mean = (double(I0.x) + double(I0.y) + double(I0.z)) / 3;
    return 2 * pi<double> * mean * ((1 - cos_inner) + (cos_inner - cos_outer) / 2);
  }
  vec3 sample_direction(const vec2& u) const override {
    const double c = 1 - u.x * (1 - cos_outer), s = std::sqrt(std::max(0.0, 1 - c * c));
    const double phi = 2 * pi<double> * u.y;
    const onb b(axis);
    return b.to_world(vec3(s * std::cos(phi), s * std::sin(phi), c));
  }
  double pdf_direction(const vec3& w) const override {
    return glm::dot(w, axis) >= cos_outer ? 1 / (2 * pi<double> * (1 - cos_outer)) : 0;
  }
};

// The course's one registration line, the same call as the built-in point light's.
scene_registry course_lights() {
  scene_registry reg;
  reg.add_light("spot", {"position", "axis", "intensity", "inner", "outer"}, [](const scene_node& n) {
    const double inner = n.number("inner", 20), outer = n.number("outer", 30);
    if (!(inner >= 0 && inner < outer && outer < 90)) n.fail("outer", "the cone must have 0 <= inner < outer < 90");
    return light(light_kinds::custom{std::make_shared<spot_light>(n.point("position"), n.direction("axis"),
                                                                  n.colour("intensity", rgb(1)), inner, outer)});
  });
  return reg;
}

const char* spot_scene = R"(
materials:
  white: {type: lambertian, albedo: 0.5}
objects:
  - {type: quad, corner: [-20, 0, 20], u: [40, 0, 0], v: [0, 0, -40], material: white}
lights:
  - {type: spot, position: [0, 2, 0], axis: [0, -1, 0], intensity: 8, inner: 20, outer: 40}
)";

}  // namespace

TEST_CASE("custom light: a registered spot light loads from YAML and is a light of every CPU renderer") {
  const loaded_scene ls = parse_scene(spot_scene, "spot.yaml", ".", course_lights());
  REQUIRE(ls.sc.lights.size() == 1);
  CHECK(light_type(ls.sc.lights[0]) == "spot");
  CHECK(ls.resolved.find("type: spot") != std::string::npos);
  const light_set lights(ls.sc);
  CHECK(lights.size() == 1);
  CHECK(lights.describe() == "lights: 1 (1 spot light), chosen by power");
  // Whitted samples every light through the same light set: the scene is not refused (the
  // next test checks what it renders).
  CHECK(error_of([&] { check_whitted_scene(ls.sc); }) == "(no error)");
}

TEST_CASE("custom light: the path tracer and Whitted give rho/pi I(theta) cos^3(theta) / h^2 on the floor") {
  // A point x on the floor at angle theta off the spot's axis, the spot at height h: distance
  // h / cos theta, incidence cos theta, so E = I(theta) cos^3 theta / h^2 and a Lambertian floor
  // reflects L = rho E / pi. One bounce: the floor cannot light itself, the sky is black, and a
  // delta light makes next-event estimation exact (no other technique finds it).
  const loaded_scene ls = parse_scene(spot_scene, "spot.yaml", ".", course_lights());
  const double h = 2, rho = 0.5, I0 = 8, inner = 20, outer = 40;
  const spot_light reference({0, h, 0}, {0, -1, 0}, rgb(float(I0)), inner, outer);
  for (const double deg : {0.0, 10.0, 25.0, 30.0, 35.0, 45.0}) {
    const double th = deg * pi<double> / 180, c = std::cos(th);
    const vec3 x(h * std::tan(th), 0, 0);
    const double expected = rho / pi<double> * I0 * reference.falloff(c) * c * c * c / (h * h);
    for (integrator m : {integrator::nee, integrator::mis}) {
      path_options o;
      o.method = m;
      o.max_depth = 1;
      const path_tracer tracer(ls.sc, o);
      rng g(7);
      std::uint64_t rays = 0;
      const vec3 eye(x.x, 1, 1);
      const rgb L = tracer(ray(eye, x - eye), g, rays);
      INFO(name(m) << " at " << deg << " degrees: " << L.x << ", expected " << expected);
      CHECK(double(L.x) == doctest::Approx(expected).epsilon(1e-5));
      if (deg >= outer) CHECK(L == rgb(0));  // past the cut-off: nothing at all
    }
    // Whitted's local model shades a Lambertian floor as rho/pi E too, from the same light set.
    const light_set lights(ls.sc);
    rng g(7);
    std::uint64_t rays = 0;
    const vec3 eye(x.x, 1, 1);
    const rgb W = whitted_radiance(ls.sc, lights, ray(eye, x - eye), g, whitted_options{}, rays);
    INFO("whitted at " << deg << " degrees: " << W.x << ", expected " << expected);
    CHECK(double(W.x) == doctest::Approx(expected).epsilon(1e-5));
  }
}

TEST_CASE("custom light: emission sampling carries the spot's flux (BDPT and photon mapping start there)") {
  // E[Le / (pdf_position pdf_direction)] over emission samples is the flux of the one light.
  const loaded_scene ls = parse_scene(spot_scene, "spot.yaml", ".", course_lights());
  const light_set lights(ls.sc);
  const double expected = 2 * pi<double> * 8 * ((1 - std::cos(pi<double> / 9)) + (std::cos(pi<double> / 9) - std::cos(2 * pi<double> / 9)) / 2);
  rng g(11);
  double sum = 0;
  const int n = 200000;
  int samples = 0, delta = 0;
  for (int i = 0; i < n; ++i) {
    const auto e = lights.sample_emission(g.uniform(), vec2(g.uniform2()), vec2(g.uniform2()));
    if (!e) continue;
    ++samples, delta += e->delta_position ? 1 : 0;
    sum += double(e->Le.x) / (e->pdf_position * e->pdf_direction);
    if (i == 0) {
      CHECK(lights.pdf_emission_direction(0, vec3(0), e->direction) == doctest::Approx(e->pdf_direction));
      CHECK(lights.intensity_towards(0, e->direction) == e->Le);
    }
  }
  CHECK(samples == n);  // a light at a point: every sample is a delta in position
  CHECK(delta == n);
  CHECK(sum / n == doctest::Approx(expected).epsilon(0.01));
  // The power the light set chooses it by is the course's own.
  CHECK(lights.lights()[0].power == doctest::Approx(expected));
}

TEST_CASE("custom light: the door's errors and the kernel's refusal name the type") {
  // An unknown type lists the built-in ones and the registered ones.
  CHECK(error_of([] { (void)parse_scene("lights: [{type: sun}]", "t.yaml", ".", course_lights()); }) ==
        "t.yaml:1:17: lights[0].type: unknown light type 'sun' (expected point, quad or sphere; registered: spot)");
  // A course's key that its type does not take, and its own check, with their places.
  CHECK(error_of([] {
          (void)parse_scene("lights: [{type: spot, position: [0, 1, 0], axis: [0, -1, 0], colour: 1}]", "t.yaml", ".",
                            course_lights());
        }).find("lights[0].colour: unknown key for a spot") != std::string::npos);
  CHECK(error_of([] {
          (void)parse_scene("lights: [{type: spot, position: [0, 1, 0], axis: [0, -1, 0], inner: 50, outer: 40}]",
                            "t.yaml", ".", course_lights());
        }).find("lights[0].outer: the cone must have") != std::string::npos);
  // The built-in names are taken.
  scene_registry reg;
  for (const char* taken : {"point", "quad", "sphere"})
    CHECK(error_of([&] { reg.add_light(taken, {}, [](const scene_node&) { return light(); }); }) ==
          std::string("scene registry: light type '") + taken + "' is built in; a registered type must have a new name");
  // The OpenCL kernel cannot run C++ code: the packing refuses the light by its type's name.
  const loaded_scene ls = parse_scene(spot_scene, "spot.yaml", ".", course_lights());
  CHECK(error_of([&] { (void)pack_scene(ls.sc, 8, 8, path_options{}); }) ==
        "realtime: light 0 is of type 'spot', a course's light, which the OpenCL kernel cannot run; render it with "
        "your course's program built on zraka::pathtrace_main (its registry has 'spot'; chapter 2.3's pathtrace has "
        "the built-in kinds only)");
}

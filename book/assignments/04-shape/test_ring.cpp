// Assignment 04 tests: a ring as a zraka::user_shape_t. Built twice by
// book/assignments/CMakeLists.txt, against student/ring.hpp (must fail) and solution/ring.hpp
// (must pass).
#include "ring.hpp"

#include <zraka/app/testing.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/scene/scene.hpp>

#include <doctest/doctest.h>

#include <memory>

using namespace zraka;
using course::ring_t;
namespace zt = zraka::testing;

TEST_CASE_TEMPLATE("ring: hits at known places, misses in the hole and outside", T, float, double) {
  using V = vec3_t<T>;
  const ring_t<T> ring(V(0, 0, 0), V(0, 0, 1), T(0.5), T(1));
  hit_t<T> h;
  // Straight down onto the ring at radius 0.75: t = 2, the front face.
  REQUIRE(ring.intersect(ray_t<T>(V(0.75, 0, 2), V(0, 0, -1)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(2));
  CHECK(h.p.x == doctest::Approx(0.75));
  CHECK(std::abs(h.p.z) <= T(1e-6));
  CHECK(h.normal.z == doctest::Approx(1));
  CHECK(h.front_face);
  CHECK(h.uv.x == doctest::Approx(0.5));  // halfway from the inner to the outer rim
  // From below: the back face, the same outward normal.
  REQUIRE(ring.intersect(ray_t<T>(V(0, -0.6, -1), V(0, 0, 1)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(1));
  CHECK_FALSE(h.front_face);
  CHECK(h.normal.z == doctest::Approx(1));
  // The hole, outside, parallel, behind, beyond t_max.
  CHECK_FALSE(ring.intersect(ray_t<T>(V(0.2, 0.1, 1), V(0, 0, -1)), T(0), infinity<T>, h));
  CHECK_FALSE(ring.intersect(ray_t<T>(V(1.2, 0, 1), V(0, 0, -1)), T(0), infinity<T>, h));
  CHECK_FALSE(ring.intersect(ray_t<T>(V(0.7, 0, 1), V(1, 0, 0)), T(0), infinity<T>, h));
  CHECK_FALSE(ring.intersect(ray_t<T>(V(0.7, 0, 1), V(0, 0, 1)), T(0), infinity<T>, h));
  CHECK_FALSE(ring.intersect(ray_t<T>(V(0.7, 0, 1), V(0, 0, -1)), T(0), T(0.5), h));
}

TEST_CASE_TEMPLATE("ring: spawned rays never hit it again, at every scale", T, float, double) {
  std::vector<zt::result> checks;
  for (const double s : {1e-3, 1.0, 1e3}) {
    const ring_t<T> ring(vec3_t<T>(vec3(1, -2, 3) * s), vec3_t<T>(glm::normalize(vec3(1, 2, 2))), T(0.3 * s), T(s));
    const onb frame{vec3(ring.normal)};
    auto isect = [&](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) { return ring.intersect(r, t0, t1, h); };
    auto aim = [&](rng& g) {
      const double rad = s * (0.35 + 0.6 * g.uniform()), phi = 2 * pi<double> * g.uniform();
      const vec3 target = vec3(ring.center) + rad * std::cos(phi) * frame.t + rad * std::sin(phi) * frame.b;
      const vec3 from = vec3(ring.center) + 3 * s * sample_uniform_sphere(g.uniform2());
      return ray_t<T>(vec3_t<T>(from), vec3_t<T>(target - from));
    };
    checks.push_back(zt::no_self_hits<T>(isect, aim, 500));
  }
  const auto r = zt::all_of(checks);
  CHECK_MESSAGE(r.ok, r.message);
}

TEST_CASE("ring: bounds hold it, the area is pi (b^2 - a^2), the samples are uniform on it") {
  const ring_t<double> ring(vec3(1, 2, 3), glm::normalize(vec3(0, 1, 1)), 0.5, 2.0);
  CHECK(ring.area() == doctest::Approx(pi<double> * (4 - 0.25)));
  const aabb b = ring.bounds();
  REQUIRE_FALSE(b.empty());
  // The tight box: along x the ring reaches 2, along y and z 2 sqrt(1/2).
  CHECK(b.hi.x - b.lo.x == doctest::Approx(4));
  CHECK(b.hi.y - b.lo.y == doctest::Approx(4 * std::sqrt(0.5)));
  const onb frame(ring.normal);
  rng g(5);
  bool inside = true, on_plane = true;
  const auto r = zt::samples_follow_density(
      [&]() -> std::optional<vec2> {
        const auto p = ring.sample_area(g.uniform2());
        if (!p) return std::nullopt;
        const vec3 q = p->p - ring.center;
        inside = inside && p->p.x >= b.lo.x - 1e-12 && p->p.x <= b.hi.x + 1e-12 && p->p.y >= b.lo.y - 1e-12 &&
                 p->p.y <= b.hi.y + 1e-12 && p->p.z >= b.lo.z - 1e-12 && p->p.z <= b.hi.z + 1e-12;
        on_plane = on_plane && std::abs(glm::dot(q, ring.normal)) < 1e-12 && p->normal == ring.normal;
        // Uniform in area <=> (r^2 - a^2)/(b^2 - a^2) and the angle / 2 pi uniform on [0, 1)^2.
        const double x = glm::dot(q, frame.t), y = glm::dot(q, frame.b);
        return vec2((x * x + y * y - 0.25) / (4 - 0.25), (std::atan2(y, x) + pi<double>) / (2 * pi<double>));
      },
      [](double, double) { return 1.0; }, 100000, grid2{16, 16, 0, 1, 0, 1});
  CHECK_MESSAGE(r.ok, r.message);
  CHECK_MESSAGE(inside, "a sampled point lies outside bounds()");
  CHECK_MESSAGE(on_plane, "a sampled point is off the ring's plane, or its normal is not the ring's");
}

TEST_CASE("ring: as an area light over a floor it gives the closed form, found and sampled") {
  // A ring light facing down at height h, radiance Le, over a floor of albedo rho. Under its
  // centre the irradiance is E = pi Le (b^2/(h^2 + b^2) - a^2/(h^2 + a^2)), and the floor
  // reflects L = rho E / pi = 0.5 * 2 * (1/2 - 0.25/1.25) = 0.3.
  scene sc;
  const int floor = sc.add_material(material::lambertian(rgb(0.5f)));
  const int lamp = sc.add_material(material::emitter(rgb(2.0f)));
  sc.add(plane::from_point_normal(vec3(0), vec3(0, 1, 0)), floor);
  sc.add(std::make_shared<const ring_t<double>>(vec3(0, 1, 0), vec3(0, -1, 0), 0.5, 1.0), lamp);
  const ray r(vec3(2, 0.5, 0), vec3(-2, -0.5, 0));
  for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
    path_options o;
    o.method = m;
    o.max_depth = 3;
    const path_tracer tracer(sc, o);
    CHECK_MESSAGE((tracer.lights.size() == 1 && tracer.lights.hit_only().empty()),
                  "the ring is not sampled as a light: " << tracer.lights.describe());
    estimator e;
    std::uint64_t rays = 0;
    for (int i = 0; i < 40000; ++i) {
      rng g(9, 0, std::uint32_t(i));
      e.add(double(tracer(r, g, rays).x));
    }
    const auto res = zt::mean_within(e, 0.3, 5);
    CHECK_MESSAGE(res.ok, name(m) << ": " << res.message);
  }
}

// Assignment 01 tests: ray-cylinder intersection. Built twice by book/assignments/CMakeLists.txt,
// against student/cylinder.hpp (must fail) and solution/cylinder.hpp (must pass).
#include "cylinder.hpp"
#include "render.hpp"

#include <zraka/app/testing.hpp>
#include <zraka/sampling/sampling.hpp>

#include <doctest/doctest.h>

using namespace zraka;
using course::cylinder_t;
namespace zt = zraka::testing;

namespace {
// A random unit vector from the seeded generator.
template <class T> vec3_t<T> random_dir(rng& g) { return vec3_t<T>(sample_uniform_sphere(g.uniform2())); }

// Rays from a shell three sizes away towards a random point inside the solid: each must hit.
template <class T> auto aim_at(const cylinder_t<T>& c) {
  return [c](rng& g) {
    const vec3 axis(c.axis), base(c.base);
    const double size = std::max(double(c.radius), double(c.height));
    const vec3 centre = base + 0.5 * double(c.height) * axis;
    const onb frame(axis);
    const vec2 disk = sample_disk_concentric(g.uniform2());
    const vec3 inside = base + frame.to_world(vec3(0.9 * double(c.radius) * disk.x,
                                                   0.9 * double(c.radius) * disk.y,
                                                   double(c.height) * (0.05 + 0.9 * g.uniform())));
    const vec3 from = centre + 3.0 * size * sample_uniform_sphere(g.uniform2());
    return ray_t<T>(vec3_t<T>(from), vec3_t<T>(inside - from));
  };
}
template <class T> auto intersect_fn(const cylinder_t<T>& c) {
  return [c](const ray_t<T>& r, T t0, T t1, hit_t<T>& h) { return course::intersect(c, r, t0, t1, h); };
}
}  // namespace

TEST_CASE_TEMPLATE("cylinder: hits at known places", T, float, double) {
  using V = vec3_t<T>;
  const cylinder_t<T> c{V(0), V(0, 0, 1), T(1), T(2)};
  // Tolerance: 8 roundings of values of order 5 (float 2.4e-6, double 4.4e-15) -> 1e-5 / 1e-13.
  const T tol = std::is_same_v<T, float> ? T(1e-5) : T(1e-13);
  hit_t<T> h;
  // Side, from outside.
  REQUIRE(course::intersect(c, ray_t<T>(V(5, 0, 1), V(-1, 0, 0)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(4).epsilon(tol));
  CHECK(glm::length(h.p - V(1, 0, 1)) < tol);
  CHECK(glm::length(h.normal - V(1, 0, 0)) < tol);
  CHECK(h.front_face);
  // The same ray past its first hit leaves through the far side: the normal still points out.
  REQUIRE(course::intersect(c, ray_t<T>(V(5, 0, 1), V(-1, 0, 0)), T(4.5), infinity<T>, h));
  CHECK(h.t == doctest::Approx(6).epsilon(tol));
  CHECK(glm::length(h.normal - V(-1, 0, 0)) < tol);
  CHECK_FALSE(h.front_face);
  // Top cap and bottom cap.
  REQUIRE(course::intersect(c, ray_t<T>(V(0.5, 0.25, 5), V(0, 0, -1)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(3).epsilon(tol));
  CHECK(glm::length(h.normal - V(0, 0, 1)) < tol);
  REQUIRE(course::intersect(c, ray_t<T>(V(0.5, 0.25, -5), V(0, 0, 1)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(5).epsilon(tol));
  CHECK(glm::length(h.normal - V(0, 0, -1)) < tol);
  // From inside: the side at distance 1, hit from the back.
  REQUIRE(course::intersect(c, ray_t<T>(V(0, 0, 1), V(0, 1, 0)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(1).epsilon(tol));
  CHECK_FALSE(h.front_face);
  // A slanted ray through the side into the top cap's underside... from inside: exits the top.
  REQUIRE(course::intersect(c, ray_t<T>(V(0, 0, 1), V(0.3, 0, 1)), T(0), infinity<T>, h));
  CHECK(h.p.z == doctest::Approx(2).epsilon(tol));
  // Misses: above the top, parallel to the axis outside, behind the origin, beyond t_max.
  CHECK_FALSE(course::intersect(c, ray_t<T>(V(5, 0, 3), V(-1, 0, 0)), T(0), infinity<T>, h));
  CHECK_FALSE(course::intersect(c, ray_t<T>(V(2, 0, -5), V(0, 0, 1)), T(0), infinity<T>, h));
  CHECK_FALSE(course::intersect(c, ray_t<T>(V(5, 0, 1), V(1, 0, 0)), T(0), infinity<T>, h));
  CHECK_FALSE(course::intersect(c, ray_t<T>(V(5, 0, 1), V(-1, 0, 0)), T(0), T(3.5), h));
  // An invalid ray (zero direction) or cylinder (zero radius) is never hit.
  CHECK_FALSE(course::intersect(c, ray_t<T>(V(5, 0, 1), V(0)), T(0), infinity<T>, h));
  CHECK_FALSE(course::intersect(cylinder_t<T>{V(0), V(0, 0, 1), T(0), T(2)},
                                ray_t<T>(V(5, 0, 1), V(-1, 0, 0)), T(0), infinity<T>, h));
}

TEST_CASE_TEMPLATE("cylinder: any axis gives the same hits as the z axis, moved", T, float, double) {
  using V = vec3_t<T>;
  rng g(11);
  // Tolerance: the rotation adds a few roundings at coordinates of order 10: 1e-4 / 1e-12.
  const T tol = std::is_same_v<T, float> ? T(1e-4) : T(1e-12);
  for (int i = 0; i < 200; ++i) {
    const V axis = random_dir<T>(g);
    const onb_t<T> frame(axis);
    const V base = V(T(3), T(-1), T(2));
    const cylinder_t<T> local{V(0), V(0, 0, 1), T(0.7), T(1.5)};
    const cylinder_t<T> moved{base, axis, T(0.7), T(1.5)};
    const V o = random_dir<T>(g) * T(4), target(T(0.2), T(-0.1), T(0.8));
    const ray_t<T> rl(o, target - o);
    const ray_t<T> rw(base + frame.to_world(o), frame.to_world(target - o));
    hit_t<T> hl, hw;
    REQUIRE(course::intersect(local, rl, T(0), infinity<T>, hl));
    REQUIRE(course::intersect(moved, rw, T(0), infinity<T>, hw));
    CHECK(hw.t == doctest::Approx(hl.t).epsilon(tol));
    CHECK(glm::length(hw.normal - frame.to_world(hl.normal)) < tol);
    CHECK(glm::length(hw.p - (base + frame.to_world(hl.p))) < tol * T(10));
  }
}

TEST_CASE_TEMPLATE("cylinder: grazing rays", T, float, double) {
  using V = vec3_t<T>;
  const cylinder_t<T> c{V(0), V(0, 0, 1), T(1), T(2)};
  hit_t<T> h;
  // Tangent to the side: a hit, if reported, lies on the line x = 1 (no NaN).
  if (course::intersect(c, ray_t<T>(V(1, -5, 1), V(0, 1, 0)), T(0), infinity<T>, h)) {
    CHECK(is_finite(h.p));
    CHECK(std::abs(h.p.x - T(1)) < T(1e-3));
  }
  // Just inside the tangent: two close roots, the first taken; just outside: a miss.
  const T delta = std::is_same_v<T, float> ? T(1e-3) : T(1e-7);
  REQUIRE(course::intersect(c, ray_t<T>(V(1 - delta, -5, 1), V(0, 1, 0)), T(0), infinity<T>, h));
  CHECK(h.t < T(5));
  CHECK(is_finite(h.normal));
  CHECK_FALSE(course::intersect(c, ray_t<T>(V(1 + delta, -5, 1), V(0, 1, 0)), T(0), infinity<T>, h));
  // Parallel to the axis, on the side surface itself: enters through the bottom cap's rim.
  REQUIRE(course::intersect(c, ray_t<T>(V(1, 0, -5), V(0, 0, 1)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(5));
  // In the plane of the top cap: grazes along it, hitting the side at the rim.
  REQUIRE(course::intersect(c, ray_t<T>(V(-5, 0, 2), V(1, 0, 0)), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(4));
}

TEST_CASE_TEMPLATE("cylinder: watertight rim (rays through the rim never slip through)", T, float, double) {
  using V = vec3_t<T>;
  rng g(5);
  long slips = 0, total = 0;
  for (const double scale : {1e-3, 1.0, 1e3}) {
    const V axis = random_dir<T>(g);
    const cylinder_t<T> c{V(vec3(1.5, -2, 0.5) * scale), axis, T(0.8 * scale), T(1.3 * scale)};
    const onb frame{vec3(axis)};
    for (int i = 0; i < 2000; ++i) {
      // A point on the rim (bottom or top circle) and a direction from outside the wedge: u has
      // a positive component along the side's normal and along the cap's normal, so the ray
      // through the rim point goes into the solid.
      const double phi = 2 * pi<double> * g.uniform();
      const bool top = g.uniform() < 0.5;
      const vec3 radial(std::cos(phi), std::sin(phi), 0);
      const vec3 rim = vec3(c.base) + frame.to_world(double(c.radius) * radial +
                                                     vec3(0, 0, top ? double(c.height) : 0.0));
      const double a = 0.05 + 0.9 * g.uniform() * 0.5 * pi<double>;  // angle from the cap plane
      const vec3 u = frame.to_world(std::cos(a) * radial + vec3(0, 0, top ? std::sin(a) : -std::sin(a)));
      const vec3 from = rim + 2.0 * scale * u;
      hit_t<T> h;
      ++total;
      // A slip shows as no hit, or as the hit where the ray leaves the solid, far from the rim.
      // Tolerance: the rim point and the hit carry roundings of coordinates of order 2 scale,
      // 1e-4 scale in float, 1e-10 scale in double.
      const double near = (std::is_same_v<T, float> ? 1e-4 : 1e-10) * scale;
      if (!course::intersect(c, ray_t<T>(V(from), V(rim - from)), T(0), infinity<T>, h) ||
          !(glm::length(vec3(h.p) - rim) <= near))
        ++slips;
    }
  }
  CHECK_MESSAGE(slips == 0, slips << " of " << total << " rays through the rim slipped through");
}

TEST_CASE_TEMPLATE("cylinder: spawned rays never re-hit their own point, at every scale", T, float, double) {
  using V = vec3_t<T>;
  rng g(3);
  // Sizes 1e-4 .. 1e4, each 5 sizes away from the origin, about a random axis.
  const auto r = zt::across_scales(std::vector<T>{T(1e-4), T(1e-2), T(1), T(1e2), T(1e4)}, [&](T s) {
    const cylinder_t<T> c{V(vec3(3, -2, 1) * 5.0) * s, random_dir<T>(g), T(0.6) * s, T(1.7) * s};
    return zt::no_self_hits<T>(intersect_fn(c), aim_at(c), 1000);
  });
  CHECK_MESSAGE(r.ok, r.message);
}

TEST_CASE_TEMPLATE("cylinder: normals agree with the surface (finite differences)", T, float, double) {
  using V = vec3_t<T>;
  rng g(9);
  for (const T s : {T(1e-2), T(1), T(1e2)}) {
    const cylinder_t<T> c{V(1, 2, -1) * s, random_dir<T>(g), T(0.5) * s, T(1.2) * s};
    // Tolerance 1 degree: see testing.hpp (the error is ~1e-3 deg in float, 1e-6 in double).
    const auto r = zt::normal_matches_surface(intersect_fn(c), aim_at(c), 300, c.radius, 1.0);
    CHECK_MESSAGE(r.ok, r.message);
  }
}

TEST_CASE("cylinder: the picture matches target.png") {
  long hits = 0;
  const image img = course::render_normals(course::demo_cylinder(), 160, 120, hits);
  // Tolerance: the same program on another compiler may flip a few rim pixels; RMSE 0.02 allows
  // about 1% of the pixels to change completely, and the mean 0.01 a slight shift in outline.
  const auto r = zt::image_matches_file(img, ASSIGNMENT_DIR "/target.png", {0.02, 0.01, 1.0});
  CHECK_MESSAGE(r.ok, r.message);
}

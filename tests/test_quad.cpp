#include <zraka/core/rng.hpp>
#include <zraka/geometry/quad.hpp>

#include <doctest/doctest.h>

#include <limits>
#include <vector>

using namespace zraka;

TEST_CASE_TEMPLATE("quad: a ray through the middle hits at the right t, point and uv", T, float, double) {
  const parallelogram_t<T> q{{T(-1), T(-1), T(0)}, {T(2), T(0), T(0)}, {T(0), T(2), T(0)}};
  const ray_t<T> r({T(0.5), T(0), T(3)}, {T(0), T(0), T(-1)});
  hit_t<T> h;
  REQUIRE(intersect(q, r, T(0), infinity<T>, h));
  // All inputs are small binary fractions: the results are exact up to one rounding.
  CHECK(h.t == doctest::Approx(3).epsilon(1e-6));
  CHECK(h.p.x == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(h.p.z == T(0));  // Q.z + a u.z + b v.z is exactly zero
  CHECK(h.uv.x == doctest::Approx(0.75).epsilon(1e-6));
  CHECK(h.uv.y == doctest::Approx(0.5).epsilon(1e-6));
  CHECK(h.front_face);
  CHECK(h.normal == vec3_t<T>(0, 0, 1));
  // From below the ray sees the back face.
  REQUIRE(intersect(q, ray_t<T>({T(0), T(0), T(-2)}, {T(0), T(0), T(1)}), T(0), infinity<T>, h));
  CHECK_FALSE(h.front_face);
  CHECK(h.facing_normal() == vec3_t<T>(0, 0, -1));
}

TEST_CASE_TEMPLATE("quad: edges and corners are inside, just outside is not", T, float, double) {
  const parallelogram_t<T> q{{T(0), T(0), T(0)}, {T(1), T(0), T(0)}, {T(0), T(0), T(1)}};  // y = 0, N = -y
  hit_t<T> h;
  // The edge values 0 and 1 come out exact for these axis-aligned rays.
  for (T x : {T(0), T(1)})
    for (T z : {T(0), T(0.5), T(1)})
      CHECK(intersect(q, ray_t<T>({x, T(1), z}, {T(0), T(-1), T(0)}), T(0), infinity<T>, h));
  // One part in 1e3 outside, far above rounding for float and double.
  for (T x : {T(-1e-3), T(1.001)})
    CHECK_FALSE(intersect(q, ray_t<T>({x, T(1), T(0.5)}, {T(0), T(-1), T(0)}), T(0), infinity<T>, h));
  CHECK_FALSE(intersect(q, ray_t<T>({T(0.5), T(1), T(1.001)}, {T(0), T(-1), T(0)}), T(0), infinity<T>, h));
}

// n / |n|^2 squares the area: for tiny quads it underflows (w = inf: never hit) and for huge
// ones it overflows (w = 0: every point of the plane inside). Each size here is beyond that range
// for its precision; the quad is hit where it is and nowhere else.
TEST_CASE_TEMPLATE("quad: tiny and huge quads are hit where they are, not lost or spread over the plane", T, float, double) {
  const std::vector<T> sizes = sizeof(T) == 4 ? std::vector<T>{T(1e-12), T(1e-15), T(1e10), T(1e15)}
                                              : std::vector<T>{T(1e-80), T(1e-120), T(1e80), T(1e120)};
  for (const T s : sizes) {
    CAPTURE(s);
    const parallelogram_t<T> q{{-s / 2, -s / 2, T(0)}, {s, T(0), T(0)}, {T(0), s, T(0)}};
    REQUIRE(q.valid());
    const T d = glm::dot(glm::cross(q.u, q.v), glm::cross(q.u, q.v));
    CHECK_FALSE((d >= std::numeric_limits<T>::min() && d <= std::numeric_limits<T>::max()));  // the case
    hit_t<T> h;
    REQUIRE(intersect(q, ray_t<T>({s / 4, T(0), 3 * s}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
    CHECK(h.t == doctest::Approx(3 * s).epsilon(1e-5));
    CHECK(h.uv.x == doctest::Approx(0.75).epsilon(1e-5));
    CHECK(h.uv.y == doctest::Approx(0.5).epsilon(1e-5));
    CHECK(h.p.x == doctest::Approx(s / 4).epsilon(1e-5));
    CHECK_FALSE(intersect(q, ray_t<T>({s * T(0.6), T(0), 3 * s}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
    CHECK_FALSE(intersect(q, ray_t<T>({T(0), s * T(-0.6), 3 * s}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
    CHECK(occludes(q, ray_t<T>({s / 4, T(0), 3 * s}, {T(0), T(0), T(-1)}), T(0), infinity<T>));
  }
}

TEST_CASE_TEMPLATE("quad: parallel, behind, out of range, degenerate and NaN give no hit", T, float, double) {
  const parallelogram_t<T> q{{T(-1), T(-1), T(0)}, {T(2), T(0), T(0)}, {T(0), T(2), T(0)}};
  hit_t<T> h;
  CHECK_FALSE(intersect(q, ray_t<T>({T(0), T(0), T(1)}, {T(1), T(0), T(0)}), T(0), infinity<T>, h));
  CHECK_FALSE(intersect(q, ray_t<T>({T(0), T(0), T(0)}, {T(1), T(1), T(0)}), T(0), infinity<T>, h));  // in the plane
  CHECK_FALSE(intersect(q, ray_t<T>({T(0), T(0), T(1)}, {T(0), T(0), T(1)}), T(0), infinity<T>, h));  // away
  CHECK_FALSE(intersect(q, ray_t<T>({T(0), T(0), T(3)}, {T(0), T(0), T(-1)}), T(0), T(2), h));        // t_max
  const parallelogram_t<T> flat{{T(0), T(0), T(0)}, {T(1), T(0), T(0)}, {T(2), T(0), T(0)}};
  CHECK_FALSE(flat.valid());
  CHECK_FALSE(intersect(flat, ray_t<T>({T(0.5), T(1), T(0)}, {T(0), T(-1), T(0)}), T(0), infinity<T>, h));
  const T nan = std::numeric_limits<T>::quiet_NaN();
  CHECK_FALSE(intersect(q, ray_t<T>({nan, T(0), T(1)}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
  const parallelogram_t<T> bad{{nan, T(0), T(0)}, {T(1), T(0), T(0)}, {T(0), T(1), T(0)}};
  CHECK_FALSE(bad.valid());
  CHECK_FALSE(intersect(bad, ray_t<T>({T(0), T(0), T(1)}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
}

// pbrt-style reintersection test: random quads over many orders of magnitude of size and
// distance from the origin, hit from a random outside point; rays spawned from the hit in random
// directions (both sides) must never hit the quad again, and the hit point must lie within its
// stated error bound of the true plane.
TEST_CASE_TEMPLATE("quad: spawned rays never re-hit the quad, over 1e-4..1e4 scales", T, float, double) {
  rng g(2024);
  auto u = [&] { return T(g.uniform()); };
  auto dir = [&] {  // uniform-ish direction; need not be exactly uniform here
    const T z = T(2) * u() - T(1), phi = T(2) * pi<T> * u();
    const T s = std::sqrt(std::max(T(0), T(1) - z * z));
    return vec3_t<T>(s * std::cos(phi), s * std::sin(phi), z);
  };
  int hits = 0, rehits = 0;
  for (int i = 0; i < 1000; ++i) {
    const T size = std::pow(T(10), T(-4) + T(8) * u());
    const T place = std::pow(T(10), T(-4) + T(8) * u());
    const parallelogram_t<T> q{place * dir(), size * dir(), size * dir()};
    if (q.area() < T(0.05) * size * size) continue;  // skip slivers: not what this test is about
    const vec3_t<T> target = q.point(T(0.05) + T(0.9) * u(), T(0.05) + T(0.9) * u());
    const vec3_t<T> from = target + T(3) * size * dir();
    hit_t<T> h;
    if (!intersect(q, ray_t<T>(from, target - from), T(0), infinity<T>, h)) continue;
    ++hits;
    // The point is on the plane within p_error (measured in double with the quad's own normal).
    const vec3 n = vec3(q.normal());
    const double off = std::abs(glm::dot(n, vec3(h.p) - vec3(q.corner)));
    // Slack: the quad's normal itself is a few ulps off (8 eps of the distances involved).
    const double slack = 8 * double(std::numeric_limits<T>::epsilon()) *
                         (glm::length(vec3(q.corner)) + glm::length(vec3(h.p) - vec3(q.corner)));
    CHECK(off <= glm::dot(glm::abs(n), vec3(h.p_error)) + slack);
    for (int k = 0; k < 10; ++k) {
      hit_t<T> again;
      if (intersect(q, spawn_ray(h, dir()), T(0), infinity<T>, again)) ++rehits;
    }
  }
  CHECK(hits > 800);
  CHECK(rehits == 0);
}

// Shadow rays ask occludes(), which stops at quad_root's decision; it must agree with intersect()
// on every ray: rays from on, near and far from the quad, grazing ones, and invalid ones.
TEST_CASE_TEMPLATE("quad: occludes agrees with intersect, ray by ray", T, float, double) {
  rng g(23);
  auto u = [&](double lo, double hi) { return T(lo + (hi - lo) * g.uniform()); };
  for (int i = 0; i < 20000; ++i) {
    const T scale = std::pow(T(10), u(-3, 3));
    const parallelogram_t<T> q{vec3_t<T>(u(-1, 1), u(-1, 1), u(-1, 1)) * scale,
                               vec3_t<T>(u(-1, 1), u(-1, 1), u(-1, 1)) * scale,
                               vec3_t<T>(u(-1, 1), u(-1, 1), u(-1, 1)) * scale};
    vec3_t<T> o = vec3_t<T>(u(-2, 2), u(-2, 2), u(-2, 2)) * scale;
    if (i % 5 == 0) o = q.point(u(0, 1), u(0, 1));  // on the quad (up to rounding)
    vec3_t<T> d(u(-1, 1), u(-1, 1), u(-1, 1));
    if (i % 7 == 0) d = q.u + T(1e-6) * d;  // grazing
    if (i % 101 == 0) d = vec3_t<T>(std::numeric_limits<T>::quiet_NaN(), 0, 1);
    const ray_t<T> r(o, d);
    const T t_max = i % 3 == 0 ? infinity<T> : u(0, 4) * scale;
    hit_t<T> h;
    CHECK(occludes(q, r, T(0), t_max) == intersect(q, r, T(0), t_max, h));
  }
}

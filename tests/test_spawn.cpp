// Tests for spawn.hpp: the offset rule moves a ray origin off the surface by its error bound,
// to the side the new direction points to, and rounds away so it cannot fall back.
// (The full reintersection test over 1,000 spheres is in test_sphere.cpp.)
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/geometry/sphere.hpp>

#include <doctest/doctest.h>

#include <limits>

using namespace zraka;

namespace {
template <class T> vec3_t<T> random_unit(rng& g) {
  const double z = 1 - 2 * g.uniform(), phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}
}  // namespace

TEST_CASE_TEMPLATE("spawn: gamma(n) bounds n roundings", T, float, double) {
  const T u = std::numeric_limits<T>::epsilon() / 2;
  CHECK(gamma<T>(1) > u);
  CHECK(gamma<T>(1) < u * T(1.0001));
  CHECK(gamma<T>(5) > 5 * u);
  CHECK(gamma<T>(6) > gamma<T>(5));
}

TEST_CASE_TEMPLATE("spawn: the origin moves to the side w points to, by at least the bound", T,
                   float, double) {
  rng g(21);
  for (int i = 0; i < 10000; ++i) {
    const T scale = T(std::pow(10.0, g.uniform() * 16 - 8));
    const vec3_t<T> p = random_unit<T>(g) * scale;
    const vec3_t<T> n = random_unit<T>(g);
    const vec3_t<T> err = glm::abs(p) * gamma<T>(6);
    const vec3_t<T> w = random_unit<T>(g);
    const vec3_t<T> po = offset_origin(p, err, n, w);
    const T side = glm::dot(w, n) < T(0) ? T(-1) : T(1);
    // Every moved component moved away from p, in the direction of side * n.
    for (int c = 0; c < 3; ++c)
      if (n[c] != T(0)) CHECK((po[c] - p[c]) * side * n[c] > T(0));
    // And by at least d = |n|.err along the normal (computed in double for float).
    const double moved = side * glm::dot(vec3(po) - vec3(p), vec3(n));
    CHECK(moved >= 0.999 * double(glm::dot(glm::abs(n), err)));
  }
  // No error bound: the point stays exactly where it is.
  const vec3_t<T> p(1, 2, 3);
  CHECK(offset_origin(p, vec3_t<T>(0), vec3_t<T>(0, 0, 1), vec3_t<T>(0, 1, 0)) == p);
}

TEST_CASE_TEMPLATE("spawn: a shadow segment between two spheres hits neither end", T, float, double) {
  // From a hit on sphere A to a point on sphere B (a light): the segment must see neither A at
  // its start nor B at its end, but must see a sphere placed in between.
  rng g(22);
  long checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const T scale = T(std::pow(10.0, g.uniform() * 8 - 4));
    const sphere_t<T> A{random_unit<T>(g) * scale * T(3), scale * T(0.5)};
    const sphere_t<T> B{random_unit<T>(g) * scale * T(3) + vec3_t<T>(0, 10 * scale, 0), scale * T(0.5)};
    hit_t<T> ha, hb;
    // Hit A and B from far outside, on the sides facing each other.
    if (!intersect(A, ray_t<T>(B.center, A.center - B.center), T(0), infinity<T>, ha)) continue;
    if (!intersect(B, ray_t<T>(A.center, B.center - A.center), T(0), infinity<T>, hb)) continue;
    const segment_t<T> seg = spawn_segment(ha, hb.p);
    CHECK_FALSE(occludes(A, seg.ray, T(0), seg.t_max));
    CHECK_FALSE(occludes(B, seg.ray, T(0), seg.t_max));
    const sphere_t<T> blocker{(ha.p + hb.p) / T(2), glm::length(hb.p - ha.p) / T(10)};
    CHECK(occludes(blocker, seg.ray, T(0), seg.t_max));
    ++checked;
  }
  CHECK(checked > 1900);
}

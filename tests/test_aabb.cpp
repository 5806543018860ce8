// Axis-aligned boxes and the robust slab test (book 1.4, used by the BVH of 5.2).
#include <zraka/core/rng.hpp>
#include <zraka/geometry/aabb.hpp>
#include <zraka/geometry/triangle.hpp>

#include <doctest/doctest.h>

using namespace zraka;

namespace {
template <class T> aabb_t<T> unit_box() {
  aabb_t<T> b;
  b.grow(vec3_t<T>(-1));
  b.grow(vec3_t<T>(1));
  return b;
}
template <class T> constexpr T qnan = std::numeric_limits<T>::quiet_NaN();
}  // namespace

TEST_CASE_TEMPLATE("grow, unite, empty", T, float, double) {
  aabb_t<T> b;
  CHECK(b.empty());
  CHECK(b.extent() == vec3_t<T>(0));
  b.grow(vec3_t<T>(1, 2, 3));
  CHECK_FALSE(b.empty());  // a single point is a (flat) box
  CHECK(b.lo == b.hi);
  b.grow(vec3_t<T>(-1, 5, 0));
  CHECK(b.lo == vec3_t<T>(-1, 2, 0));
  CHECK(b.hi == vec3_t<T>(1, 5, 3));
  CHECK(b.contains(vec3_t<T>(0, 3, 1)));
  CHECK_FALSE(b.contains(vec3_t<T>(0, 6, 1)));
  const aabb_t<T> u = unite(b, aabb_t<T>());  // the empty box is the identity
  CHECK(u.lo == b.lo);
  CHECK(u.hi == b.hi);
  const aabb_t<T> w = unite(b, unit_box<T>());
  CHECK(w.lo == vec3_t<T>(-1, -1, -1));
  CHECK(w.hi == vec3_t<T>(1, 5, 3));
  CHECK(w.surface_area() == T(2) * (2 * 6 + 6 * 4 + 4 * 2));
}

TEST_CASE_TEMPLATE("rays along the axes", T, float, double) {
  const auto box = unit_box<T>();
  for (int a = 0; a < 3; ++a)
    for (const T s : {T(1), T(-1)}) {
      vec3_t<T> o(0), d(0);
      o[a] = -5 * s;
      d[a] = s;
      T t0 = 0, t1 = 0;
      REQUIRE(intersect(box, ray_t<T>(o, d), T(0), infinity<T>, &t0, &t1));
      CHECK(t0 == T(4));
      CHECK(t1 >= T(6));  // widened by 1 + 2 gamma(3), no more
      CHECK(t1 <= T(6) * (1 + 2 * gamma<T>(3)));
      CHECK_FALSE(intersect(box, ray_t<T>(o, -d), T(0), infinity<T>));  // pointing away
      CHECK_FALSE(intersect(box, ray_t<T>(o, d), T(0), T(3.5)));        // stops short
      // Offset sideways out of the box, parallel to it: a miss.
      vec3_t<T> side = o;
      side[(a + 1) % 3] = T(1.5);
      CHECK_FALSE(intersect(box, ray_t<T>(side, d), T(0), infinity<T>));
    }
}

TEST_CASE_TEMPLATE("zero direction components: rays in the planes of faces", T, float, double) {
  const auto box = unit_box<T>();
  // The origin lies exactly on the plane x = 1 (a face) and the ray runs in that plane: the box
  // is closed, so it is hit. A naive slab test computes 0 * inf = NaN here.
  CHECK(intersect(box, ray_t<T>(vec3_t<T>(1, -5, 0), vec3_t<T>(0, 1, 0)), T(0), infinity<T>));
  CHECK(intersect(box, ray_t<T>(vec3_t<T>(-1, -5, 1), vec3_t<T>(0, 1, 0)), T(0), infinity<T>));
  // Just outside the face: a miss.
  const T out = std::nextafter(T(1), T(2));
  CHECK_FALSE(
      intersect(box, ray_t<T>(vec3_t<T>(out, -5, 0), vec3_t<T>(0, 1, 0)), T(0), infinity<T>));
  // Negative zero components behave like positive ones.
  CHECK(intersect(box, ray_t<T>(vec3_t<T>(1, -5, 0), vec3_t<T>(-0.0, 1, -0.0)), T(0), infinity<T>));
  // A flat box (zero thickness in z), as around the teapot's flat bottom, hit straight on.
  aabb_t<T> flat;
  flat.grow(vec3_t<T>(-1, -1, 0));
  flat.grow(vec3_t<T>(1, 1, 0));
  T t0 = 0;
  CHECK(intersect(flat, ray_t<T>(vec3_t<T>(0.25, 0.5, 3), vec3_t<T>(0.1, 0, -1)), T(0), infinity<T>,
                  &t0));
  CHECK(t0 > T(0));
}

TEST_CASE_TEMPLATE("origin inside the box", T, float, double) {
  const auto box = unit_box<T>();
  rng g(1);
  for (int k = 0; k < 100; ++k) {
    const vec3_t<T> d(T(g.uniform() - 0.5), T(g.uniform() - 0.5), T(g.uniform() - 0.5));
    T t0 = -1, t1 = -1;
    REQUIRE(intersect(box, ray_t<T>(vec3_t<T>(0.1, 0.2, -0.3), d), T(0), infinity<T>, &t0, &t1));
    CHECK(t0 == T(0));  // entered at t_min: the origin is already inside
    CHECK(t1 > T(0));
    CHECK(t1 < T(4));  // the box's diagonal is 2 sqrt(3)
  }
}

TEST_CASE_TEMPLATE("NaN and invalid inputs are misses", T, float, double) {
  const auto box = unit_box<T>();
  const vec3_t<T> o(0, 0, -5), d(0, 0, 1);
  CHECK(intersect(box, ray_t<T>(o, d), T(0), infinity<T>));
  CHECK_FALSE(intersect(box, ray_t<T>(vec3_t<T>(qnan<T>, 0, -5), d), T(0), infinity<T>));
  CHECK_FALSE(intersect(box, ray_t<T>(o, vec3_t<T>(qnan<T>, 0, 1)), T(0), infinity<T>));
  CHECK_FALSE(intersect(box, ray_t<T>(o, vec3_t<T>(0)), T(0), infinity<T>));  // zero direction
  CHECK_FALSE(intersect(box, ray_t<T>(o, d), qnan<T>, infinity<T>));
  CHECK_FALSE(intersect(box, ray_t<T>(o, d), T(0), qnan<T>));
  aabb_t<T> bad = box;
  bad.hi.x = qnan<T>;
  CHECK_FALSE(intersect(bad, ray_t<T>(o, d), T(0), infinity<T>));          // a NaN box
  CHECK_FALSE(intersect(aabb_t<T>(), ray_t<T>(o, d), T(0), infinity<T>));  // the empty box
  // From inside the empty box's "range" along a zero component too.
  CHECK_FALSE(intersect(aabb_t<T>(), ray_t<T>(vec3_t<T>(0), d), T(0), infinity<T>));
}

TEST_CASE_TEMPLATE("a box around a triangle is hit by every ray that hits the triangle", T, float,
                   double) {
  // The widening of t_max (Ize 2013) at work: thin triangles far from the origin, rays aimed at
  // their vertices and edges, where the triangle test and the slab test both round their worst.
  rng g(42);
  int hits = 0;
  for (int k = 0; k < 20000; ++k) {
    const vec3_t<T> c = vec3_t<T>(T(1e3 * g.uniform()), T(1e3 * g.uniform()), T(1e3 * g.uniform()));
    triangle_t<T> tri{c, c + vec3_t<T>(T(g.uniform()), 0, T(1e-3 * g.uniform())),
                      c + vec3_t<T>(0, T(g.uniform()), T(1e-3 * g.uniform()))};
    aabb_t<T> box;
    box.grow(tri.a);
    box.grow(tri.b);
    box.grow(tri.c);
    const T w = T(g.uniform()), s = T(g.uniform());  // a point on an edge or at a vertex
    const vec3_t<T> target = k % 2 ? (1 - w) * tri.a + w * tri.b : (k % 3 ? tri.c : tri.a);
    const vec3_t<T> o(T(-50 + 10 * s), T(-70), T(2e3));
    const ray_t<T> r(o, target - o);
    hit_t<T> h;
    if (intersect(tri, r, T(0), infinity<T>, h)) {
      ++hits;
      CHECK(intersect(box, r, T(0), h.t * (1 + 2 * gamma<T>(3))));
      CHECK(intersect(box, r, T(0), infinity<T>));
    }
  }
  CHECK(hits > 1000);  // the test exercises something
}

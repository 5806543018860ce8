// Tests for ray.hpp: R(t) = O + tD with a unit direction (book 1.1, thesis Remark 1.1.3, B1).
#include <zraka/core/ray.hpp>

#include <doctest/doctest.h>

#include <limits>

using namespace zraka;

TEST_CASE_TEMPLATE("ray: the stored direction is unit length for any finite non-zero input", T,
                   float, double) {
  // 1e200 and 1e-200 for double; for float the extremes of its range. |d|^2 would overflow or
  // underflow; normalize_or_zero scales first. Tolerance: 4 ulps of 1 (a few roundings).
  const T huge = sizeof(T) == 4 ? T(1e37) : T(1e200), tiny = sizeof(T) == 4 ? T(1e-37) : T(1e-200);
  for (T s : {huge, tiny, std::numeric_limits<T>::denorm_min(), T(1), T(-3)})
    for (vec3_t<T> d : {vec3_t<T>(1, 2, 3), vec3_t<T>(0, 0, 1), vec3_t<T>(-1, 1e-3, 7)}) {
      const ray_t<T> r({T(0), T(0), T(0)}, d * s);
      CHECK(r.valid());
      CHECK(std::abs(glm::length(r.direction) - T(1)) <= 4 * std::numeric_limits<T>::epsilon());
      // Same direction as the input actually passed (at denorm_min, 1e-3 * s is already 0):
      // the reference direction is that vector, rescaled and normalised in long double.
      const vec3_t<T> in = d * s;
      const long double m = std::max({std::abs((long double)in.x), std::abs((long double)in.y),
                                      std::abs((long double)in.z)});
      const glm::vec<3, long double> v = glm::vec<3, long double>(in) / m;
      const vec3_t<T> unit_d(v / std::sqrt(glm::dot(v, v)));
      CHECK(glm::length(glm::cross(r.direction, unit_d)) <= 8 * std::numeric_limits<T>::epsilon());
      CHECK(glm::dot(r.direction, unit_d) > T(0));
    }
}

TEST_CASE_TEMPLATE("ray: zero, NaN or inf direction gives the zero direction and valid() false", T,
                   float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>;
  for (vec3_t<T> d : {vec3_t<T>(0), vec3_t<T>(nan, 0, 0), vec3_t<T>(0, 1, nan),
                      vec3_t<T>(inf, 0, 0), vec3_t<T>(1, -inf, 1)}) {
    const ray_t<T> r({T(1), T(2), T(3)}, d);
    CHECK(r.direction == vec3_t<T>(0));
    CHECK_FALSE(r.valid());
    CHECK(r.at(T(5)) == r.origin);  // it goes nowhere, and never NaN
  }
  CHECK_FALSE(ray_t<T>({nan, T(0), T(0)}, {T(0), T(0), T(1)}).valid());
  CHECK(ray_t<T>().valid());  // the default ray: origin 0, looking along +z
}

TEST_CASE_TEMPLATE("ray: at(t) = O + t D, and t is a distance", T, float, double) {
  const ray_t<T> r({T(1), T(2), T(3)}, {T(0), T(3), T(4)});  // |d| = 5, stored as (0, .6, .8)
  CHECK(r.at(T(0)) == r.origin);
  for (T t : {T(0.5), T(1), T(10), T(-2)}) {
    const vec3_t<T> p = r.at(t);
    CHECK(p.x == T(1));
    CHECK(p.y == doctest::Approx(2 + 0.6 * t));
    CHECK(p.z == doctest::Approx(3 + 0.8 * t));
    CHECK(glm::length(p - r.origin) == doctest::Approx(std::abs(t)));
  }
}

// Tests for vec.hpp: the vector helpers of book 1.0 (Def 1.0.4-1.0.6) and normalize_or_zero.
#include <zraka/core/rng.hpp>
#include <zraka/core/vec.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

using namespace zraka;

namespace {
template <class T> vec3_t<T> random_vec(rng& g, double scale) {
  return vec3_t<T>(vec3(g.uniform() - 0.5, g.uniform() - 0.5, g.uniform() - 0.5) * (2 * scale));
}
}  // namespace

TEST_CASE_TEMPLATE("vec: dot, norm, cross follow Def 1.0.4-1.0.6", T, float, double) {
  const vec3_t<T> a(1, 2, 3), b(-4, 5, 0.5);
  CHECK(glm::dot(a, b) == T(1 * -4 + 2 * 5 + 3 * 0.5));
  CHECK(length2(a) == T(14));
  CHECK(glm::length(a) == doctest::Approx(std::sqrt(14.0)));
  // Determinant expansion, written out.
  const vec3_t<T> c = glm::cross(a, b);
  CHECK(c == vec3_t<T>(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x));
  // Right-handed: x cross y = z.
  CHECK(glm::cross(vec3_t<T>(1, 0, 0), vec3_t<T>(0, 1, 0)) == vec3_t<T>(0, 0, 1));
}

TEST_CASE_TEMPLATE("vec: |a x b| = |a||b| sin(theta), perpendicular to both (Remark 1.0.7)", T,
                   float, double) {
  rng g(1);
  double worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3_t<T> a = random_vec<T>(g, 10), b = random_vec<T>(g, 10);
    const vec3_t<T> c = glm::cross(a, b);
    // theta from atan2(|a x b|, a.b) would be circular; take it from the law of cosines in
    // double and compare the areas in double.
    const double la = glm::length(vec3(a)), lb = glm::length(vec3(b));
    const double cos_t = glm::dot(vec3(a), vec3(b)) / (la * lb);
    const double area = la * lb * std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
    const double err = std::abs(double(glm::length(c)) - area) / (la * lb);
    worst = std::max(worst, err);
    // Tolerance: a few roundings relative to |a||b|, and 1 - cos^2 loses digits when
    // theta is tiny; 1e-4 (float) / 1e-7 (double) relative to |a||b| covers both.
    CHECK(err < (sizeof(T) == 4 ? 1e-4 : 1e-7));
    // (a x b).a: each product is rounded, error about 4 eps |a|^2 |b|; bound 1e-5 (float) or
    // 1e-13 (double) relative to |a|^2 |b|, i.e. about 80 / 450 eps.
    CHECK(std::abs(double(glm::dot(c, a))) <= 1e-5 * la * la * lb * (sizeof(T) == 4 ? 1 : 1e-8));
  }
  MESSAGE(std::string(sizeof(T) == 4 ? "[float]" : "[double]") << " worst | |a x b| - |a||b| sin | / |a||b| = " << worst);
}

TEST_CASE_TEMPLATE("vec: normalize_or_zero for huge, tiny, zero, NaN and inf", T, float, double) {
  const T huge = std::numeric_limits<T>::max() / 4, tiny = std::numeric_limits<T>::denorm_min();
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>;
  // Tolerance: doctest's Approx (relative 100 float-eps = 1.2e-5); at denorm_min the input
  // (3, -4, 0) * s is itself exact (3 and 4 times the smallest subnormal), so any real failure
  // of the scaling shows up as 0, inf or NaN, far outside it.
  for (T s : {huge, tiny, T(1), std::numeric_limits<T>::min()}) {
    const vec3_t<T> n = normalize_or_zero(vec3_t<T>(3, -4, 0) * s);
    CHECK(n.x == doctest::Approx(0.6));
    CHECK(n.y == doctest::Approx(-0.8));
    CHECK(n.z == T(0));
    // The naive v / |v| fails at these scales: |v|^2 overflows to inf or underflows to 0.
    if (s != T(1)) {
      const vec3_t<T> naive = glm::normalize(vec3_t<T>(3, -4, 0) * s);
      CHECK_FALSE((is_finite(naive) && std::abs(glm::length(naive) - T(1)) < T(1e-3)));
    }
  }
  // (1, NaN, 1): a max over components can skip the NaN; the result must still be zero.
  for (vec3_t<T> v : {vec3_t<T>(0), vec3_t<T>(nan, 1, 1), vec3_t<T>(1, nan, 1),
                      vec3_t<T>(1, 1, nan), vec3_t<T>(inf, 0, 0), vec3_t<T>(1, -inf, 0),
                      vec3_t<T>(0, 0, -0.0)})
    CHECK(normalize_or_zero(v) == vec3_t<T>(0));
}

// The unscaled division runs only where ||v||^2 is in [2^-60, 2^60] (float) or [2^-500, 2^500]
// (double). Across both edges, and with components too small to count beside the largest, the
// result agrees with the scaled form to 2 ulps and is unit to 3 ulps.
TEST_CASE_TEMPLATE("vec: normalize_or_zero is the same on both sides of its fast range", T, float, double) {
  const int edge = sizeof(T) == 4 ? 30 : 250;  // ||v|| = 2^edge: ||v||^2 at the range's end
  const T eps = std::numeric_limits<T>::epsilon();
  auto scaled = [](const vec3_t<T>& v) {  // the careful form alone
    const vec3_t<T> s = v / max_component(glm::abs(v));
    return s / std::sqrt(glm::dot(s, s));
  };
  rng g(7);
  for (int e : {-edge - 1, -edge, -edge + 1, 0, edge - 1, edge, edge + 1})
    for (int i = 0; i < 200; ++i) {
      const T scale = std::ldexp(T(1), e);
      vec3_t<T> v = random_vec<T>(g, 1.0) * scale;
      if (i % 4 == 0) v.y = std::ldexp(T(1), e - 40), v.z = std::numeric_limits<T>::denorm_min();  // squares that underflow
      if (v == vec3_t<T>(0)) continue;
      const vec3_t<T> n = normalize_or_zero(v), m = scaled(v);
      INFO("scale 2^", e, ", v = (", v.x, ", ", v.y, ", ", v.z, ")");
      for (int a = 0; a < 3; ++a) CHECK(std::abs(n[a] - m[a]) <= 2 * eps);
      CHECK(std::abs(glm::length(n) - T(1)) <= 3 * eps);
    }
}

TEST_CASE_TEMPLATE("vec: is_finite, max_component, constants", T, float, double) {
  CHECK(is_finite(vec3_t<T>(1, 2, 3)));
  CHECK_FALSE(is_finite(vec3_t<T>(1, std::numeric_limits<T>::quiet_NaN(), 3)));
  CHECK_FALSE(is_finite(vec3_t<T>(1, 2, -infinity<T>)));
  CHECK(max_component(vec3_t<T>(-5, 2, 1)) == T(2));
  CHECK(pi<T> == T(3.14159265358979323846));
  CHECK(std::isinf(infinity<T>));
}

// abs3 clears the sign bits (glm::abs keeps -0 as -0 and is a branch per component): the
// magnitudes of every kind of float, -0 made +0, NaN kept NaN, and the same as glm::abs wherever
// that is a number other than a zero.
TEST_CASE_TEMPLATE("vec: abs3 for -0, NaN, inf, subnormal and huge components", T, float, double) {
  using lim = std::numeric_limits<T>;
  const vec3_t<T> a = abs3(vec3_t<T>(T(-0.0), -lim::denorm_min(), -lim::max()));
  CHECK(a == vec3_t<T>(0, lim::denorm_min(), lim::max()));
  CHECK_FALSE(std::signbit(a.x));
  const vec3_t<T> b = abs3(vec3_t<T>(-lim::quiet_NaN(), -infinity<T>, T(2.5)));
  CHECK(std::isnan(b.x));
  CHECK(b.y == infinity<T>);
  CHECK(b.z == T(2.5));
  for (const T x : {T(-3), T(1e-30), T(-1e30), T(7)}) {
    const vec3_t<T> v(x, -x, x * 2);
    CHECK(abs3(v) == glm::abs(v));
  }
}

// Tests for onb.hpp: the basis is orthonormal and right-handed for every unit normal, including
// the directions where the usual cross(n, fixed axis) recipe breaks down.
#include <zraka/core/onb.hpp>
#include <zraka/core/rng.hpp>

#include <doctest/doctest.h>

#include <limits>
#include <string>

using namespace zraka;

namespace {
// Worst deviation from an orthonormal right-handed frame: | |t|-1 |, |t.b|, |t x b - n| etc.
template <class T> double deviation(const onb_t<T>& f) {
  const double e[] = {
      std::abs(double(glm::length(f.t)) - 1), std::abs(double(glm::length(f.b)) - 1),
      std::abs(double(glm::length(f.n)) - 1), std::abs(double(glm::dot(f.t, f.b))),
      std::abs(double(glm::dot(f.t, f.n))),   std::abs(double(glm::dot(f.b, f.n))),
      double(glm::length(glm::cross(f.t, f.b) - f.n))};  // right-handed: t x b = n
  double worst = 0;
  for (double x : e) worst = std::isfinite(x) ? std::max(worst, x) : infinity<double>;
  return worst;
}
// Tolerance: a handful of roundings on unit-size numbers; 8 eps covers the construction (about
// 3 roundings per component) plus the checks' own dot/cross roundings.
template <class T> constexpr double tolerance = 8 * std::numeric_limits<T>::epsilon();
}  // namespace

TEST_CASE_TEMPLATE("onb: the axes, signed zeros and near -z", T, float, double) {
  const T tiny = std::numeric_limits<T>::min();
  const vec3_t<T> dirs[] = {
      {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, 0, T(-0.0)},
      {T(-0.0), T(-0.0), -1}, normalize_or_zero(vec3_t<T>(tiny, 0, -1)),
      normalize_or_zero(vec3_t<T>(T(1e-4), T(-1e-4), -1)), normalize_or_zero(vec3_t<T>(1, 1, 1)),
      normalize_or_zero(vec3_t<T>(std::numeric_limits<T>::epsilon(), 0, -1))};
  for (const vec3_t<T>& n : dirs) {
    if (n == vec3_t<T>(0, 0, T(-0.0))) continue;  // not a unit vector; listed to show it is skipped
    const onb_t<T> f(n);
    CAPTURE(n.x);
    CAPTURE(n.y);
    CAPTURE(n.z);
    CHECK(deviation(f) <= tolerance<T>);
    CHECK(f.n == n);
  }
}

TEST_CASE_TEMPLATE("onb: 10k random directions, worst deviation", T, float, double) {
  rng g(3);
  double worst = 0;
  for (int i = 0; i < 10000; ++i) {
    const double z = 1 - 2 * g.uniform(), phi = 2 * pi<double> * g.uniform();
    const double s = std::sqrt(std::max(0.0, 1 - z * z));
    const vec3_t<T> n = normalize_or_zero(vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z)));
    worst = std::max(worst, deviation(onb_t<T>(n)));
  }
  MESSAGE(std::string(sizeof(T) == 4 ? "[float]" : "[double]") << " onb: worst deviation over 10k random "
          << "directions " << worst << " = " << worst / std::numeric_limits<T>::epsilon() << " eps");
  CHECK(worst <= tolerance<T>);
}

TEST_CASE_TEMPLATE("onb: to_world and to_local are inverse; +z maps to n", T, float, double) {
  const onb_t<T> f(normalize_or_zero(vec3_t<T>(0.3, -0.2, 0.9)));
  CHECK(glm::length(f.to_world(vec3_t<T>(0, 0, 1)) - f.n) <= tolerance<T>);
  const vec3_t<T> v(0.25, -1.5, 2);
  CHECK(glm::length(f.to_world(f.to_local(v)) - v) <= 4 * tolerance<T>);
  CHECK(glm::length(f.to_local(f.to_world(v)) - v) <= 4 * tolerance<T>);
}

// Tests for camera.hpp: where primary rays go, and the thin lens.
#include <zraka/cameras/camera.hpp>

#include <doctest/doctest.h>

#include <limits>

using namespace zraka;

namespace {
template <class T> double angle(const vec3_t<T>& a, const vec3_t<T>& b) {
  const vec3 x = normalize_or_zero(vec3(a)), y = normalize_or_zero(vec3(b));
  return std::atan2(glm::length(glm::cross(x, y)), glm::dot(x, y));
}
// Tolerance for angles: a few roundings of tan/sqrt on unit-size numbers, 1e-5 rad (float),
// 1e-12 rad (double).
template <class T> constexpr double tol = sizeof(T) == 4 ? 1e-5 : 1e-12;
template <class T> camera_t<T> test_camera() {
  camera_t<T> c;
  c.position = {T(1), T(2), T(3)};
  c.look_at = {T(-2), T(0.5), T(-4)};
  c.vfov_degrees = T(50);
  c.aspect = T(1.5);
  return c;
}
}  // namespace

TEST_CASE_TEMPLATE("camera: the centre ray points at look_at", T, float, double) {
  const camera_t<T> c = test_camera<T>();
  const auto cam = c.prepare();
  const ray_t<T> r = cam.generate(T(0.5), T(0.5));
  CHECK(r.origin == c.position);
  CHECK(angle(r.direction, c.look_at - c.position) <= tol<T>);
}

TEST_CASE_TEMPLATE("camera: edge rays make half the field of view, corners the diagonal", T, float,
                   double) {
  const camera_t<T> c = test_camera<T>();
  const auto cam = c.prepare();
  const vec3_t<T> centre = cam.generate(T(0.5), T(0.5)).direction;
  const double half_v = 25 * pi<double> / 180, tan_v = std::tan(half_v);
  CHECK(angle(cam.generate(T(0.5), T(0)).direction, centre) == doctest::Approx(half_v).epsilon(tol<T>));
  CHECK(angle(cam.generate(T(0.5), T(1)).direction, centre) == doctest::Approx(half_v).epsilon(tol<T>));
  CHECK(angle(cam.generate(T(0), T(0.5)).direction, centre) ==
        doctest::Approx(std::atan(1.5 * tan_v)).epsilon(tol<T>));
  const double diag = std::atan(tan_v * std::sqrt(1 + 1.5 * 1.5));
  for (T s : {T(0), T(1)})
    for (T t : {T(0), T(1)})
      CHECK(angle(cam.generate(s, t).direction, centre) == doctest::Approx(diag).epsilon(tol<T>));
  // Orientation: t = 0 is the top (towards up), s = 1 is the right (up x backward = right).
  const vec3_t<T> w = normalize_or_zero(c.position - c.look_at);
  const vec3_t<T> right = normalize_or_zero(glm::cross(c.up, w));
  CHECK(glm::dot(cam.generate(T(0.5), T(0)).direction, c.up) > glm::dot(centre, c.up));
  CHECK(glm::dot(cam.generate(T(1), T(0.5)).direction, right) > T(0));
}

TEST_CASE_TEMPLATE("camera: thin lens rays of one pixel meet on the focus plane", T, float, double) {
  camera_t<T> c = test_camera<T>();
  c.aperture = T(0.5);
  c.focus_distance = T(6);
  const auto cam = c.prepare();
  const vec3_t<T> forward = -normalize_or_zero(c.position - c.look_at);
  for (T s : {T(0.1), T(0.5), T(0.93)})
    for (T t : {T(0.2), T(0.77)}) {
      vec3 first(0);
      double spread = 0, lens_spread = 0;
      for (int k = 0; k < 16; ++k) {
        const T lu = T((k % 4 + 0.5) / 4), lv = T((k / 4 + 0.5) / 4);
        const ray_t<T> r = cam.generate(s, t, lu, lv);
        // The lens is the plane through the position perpendicular to the view direction.
        CHECK(std::abs(double(glm::dot(r.origin - c.position, forward))) <= tol<T> * 10);
        CHECK(glm::length(vec3(r.origin - c.position)) <= 0.25 * (1 + tol<T>));
        const T tf = c.focus_distance / glm::dot(r.direction, forward);
        const vec3 p = vec3(r.at(tf));
        if (k == 0) first = p;
        spread = std::max(spread, glm::length(p - first));
        lens_spread = std::max(lens_spread, glm::length(vec3(r.origin - c.position)));
      }
      CHECK(lens_spread > 0.1);                   // the rays really start at different points
      CHECK(cam.generate(s, t).origin == c.position);  // no lens sample: the lens centre
      // ... and meet in one point: coordinates ~5 units with a few roundings each (normalise,
      // divide, multiply-add): 1e-4 (float) / 1e-12 (double) is about 100 ulps of 5.
      CHECK(spread <= (sizeof(T) == 4 ? 1e-4 : 1e-12));
    }
}

TEST_CASE_TEMPLATE("camera: settings that define no camera are refused", T, float, double) {
  camera_t<T> c;
  c.look_at = c.position;
  CHECK_THROWS_WITH_AS(c.prepare(), doctest::Contains("position equals look_at"), error);
  c = camera_t<T>();
  c.up = {T(0), T(0), T(2)};  // parallel to the view direction
  CHECK_THROWS_AS(c.prepare(), error);
  for (T fov : {T(0), T(180), T(-10), std::numeric_limits<T>::quiet_NaN()}) {
    c = camera_t<T>();
    c.vfov_degrees = fov;
    CHECK_THROWS_WITH_AS(c.prepare(), doctest::Contains("vfov_degrees"), error);
  }
  c = camera_t<T>();
  c.aspect = T(0);
  CHECK_THROWS_AS(c.prepare(), error);
  c = camera_t<T>();
  c.aperture = T(-1);
  CHECK_THROWS_AS(c.prepare(), error);
}

// Assignment 00 (the template) tests. Built twice by book/assignments/CMakeLists.txt: against
// student/reflect.hpp (must fail) and solution/reflect.hpp (must pass).
#include "reflect.hpp"  // the student's file, by its bare name: CMake picks the folder

#include <zraka/app/testing.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/sampling.hpp>

#include <doctest/doctest.h>

using namespace zraka;
namespace zt = zraka::testing;

TEST_CASE_TEMPLATE("reflect: known values", T, float, double) {
  using V = vec3_t<T>;
  // Exact: one subtraction of exactly representable values.
  CHECK(course::reflect(V(1, -1, 0), V(0, 1, 0)) == V(1, 1, 0));
  CHECK(course::reflect(V(0, 0, -1), V(0, 0, 1)) == V(0, 0, 1));
  CHECK(course::reflect(V(1, 0, 0), V(0, 0, 1)) == V(1, 0, 0));  // grazing: unchanged
}

TEST_CASE_TEMPLATE("reflect: keeps the length and mirrors the angle", T, float, double) {
  rng g(1);
  // One check on the worst case over 1000 random pairs, so a wrong answer prints one line.
  // Tolerance: a few roundings of unit values, 8 eps.
  const T tol = T(8) * std::numeric_limits<T>::epsilon();
  T worst = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3_t<T> n(sample_uniform_sphere(g.uniform2())), d(sample_uniform_sphere(g.uniform2()));
    const vec3_t<T> r = course::reflect(d, n);
    worst = std::max({worst, std::abs(glm::length(r) - T(1)),             // length kept
                      std::abs(glm::dot(r, n) + glm::dot(d, n)),          // normal part flipped
                      glm::length((r - glm::dot(r, n) * n) - (d - glm::dot(d, n) * n))});  // tangent kept
  }
  CHECK_MESSAGE(worst < T(4) * tol, "worst error " << worst << " (allowed " << T(4) * tol << ")");
}

TEST_CASE("reflect: the mean cosine after reflection (a testing.hpp check)") {
  // For d uniform over the directions towards the surface (d.n < 0), r.n = |d.n| has mean 1/2.
  rng g(2);
  const vec3 n(0, 0, 1);
  const auto r = zt::mean_within([&] {
    const vec3 d = -sample_uniform_hemisphere(g.uniform2());
    return glm::dot(course::reflect(d, n), n);
  }, 10000, 0.5);
  CHECK_MESSAGE(r.ok, r.message);
}

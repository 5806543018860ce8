// Tests for hit.hpp: the hit record's defaults and face orientation.
#include <zraka/core/hit.hpp>

#include <doctest/doctest.h>

using namespace zraka;

TEST_CASE_TEMPLATE("hit: defaults say 'nothing hit yet'", T, float, double) {
  const hit_t<T> h;
  CHECK(h.t == infinity<T>);
  CHECK(h.p_error == vec3_t<T>(0));
  CHECK(h.front_face);
}

TEST_CASE_TEMPLATE("hit: set_face and facing_normal", T, float, double) {
  hit_t<T> h;
  h.normal = {T(0), T(1), T(0)};
  h.set_face({T(0), T(-1), T(0)});  // coming down onto an upward normal: from the outside
  CHECK(h.front_face);
  CHECK(h.facing_normal() == vec3_t<T>(0, 1, 0));
  h.set_face({T(0.5), T(0.5), T(0)});  // leaving through the surface: from the inside
  CHECK_FALSE(h.front_face);
  CHECK(h.facing_normal() == vec3_t<T>(0, -1, 0));
  // The facing normal always opposes the incoming direction.
  for (vec3_t<T> d : {vec3_t<T>(1, -2, 0), vec3_t<T>(-1, 3, 1), vec3_t<T>(0, 1e-6, 1)}) {
    h.set_face(d);
    CHECK(glm::dot(h.facing_normal(), d) < T(0));
  }
}

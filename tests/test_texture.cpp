#include <zraka/texture.hpp>

#include <doctest/doctest.h>

using namespace zraka;

TEST_CASE("texture: the checker alternates and ignores rounding across the surface's own plane") {
  const texture t = texture::checker(rgb(1), rgb(0), 0.5);
  const vec3 up(0, 1, 0);
  CHECK(evaluate(t, vec3(0.1, 0, 0.1), up) == rgb(1));
  CHECK(evaluate(t, vec3(0.6, 0, 0.1), up) == rgb(0));
  CHECK(evaluate(t, vec3(0.6, 0, 0.6), up) == rgb(1));
  CHECK(evaluate(t, vec3(-0.1, 0, 0.1), up) == rgb(0));  // floor, not truncation towards zero
  // Hit points a rounding above or below the floor plane get the same cell.
  CHECK(evaluate(t, vec3(0.1, 1e-17, 0.1), up) == evaluate(t, vec3(0.1, -1e-17, 0.1), up));
  // A wall x = 0 uses y and z.
  CHECK(evaluate(t, vec3(-1e-17, 0.1, 0.1), vec3(1, 0, 0)) == evaluate(t, vec3(1e-17, 0.1, 0.1), vec3(1, 0, 0)));
  CHECK(evaluate(texture::solid(rgb(0.3f)), vec3(5, 5, 5), up) == rgb(0.3f));
}

#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

#include <algorithm>

using namespace zraka;

namespace {
vec3 random_dir(rng& g) { return sample_uniform_sphere(g.uniform2()); }

scene random_scene(rng& g) {
  scene sc;
  const int grey = sc.add_material(material::lambertian(rgb(0.5f)));
  for (int i = 0; i < 12; ++i) sc.add(sphere{3.0 * random_dir(g), 0.2 + g.uniform()}, grey);
  for (int i = 0; i < 8; ++i) sc.add(quad{3.0 * random_dir(g), 2.0 * random_dir(g), 2.0 * random_dir(g)}, grey);
  return sc;
}
}  // namespace

TEST_CASE("scene: nearest_hit is the minimum over every object, whatever their order") {
  rng g(77);
  int hits = 0;
  for (int k = 0; k < 20; ++k) {
    scene sc = random_scene(g);
    scene reversed = sc;
    std::reverse(reversed.spheres.begin(), reversed.spheres.end());
    std::reverse(reversed.quads.begin(), reversed.quads.end());
    for (int i = 0; i < 200; ++i) {
      const vec3 o = 6.0 * random_dir(g);
      const ray r(o, 3.0 * random_dir(g) - o);  // roughly towards the objects
      double t_min_all = infinity<double>;
      for (const auto& s : sc.spheres) {
        hit h;
        if (intersect(s.shape, r, 0.0, infinity<double>, h)) t_min_all = std::min(t_min_all, h.t);
      }
      for (const auto& q : sc.quads) {
        hit h;
        if (intersect(q.shape, r, 0.0, infinity<double>, h)) t_min_all = std::min(t_min_all, h.t);
      }
      scene_hit a, b;
      const bool found = nearest_hit(sc, r, a);
      CHECK(found == (t_min_all < infinity<double>));
      CHECK(found == nearest_hit(reversed, r, b));
      if (found) {
        ++hits;
        CHECK(a.h.t == t_min_all);  // the same computation: bit-identical
        CHECK(b.h.t == t_min_all);
        hit again;
        CHECK(intersect_object(sc, a.object, r, 0.0, infinity<double>, again));
        CHECK(again.t == a.h.t);
      }
    }
  }
  CHECK(hits > 500);
}

TEST_CASE("scene: bad material indices are an error") {
  scene sc;
  sc.add_material(material::lambertian(rgb(0.5f)));
  CHECK_THROWS_AS(sc.add(sphere{{0, 0, 0}, 1}, 7), error);
  CHECK_THROWS_AS(sc.add(quad{}, -1), error);
}

TEST_CASE("scene: shadow segments stop before the light and are blocked by what is between") {
  scene sc;
  const int grey = sc.add_material(material::lambertian(rgb(0.5f)));
  const int lamp = sc.add_material(material::emitter(rgb(1)));
  sc.add(quad{{-5, 0, 5}, {10, 0, 0}, {0, 0, -10}}, grey);  // floor y = 0, normal +y
  sc.add(quad{{-1, 3, -1}, {2, 0, 0}, {0, 0, 2}}, lamp);    // light y = 3, normal -y
  scene_hit floor_hit;
  REQUIRE(nearest_hit(sc, ray({0.3, 1, 0.2}, {0, -1, 0}), floor_hit));
  REQUIRE(floor_hit.object.kind == shape_kind::quad);
  REQUIRE(floor_hit.object.index == 0);
  CHECK_FALSE(occluded(sc, spawn_segment(floor_hit.h, vec3(0.5, 3, 0.5))));  // the light is not its own blocker
  sc.add(sphere{{0.4, 1.5, 0.35}, 0.3}, grey);
  CHECK(occluded(sc, spawn_segment(floor_hit.h, vec3(0.5, 3, 0.5))));
}

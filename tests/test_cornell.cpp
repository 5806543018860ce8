#include <zraka/scene/cornell.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

using namespace zraka;

TEST_CASE_TEMPLATE("cornell: add_box makes six quads whose normals point out of the box", T, float, double) {
  for (T degrees : {T(0), T(17), T(-18), T(90), T(400)}) {
    scene_t<T> sc;
    sc.add_material(material::lambertian(rgb(0.5f)));
    const vec3_t<T> c(T(0.3), T(0.6), T(-0.2)), size(T(0.6), T(1.2), T(0.4));
    add_box(sc, c, size, degrees, 0);
    REQUIRE(sc.quads.size() == 6);
    T area = 0;
    for (const auto& q : sc.quads) {
      const vec3_t<T> face_centre = q.shape.point(T(0.5), T(0.5));
      CHECK(glm::dot(q.shape.normal(), face_centre - c) > T(0));  // outward
      area += q.shape.area();
    }
    // Surface area 2 (xy + yz + xz) = 2 (0.72 + 0.48 + 0.24) = 2.88; float keeps 6 digits.
    CHECK(area == doctest::Approx(2.88).epsilon(1e-5));
  }
}

TEST_CASE("cornell: walls face the room, the light faces down, every camera ray hits the room") {
  for (cornell_variant v : {cornell_variant::boxes, cornell_variant::glass, cornell_variant::spheres}) {
    const scene sc = cornell_box<double>(v);
    const light_set ls(sc);
    REQUIRE(ls.size() == 1);
    REQUIRE(ls.lights()[0].object.kind == shape_kind::quad);
    const auto& lamp = sc.quads[std::size_t(ls.lights()[0].object.index)].shape;
    CHECK(lamp.normal() == vec3(0, -1, 0));
    for (int i = 0; i < 5; ++i) {  // the five walls: normals towards the room's centre (0, 1, 0)
      const auto& q = sc.quads[std::size_t(i)].shape;
      CHECK(glm::dot(q.normal(), vec3(0, 1, 0) - q.point(0.5, 0.5)) > 0);
    }
    // The camera sees only the inside: each ray of a 40x40 grid hits the room (no sky).
    const auto cam = sc.prepared_camera();
    int misses = 0;
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x) {
        scene_hit sh;
        misses += nearest_hit(sc, cam.generate((x + 0.5) / 40, (y + 0.5) / 40), sh) ? 0 : 1;
      }
    CHECK(misses == 0);
  }
  CHECK(cornell_box<double>(cornell_variant::boxes).quads.size() == 6 + 12);
  CHECK(cornell_box<double>(cornell_variant::glass).spheres.size() == 1);
  CHECK(cornell_box<double>(cornell_variant::spheres).spheres.size() == 2);
  CHECK(parse_cornell_variant("glass") == cornell_variant::glass);
  CHECK_THROWS_AS(parse_cornell_variant("teapot"), error);
}

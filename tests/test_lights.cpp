#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <memory>

using namespace zraka;

namespace {

// A unit square at height y, as a mesh of two triangles facing down (-y).
mesh square_mesh(double y, double x0, double z0, double size) {
  mesh m;
  m.positions = {{x0, y, z0}, {x0 + size, y, z0}, {x0 + size, y, z0 + size}, {x0, y, z0 + size}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};  // (1,0,0) x (1,0,1) = (0,-1,0): faces down
  return m;
}

// A scene with one light of every kind above a floor, seen from points near the origin.
scene every_kind(bool two_sided) {
  scene sc;
  const int grey = sc.add_material(material::lambertian(rgb(0.5f)));
  const int lamp = sc.add_material(material::emitter(rgb(1, 2, 3), two_sided));
  sc.add(quad{{-5, 0, 5}, {10, 0, 0}, {0, 0, -10}}, grey);
  sc.add(quad{{-2.5, 2, -0.5}, {1, 0, 0}, {0, 0, 1}}, lamp);          // quad, faces down
  sc.add(sphere{{2, 1.5, 0}, 0.4}, lamp);                              // sphere
  sc.add(triangle{{0, 2.5, 1}, {0.5, 2.5, 1}, {0, 2.5, 1.5}}, lamp);    // faces down
  sc.add(square_mesh(3.0, -0.5, -2.0, 0.8), lamp);                     // mesh
  sc.add(point_light_t<double>{{0.5, 1.0, -1.0}, rgb(4)});
  return sc;
}

}  // namespace

TEST_CASE("lights: every emitting object is a light, planes are hit only, and it says so") {
  scene sc = every_kind(false);
  sc.add(plane::from_point_normal(vec3(0, 10, 0), vec3(0, -1, 0)), 1);  // a glowing ceiling plane
  const light_set ls(sc);
  CHECK(ls.size() == 5);
  CHECK(ls.index_of({shape_kind::quad, 0}) == -1);  // the floor does not glow
  CHECK(ls.index_of({shape_kind::quad, 1}) >= 0);
  CHECK(ls.index_of({shape_kind::sphere, 0}) >= 0);
  CHECK(ls.index_of({shape_kind::triangle, 0}) >= 0);
  CHECK(ls.index_of({shape_kind::mesh, 0}) >= 0);
  CHECK(ls.index_of({shape_kind::plane, 0}) == -1);
  REQUIRE(ls.hit_only().size() == 1);
  CHECK(ls.describe() == "lights: 5 (1 sphere, 1 quad, 1 triangle, 1 mesh, 1 point light), chosen by power; "
                         "hit only: plane 0 (infinite)");
}

TEST_CASE("lights: chosen in proportion to power, or uniformly") {
  scene sc;
  const int bright = sc.add_material(material::emitter(rgb(100)));
  const int dim = sc.add_material(material::emitter(rgb(1)));
  const int both = sc.add_material(material::emitter(rgb(1), true));
  sc.add(quad{{0, 2, 0}, {1, 0, 0}, {0, 0, 1}}, bright);  // area 1
  sc.add(quad{{2, 2, 0}, {2, 0, 0}, {0, 0, 1}}, dim);     // area 2
  sc.add(quad{{5, 2, 0}, {1, 0, 0}, {0, 0, 1}}, both);    // area 1, two-sided
  sc.add(point_light_t<double>{{0, 1, 0}, rgb(1)});
  const double p[] = {100 * pi<double>, 2 * pi<double>, 2 * pi<double>, 4 * pi<double>};
  const double total = p[0] + p[1] + p[2] + p[3];
  const light_set ls(sc);
  for (int i = 0; i < 4; ++i) CHECK(ls.selection_pdf(i) == doctest::Approx(p[i] / total).epsilon(1e-12));
  const light_set uni(sc, light_selection::uniform);
  for (int i = 0; i < 4; ++i) CHECK(uni.selection_pdf(i) == doctest::Approx(0.25));
  // sample() draws light i with that probability (u_select on a fine grid).
  int counts[4] = {};
  hit h;
  const int n = 100000;
  for (int k = 0; k < n; ++k)
    if (const auto s = ls.sample(h, (k + 0.5) / n, vec2(0.5))) ++counts[s->light];
  for (int i = 0; i < 4; ++i) CHECK(double(counts[i]) / n == doctest::Approx(p[i] / total).epsilon(1e-3));
}

TEST_CASE("lights: sample() and pdf() give one density for every light kind") {
  // From many points, a sample's direction is traced; where the first hit is the sampled point,
  // the density pdf() gives for that hit must equal the sampler's (quad, triangle and mesh in
  // area measure, the sphere in its cone; the big sphere is seen from inside).
  for (bool two_sided : {false, true}) {
    scene sc = every_kind(two_sided);
    sc.add(sphere{{0, 0, 0}, 20}, 1);  // a glowing room around everything: sampled from inside
    const light_set ls(sc, light_selection::uniform);  // by power, the room would take nearly all
    int checked[6] = {};
    for (int i = 0; i < 4000; ++i) {
      rng g(9, std::uint32_t(two_sided), std::uint32_t(i));
      hit h;
      h.p = vec3(0.3 * (i % 7) - 1, 0.5 + 0.1 * (i % 3), 0.2 * (i % 5) - 0.5);
      const auto e = ls.sample(h, g.uniform(), g.uniform2());
      if (!e || e->delta) continue;
      scene_hit sh;
      REQUIRE(nearest_hit(sc, spawn_ray(h, e->wi), sh));
      if (!(glm::length(sh.h.p - e->point) < 1e-5 * (1 + glm::length(e->point)))) continue;  // blocked
      CHECK(ls.index_of(sh.object) == e->light);
      CHECK(ls.pdf(sh.object, h.p, e->wi, sh.h) == doctest::Approx(e->pdf).epsilon(1e-4));
      CHECK(e->Le == emitted(sc.material_of(sh.object), sh.h));  // the face the ray meets
      ++checked[int(sh.object.kind)];
    }
    for (shape_kind k : {shape_kind::sphere, shape_kind::quad, shape_kind::triangle, shape_kind::mesh}) {
      INFO("kind " << int(k) << ": " << checked[int(k)] << " samples checked");
      CHECK(checked[int(k)] > 50);
    }
  }
}

TEST_CASE("lights: a quad light's samples integrate to its solid angle; its back is dark unless two-sided") {
  for (bool two_sided : {false, true}) {
    scene sc;
    const int lamp = sc.add_material(material::emitter(rgb(1), two_sided));
    // A 2 x 1 rectangle centred above the origin at height 1, facing down: u x v = -y.
    sc.add(quad{{-1, 1, -0.5}, {2, 0, 0}, {0, 0, 1}}, lamp);
    const light_set ls(sc);
    // Solid angle of an a x b rectangle seen on its axis from distance d:
    // 4 asin(a b / sqrt((a^2 + 4 d^2)(b^2 + 4 d^2))).
    const double omega = 4 * std::asin(2.0 / std::sqrt((4.0 + 4.0) * (1.0 + 4.0)));
    const int n = 40000;
    double sum = 0, sum2 = 0;
    for (int i = 0; i < n; ++i) {
      rng g(5, 0, std::uint32_t(i));
      hit h;  // the origin, below the light
      const auto s = ls.sample(h, g.uniform(), g.uniform2());
      REQUIRE(s);
      CHECK(s->Le == rgb(1));
      sum += 1 / s->pdf;
      sum2 += 1 / (s->pdf * s->pdf);
    }
    const double mean = sum / n, se = std::sqrt((sum2 / n - mean * mean) / n);
    INFO("estimate " << mean << " +- " << se << ", exact " << omega);
    CHECK(std::abs(mean - omega) < 5 * se);
    hit above;
    above.p = vec3(0, 2, 0);
    const auto back = ls.sample(above, 0.5, vec2(0.3, 0.6));
    REQUIRE(back);
    CHECK(back->Le == (two_sided ? rgb(1) : rgb(0)));
  }
}

TEST_CASE("lights: a sphere seen from outside is sampled in its cone, from inside in every direction") {
  scene sc;
  const int lamp = sc.add_material(material::emitter(rgb(2)));
  const int glow_in = sc.add_material(material::emitter(rgb(3), true));
  sc.add(sphere{{0, 4, 0}, 1}, lamp);
  sc.add(sphere{{0, -30, 0}, 10}, glow_in);
  const light_set ls(sc, light_selection::uniform);
  const double one_minus_cos = 1 - std::sqrt(1 - 1.0 / 16);
  for (int i = 0; i < 1000; ++i) {
    rng g(9, 0, std::uint32_t(i));
    hit h;
    const auto s = ls.sample_one(0, h, g.uniform2());
    REQUIRE(s);
    CHECK(glm::length(s->point - vec3(0, 4, 0)) == doctest::Approx(1).epsilon(1e-12));
    CHECK(s->pdf == doctest::Approx(1 / (2 * pi<double> * one_minus_cos)).epsilon(1e-9));
    CHECK(s->Le == rgb(2));
    hit inside;
    inside.p = vec3(1, -31, 2);
    const auto t = ls.sample_one(1, inside, g.uniform2());
    REQUIRE(t);
    CHECK(t->pdf == doctest::Approx(1 / (4 * pi<double>)).epsilon(1e-9));
    CHECK(t->Le == rgb(3));  // the inside of a two-sided glow
    CHECK(glm::length(t->point - vec3(0, -30, 0)) == doctest::Approx(10).epsilon(1e-12));
  }
}

TEST_CASE("lights: a point light gives I / d^2 as a delta") {
  scene sc;
  sc.add(point_light_t<double>{{0, 3, 0}, rgb(9)});
  const light_set ls(sc);
  hit h;
  const auto s = ls.sample(h, 0.7, vec2(0.1, 0.2));
  REQUIRE(s);
  CHECK(s->delta);
  CHECK(s->pdf == 1.0);
  CHECK(s->Le == rgb(1));
  CHECK(s->wi == vec3(0, 1, 0));
}

TEST_CASE_TEMPLATE("lights: shadow rays to points on a mesh light are not blocked by the light itself", T, float, double) {
  // The mesh is tested in float (triangle_bvh.hpp): the segment must stop short of the float
  // triangle too, at any scale and at grazing angles.
  for (double scale : {1e-3, 1.0, 1e3, 1e5}) {
    scene_t<T> sc;
    const int lamp = sc.add_material(material::emitter(rgb(1), true));
    mesh_t<T> m;
    const double x0 = 0.37 * scale, y = 2.11 * scale, z0 = -0.53 * scale, s = 0.9 * scale;
    // planar but tilted (y = y0 + 0.2 dx + 0.1 dz): no triangle can hide the other
    m.positions = {vec3_t<T>(x0, y, z0), vec3_t<T>(x0 + s, y + 0.2 * s, z0),
                   vec3_t<T>(x0 + s, y + 0.3 * s, z0 + s), vec3_t<T>(x0, y + 0.1 * s, z0 + s)};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    sc.add(m, lamp);
    const light_set_t<T> ls(sc);
    int blocked = 0;
    for (int i = 0; i < 2000; ++i) {
      rng g(3, 0, std::uint32_t(i));
      hit_t<T> h;
      // points on a line far below and beside the light, so that some rays graze it
      h.p = vec3_t<T>(T(scale * (-3 + 0.003 * i)), T(scale * 0.5 * (i % 5)), T(scale * 0.1));
      const auto e = ls.sample(h, T(g.uniform()), vec2_t<T>(g.uniform2()));
      if (!e) continue;
      blocked += occluded(sc, e->shadow);
    }
    INFO("scale " << scale << ": " << blocked << " of 2000 shadow rays blocked by the light itself");
    CHECK(blocked == 0);
  }
}

TEST_CASE("lights: a user shape with area sampling is a light; without it, hit only") {
  struct disk final : user_shape {
    bool can_sample;
    explicit disk(bool s) : can_sample(s) {}
    std::string name() const override { return "disk"; }
    bool intersect(const ray& r, double t_min, double t_max, hit& h) const override {
      if (r.direction.y == 0) return false;
      const double t = (2 - r.origin.y) / r.direction.y;
      const vec3 p = r.at(t);
      if (!(t > t_min && t < t_max) || p.x * p.x + p.z * p.z > 1) return false;
      h.t = t;
      h.p = vec3(p.x, 2, p.z);
      h.p_error = vec3(0, 1e-15, 0);
      h.normal = vec3(0, -1, 0);
      h.set_face(r.direction);
      return true;
    }
    aabb bounds() const override { return {vec3(-1, 2, -1), vec3(1, 2, 1)}; }
    double area() const override { return can_sample ? pi<double> : 0.0; }
    std::optional<surface_point_t<double>> sample_area(const vec2& u) const override {
      const vec2 d = sample_disk_concentric(u);
      return surface_point_t<double>{vec3(d.x, 2, d.y), vec3(0, -1, 0), vec3(0, 1e-15, 0)};
    }
  };
  for (bool can : {true, false}) {
    scene sc;
    const int lamp = sc.add_material(material::emitter(rgb(1)));
    sc.add(std::make_shared<disk>(can), lamp);
    const light_set ls(sc);
    CHECK(ls.size() == (can ? 1u : 0u));
    CHECK(ls.hit_only().size() == (can ? 0u : 1u));
    if (!can) continue;
    // The disk's solid angle from the origin below its centre: 2 pi (1 - d / sqrt(d^2 + 1)), d = 2.
    double sum = 0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      rng g(4, 0, std::uint32_t(i));
      hit h;
      const auto s = ls.sample(h, 0.5, g.uniform2());
      REQUIRE(s);
      scene_hit sh;
      REQUIRE(nearest_hit(sc, spawn_ray(h, s->wi), sh));
      CHECK(ls.pdf(sh.object, h.p, s->wi, sh.h) == doctest::Approx(s->pdf).epsilon(1e-9));
      sum += 1 / s->pdf;
    }
    CHECK(sum / n == doctest::Approx(2 * pi<double> * (1 - 2 / std::sqrt(5.0))).epsilon(0.01));
  }
}

TEST_CASE("lights: a NaN or infinite glow is an error, not a silent light") {
  scene sc;
  material m = material::lambertian(rgb(0.5f));
  m.radiance = rgb(1, std::numeric_limits<float>::quiet_NaN(), 1);
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(m));
  CHECK_THROWS_WITH_AS(light_set{sc}, doctest::Contains("non-finite"), error);
  scene pl;
  pl.add(point_light_t<double>{{0, 1, 0}, rgb(std::numeric_limits<float>::infinity())});
  CHECK_THROWS_WITH_AS(light_set{pl}, doctest::Contains("point light 0"), error);
}

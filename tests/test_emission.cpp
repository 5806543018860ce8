// Emission sampling (lights.hpp, book 6.2): the points light subpaths start from and the
// directions they leave in. Position densities against the area closed forms, the direction
// sampler by chi-square, and the emitted power the samples estimate against the power the light
// set chooses lights by.
#include <zraka/app/chi_square.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/scene/lights.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <memory>

using namespace zraka;

namespace {

// A disk of radius r at height y facing down: a user shape with area sampling.
struct disk final : user_shape {
  vec3 c;
  double r;
  disk(vec3 centre, double radius) : c(centre), r(radius) {}
  std::string name() const override { return "disk"; }
  bool intersect(const ray&, double, double, hit&) const override { return false; }
  aabb bounds() const override { return {c - vec3(r, 0, r), c + vec3(r, 0, r)}; }
  double area() const override { return pi<double> * r * r; }
  std::optional<surface_point_t<double>> sample_area(const vec2& u) const override {
    const vec2 d = r * sample_disk_concentric(u);
    return surface_point_t<double>{c + vec3(d.x, 0, d.y), vec3(0, -1, 0), vec3(0)};
  }
};

// Every light kind: a quad, a two-sided sphere, a triangle, a mesh, a disk and a point light.
scene every_light() {
  scene sc;
  const int q = sc.add_material(material::emitter(rgb(4, 3, 2)));
  material two = material::emitter(rgb(1.5f));
  two.two_sided = true;
  const int s = sc.add_material(two);
  const int t = sc.add_material(material::emitter(rgb(2)));
  const int m = sc.add_material(material::emitter(rgb(0.5f, 1, 1.5f)));
  const int d = sc.add_material(material::emitter(rgb(3)));
  sc.add(quad{{-1, 2, -1}, {2, 0, 0}, {0, 0, 0.5}}, q);
  sc.add(sphere{{0, 1, 0}, 0.3}, s);
  sc.add(triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, t);
  mesh me;
  me.positions = {{0, 0, 2}, {2, 0, 2}, {2, 1, 2}, {0, 1, 2}};
  me.triangles = {{0, 1, 2}, {0, 2, 3}};
  sc.add(me, m);
  sc.add(std::make_shared<disk>(vec3(3, 2, 0), 0.4), d);
  sc.add(point_light_t<double>{{0, 3, 0}, rgb(5)});
  return sc;
}

double mean3(const rgb& c) { return (double(c.x) + c.y + c.z) / 3; }

}  // namespace

TEST_CASE("sample_emission: the emitted power its samples estimate is the power lights are chosen by") {
  const scene sc = every_light();
  const light_set lights(sc);
  REQUIRE(lights.size() == 6);
  double total = 0;
  for (const auto& l : lights.lights()) total += l.power;
  rng g(3);
  estimator_t<double> phi;
  std::vector<estimator_t<double>> per(lights.size());
  const long n = 400000;
  for (long k = 0; k < n; ++k) {
    const auto e = lights.sample_emission(g.uniform(), g.uniform2(), g.uniform2());
    REQUIRE(e);
    const double c = e->delta_position ? 1.0 : std::abs(glm::dot(e->normal, e->direction));
    const double v = mean3(e->Le) * c / (e->pdf_position * e->pdf_direction);
    phi.add(v);
    for (std::size_t i = 0; i < lights.size(); ++i) per[i].add(int(i) == e->light ? v : 0.0);
    // the densities the sampler reports are the ones MIS asks for
    CHECK(e->pdf_position == doctest::Approx(lights.pdf_emission_position(e->light)).epsilon(1e-12));
    CHECK(e->pdf_direction == doctest::Approx(lights.pdf_emission_direction(e->light, e->normal, e->direction)).epsilon(1e-9));
  }
  CHECK(std::abs(phi.mean() - total) < 5 * phi.standard_error() + 1e-9 * total);
  for (std::size_t i = 0; i < lights.size(); ++i) {
    INFO("light " << i);
    // chosen by power, every light's share is exact up to the direction's cosine
    CHECK(std::abs(per[i].mean() - lights.lights()[i].power) < 5 * per[i].standard_error() + 1e-9 * total);
  }
}

TEST_CASE("sample_emission: positions are uniform in area (quad halves, sphere caps, mesh triangles)") {
  const scene sc = every_light();
  const light_set lights(sc);
  rng g(11);
  const long n = 200000;
  std::vector<long> count(lights.size(), 0);
  long quad_left = 0, sphere_cap = 0, mesh_right = 0;
  for (long k = 0; k < n; ++k) {
    const auto e = lights.sample_emission(g.uniform(), g.uniform2(), g.uniform2());
    REQUIRE(e);
    ++count[std::size_t(e->light)];
    const auto& l = lights.lights()[std::size_t(e->light)];
    if (l.point >= 0) {
      CHECK(e->delta_position);
      CHECK(e->point == vec3(0, 3, 0));
      continue;
    }
    if (l.object.kind == shape_kind::quad) {
      CHECK(e->point.y == doctest::Approx(2));
      quad_left += e->point.x < -0.5;  // a quarter of the quad's width
    }
    if (l.object.kind == shape_kind::sphere) {
      CHECK(glm::length(e->point - vec3(0, 1, 0)) == doctest::Approx(0.3));
      sphere_cap += e->point.y > 1.15;  // cap of height r/2: area fraction 1/4
    }
    if (l.object.kind == shape_kind::mesh) mesh_right += e->point.x > 1.0 && e->point.y < e->point.x - 1.0;
  }
  auto binomial_ok = [&](long k, long trials, double p) {
    const double sd = std::sqrt(trials * p * (1 - p));
    return std::abs(double(k) - trials * p) < 5 * sd;
  };
  for (std::size_t i = 0; i < lights.size(); ++i) CHECK(binomial_ok(count[i], n, lights.selection_pdf(int(i))));
  const long nq = count[std::size_t(lights.index_of({shape_kind::quad, 0}))];
  const long ns = count[std::size_t(lights.index_of({shape_kind::sphere, 0}))];
  const long nm = count[std::size_t(lights.index_of({shape_kind::mesh, 0}))];
  CHECK(binomial_ok(quad_left, nq, 0.25));
  CHECK(binomial_ok(sphere_cap, ns, 0.25));
  // the mesh is a 2 x 1 rectangle; {x > 1, y < x/2} is the triangle (1,0) (2,0) (2,1): area 1/2 of 2
  CHECK(binomial_ok(mesh_right, nm, 0.25));
  // closed forms of the position density
  CHECK(lights.pdf_emission_position(lights.index_of({shape_kind::quad, 0})) ==
        doctest::Approx(lights.selection_pdf(lights.index_of({shape_kind::quad, 0})) / 1.0));
  CHECK(lights.pdf_emission_position(lights.index_of({shape_kind::sphere, 0})) ==
        doctest::Approx(lights.selection_pdf(lights.index_of({shape_kind::sphere, 0})) / (4 * pi<double> * 0.09)));
}

TEST_CASE("sample_emission: directions follow their density (chi-square), one- and two-sided") {
  const scene sc = every_light();
  const light_set lights(sc);
  const int tests = 3;
  const double level = sidak_level(0.01, tests);
  // one light at a time: the selection number is fixed inside each light's share of the cdf
  auto u_select_of = [&](int i) {
    double lo = 0;
    for (int j = 0; j < i; ++j) lo += lights.selection_pdf(j);
    return lo + 0.5 * lights.selection_pdf(i);
  };
  for (const object_ref o : {object_ref{shape_kind::quad, 0}, object_ref{shape_kind::sphere, 0}, object_ref{shape_kind::user, 0}}) {
    const int i = lights.index_of(o);
    REQUIRE(i >= 0);
    rng g(100 + i);
    // Directions in the frame of the sampled point's normal: the density depends on them alone.
    const auto r = chi_square_directions(
        [&]() -> std::optional<vec3> {
          const auto e = lights.sample_emission(u_select_of(i), g.uniform2(), g.uniform2());
          if (!e || e->light != i) return std::nullopt;
          return onb(e->normal).to_local(e->direction);
        },
        [&](const vec3& w) { return lights.pdf_emission_direction(i, vec3(0, 0, 1), w); }, 200000,
        direction_grid(16, 16));
    INFO("light kind " << int(o.kind) << ": X^2 p = " << r.p_value);
    CHECK(r.p_value > level);
  }
  // A point light: uniform over the sphere.
  const int p = int(lights.size()) - 1;
  REQUIRE(lights.lights()[std::size_t(p)].point >= 0);
  CHECK(lights.pdf_emission_direction(p, vec3(0), vec3(0, 0, 1)) == doctest::Approx(1 / (4 * pi<double>)));
}

// Analytic probes of light transport, for every CPU renderer (issue "one light-transport core"):
// the radiance of a Lambertian floor point under each kind of emitter against its closed form,
// from both sides of one- and two-sided emitters, and the furnace seen from inside a glowing
// sphere. The renderers: the path tracer's naive, nee and mis (path.hpp, the loop pathtrace and
// the book show) and Whitted's direct light (whitted.hpp). Each estimate must lie within 5
// standard errors (and 1 %) of the closed form; an emitter seen from its back gives exactly 0.
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/whitted.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

using namespace zraka;

namespace {

// Irradiance at x (normal n) from a polygon of uniform radiance Le seen from its emitting side:
// Lambert's formula E = Le/2 sum_k theta_k n . unit(g_k x g_k+1), g_k the unit directions to the
// vertices, theta_k the angle between consecutive ones (Arvo 1995, "Applications of irradiance
// tensors"). The polygon must lie wholly above x's horizon.
double polygon_irradiance(const vec3& x, const vec3& n, const std::vector<vec3>& v, double Le) {
  double sum = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const vec3 a = glm::normalize(v[k] - x), b = glm::normalize(v[(k + 1) % v.size()] - x);
    sum += std::acos(std::clamp(glm::dot(a, b), -1.0, 1.0)) * glm::dot(n, glm::normalize(glm::cross(a, b)));
  }
  return Le / 2 * std::abs(sum);
}

struct estimate {
  double mean = 0, se = 0;
};

using radiance_fn = std::function<rgb(const ray&, rng&)>;

estimate measure(const radiance_fn& L, const ray& r, int n, std::uint64_t seed) {
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    rng g(seed, 7, std::uint32_t(i));
    const double v = L(r, g).x;
    REQUIRE(std::isfinite(v));
    sum += v, sum2 += v * v;
  }
  const double m = sum / n;
  return {m, std::sqrt(std::max(0.0, sum2 / n - m * m) / n)};
}

// Every renderer, as a function of the scene: name -> radiance along a ray.
struct renderer {
  std::string name;
  std::function<radiance_fn(const scene&)> make;
  bool finds_point_lights;
};

std::vector<renderer> renderers() {
  std::vector<renderer> out;
  for (integrator m : {integrator::naive, integrator::nee, integrator::mis})
    out.push_back({name(m),
                   [m](const scene& sc) -> radiance_fn {
                     path_options o;
                     o.method = m;
                     o.max_depth = 3;
                     auto t = std::make_shared<path_tracer>(sc, o);
                     return [t](const ray& r, rng& g) {
                       std::uint64_t rays = 0;
                       return (*t)(r, g, rays);
                     };
                   },
                   m != integrator::naive});
  out.push_back({"whitted",
                 [](const scene& sc) -> radiance_fn {
                   check_whitted_scene(sc);
                   auto ls = std::make_shared<light_set>(sc);
                   return [&sc, ls](const ray& r, rng& g) {
                     std::uint64_t rays = 0;
                     return whitted_radiance(sc, *ls, r, g, whitted_options{}, rays);
                   };
                 },
                 true});
  return out;
}

constexpr float rho = 0.5f;
const vec3 x0(0.1, 0, -0.05);             // the probed floor point
const ray eye(vec3(0.6, 1.5, 1.2), x0 - vec3(0.6, 1.5, 1.2));

scene floor_scene() {
  scene sc;
  sc.add(quad{{-50, 0, 50}, {100, 0, 0}, {0, 0, -100}}, sc.add_material(material::lambertian(rgb(rho))));
  return sc;
}

// Checks every renderer's estimate at x0 against rho/pi E.
void check_all(const scene& sc, double E, const std::string& what, bool has_point_light = false) {
  const double want = rho / pi<double> * E;
  for (const renderer& rd : renderers()) {
    if (has_point_light && !rd.finds_point_lights) {
      CHECK_THROWS_WITH_AS(rd.make(sc), doctest::Contains("point light"), error);
      continue;
    }
    const estimate e = measure(rd.make(sc), eye, rd.name == "naive" ? 200000 : 20000, 3);
    INFO(what << ", " << rd.name << ": " << e.mean << " +- " << e.se << ", closed form " << want);
    if (want == 0) {
      CHECK(e.mean == 0.0);
    } else {
      CHECK(std::abs(e.mean - want) < 5 * e.se + 1e-6 * want);  // + float colours' rounding
      CHECK(std::abs(e.mean - want) < 0.01 * want);
    }
  }
}

}  // namespace

TEST_CASE("probes: a floor under a quad light, one- and two-sided, from both sides") {
  // The quad at height 1.3, 0.8 x 0.5, above and beside x0.
  const vec3 c(0.3, 1.3, 0.2), u(0.8, 0, 0), v(0, 0, 0.5);
  const std::vector<vec3> poly = {c, c + u, c + u + v, c + v};
  const double E = polygon_irradiance(x0, vec3(0, 1, 0), poly, 3.0);
  for (bool two_sided : {false, true})
    for (bool faces_down : {true, false}) {
      scene sc = floor_scene();
      const int lamp = sc.add_material(material::emitter(rgb(3), two_sided));
      // u x v = (0, -0.4, 0): down; swapped, up (the floor then sees its back).
      if (faces_down) sc.add(quad{c, u, v}, lamp);
      else sc.add(quad{c, v, u}, lamp);
      const std::string what = std::string(two_sided ? "two-sided" : "one-sided") + " quad facing " +
                               (faces_down ? "the floor" : "away");
      check_all(sc, faces_down || two_sided ? E : 0.0, what);
    }
}

TEST_CASE("probes: a floor under an emissive triangle and an emissive mesh") {
  const vec3 a(-0.4, 1.1, -0.3), b(0.5, 1.4, -0.2), c(0.0, 1.2, 0.6);
  const double E_tri = polygon_irradiance(x0, vec3(0, 1, 0), {a, b, c}, 2.0);
  for (bool two_sided : {false, true})
    for (bool faces_down : {true, false}) {
      scene sc = floor_scene();
      const int lamp = sc.add_material(material::emitter(rgb(2), two_sided));
      const bool down = glm::cross(b - a, c - a).y < 0;
      if (down == faces_down) sc.add(triangle{a, b, c}, lamp);
      else sc.add(triangle{a, c, b}, lamp);
      const std::string what = std::string(two_sided ? "two-sided" : "one-sided") + " triangle facing " +
                               (faces_down ? "the floor" : "away");
      check_all(sc, faces_down || two_sided ? E_tri : 0.0, what);
    }
  // A mesh of two triangles making a quad (tested in float by its BVH): the quad's irradiance.
  const vec3 q(-0.2, 1.0, -0.4), u(0.7, 0.1, 0), v(0, 0.05, 0.6);
  scene sc = floor_scene();
  mesh m;
  m.positions = {q, q + u, q + u + v, q + v};  // counter-clockwise seen from below: faces down
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  REQUIRE(glm::cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]).y < 0);
  sc.add(m, sc.add_material(material::emitter(rgb(1.5f))));
  check_all(sc, polygon_irradiance(x0, vec3(0, 1, 0), m.positions, 1.5), "mesh light");
}

TEST_CASE("probes: a point light at distance d gives I cos / d^2") {
  for (double d : {0.01, 1.0, 100.0}) {
    scene sc = floor_scene();
    const vec3 p = x0 + d * glm::normalize(vec3(0.3, 1, -0.2));
    sc.add(point_light_t<double>{p, rgb(2)});
    const double cos_theta = glm::normalize(p - x0).y;
    check_all(sc, 2.0 * cos_theta / (d * d), "point light at d = " + std::to_string(d), true);
  }
}

TEST_CASE("probes: inside a glowing sphere (the furnace)") {
  // Path tracers: L = Le / (1 - a) for albedo a (depth large enough that the tail is below 1e-6).
  // Whitted, with no indirect light: L = Le + a Le (the sphere's own light, once reflected).
  scene sc;
  material glow = material::lambertian(rgb(0.5f));
  glow.radiance = rgb(1);
  glow.two_sided = true;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(glow));
  const ray inside(vec3(0.2, -0.1, 0.3), vec3(0.3, 0.5, -0.8));
  for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
    path_options o;
    o.method = m;
    o.max_depth = 24;
    const path_tracer t(sc, o);
    const estimate e = measure([&](const ray& r, rng& g) { std::uint64_t n = 0; return t(r, g, n); }, inside, 20000, 5);
    INFO(name(m) << ": " << e.mean << " +- " << e.se);
    CHECK(std::abs(e.mean - 2.0) < 5 * e.se + 1e-6);
    CHECK(std::abs(e.mean - 2.0) < 0.02);
  }
  const light_set ls(sc);
  const estimate w = measure([&](const ray& r, rng& g) {
    std::uint64_t n = 0;
    return whitted_radiance(sc, ls, r, g, whitted_options{}, n);
  }, inside, 20000, 6);
  INFO("whitted: " << w.mean << " +- " << w.se);
  CHECK(std::abs(w.mean - 1.5) < 5 * w.se + 1e-6);
  CHECK(std::abs(w.mean - 1.5) < 0.01);
}

TEST_CASE("probes: Whitted refuses a custom BSDF by name") {
  struct grey final : custom_bsdf {
    std::string name() const override { return "grey"; }
    vec3 eval(const bsdf_frame&, const vec3&, const vec3&) const override { return vec3(0.1); }
    std::optional<custom_sample> sample(const bsdf_frame&, const vec3&, const vec3&) const override { return std::nullopt; }
    double pdf(const bsdf_frame&, const vec3&, const vec3&) const override { return 0; }
  };
  scene sc;
  sc.add(sphere{{0, 0, 0}, 1}, sc.add_material(material::custom(std::make_shared<grey>())));
  image img(sc.settings.width, sc.settings.height);
  CHECK_THROWS_WITH_AS(render_whitted(sc, img, whitted_options{}), doctest::Contains("custom BSDF ('grey')"), error);
}

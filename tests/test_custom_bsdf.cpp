#include <zraka/integrators/path.hpp>
#include <zraka/materials/custom_bsdf.hpp>
#include <zraka/materials/material.hpp>

#include <doctest/doctest.h>

#include <cstring>
#include <string>
#include <memory>

using namespace zraka;

namespace {

// Lambert written as a user would write it, on top of bxdf.hpp's own lambert_brdf.
struct my_lambert final : custom_bsdf {
  lambert_brdf f;
  explicit my_lambert(vec3 rho) : f{rho} {}
  std::string name() const override { return "my_lambert"; }
  vec3 eval(const bsdf_frame& fr, const vec3& wo, const vec3& wi) const override { return f.eval(wi, wo, fr.n); }
  std::optional<custom_sample> sample(const bsdf_frame& fr, const vec3& wo, const vec3& u) const override {
    const auto s = f.sample(wo, fr.n, vec2(u));
    if (!s) return std::nullopt;
    return custom_sample{s->wi, s->weight, s->pdf};
  }
  double pdf(const bsdf_frame& fr, const vec3& wo, const vec3& wi) const override { return f.pdf(wi, wo, fr.n); }
};

// A small closed scene: a Lambertian floor, a sphere of the tested material, a quad light and a
// glowing ceiling (light that only the BSDF sampling or MIS finds).
scene cornerstone(const material& tested) {
  scene sc;
  const int floor = sc.add_material(material::lambertian(rgb(0.7f, 0.6f, 0.5f)));
  const int ball = sc.add_material(tested);
  const int light = sc.add_material(material::emitter(rgb(8), true));
  sc.add(quad{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, floor);
  sc.add(sphere{{0, 0.6, 0}, 0.6}, ball);
  sc.add(quad{{-0.5, 2.5, -0.5}, {1, 0, 0}, {0, 0, 1}}, light);
  sc.background = rgb(0.2f, 0.3f, 0.4f);
  sc.camera.position = vec3(0, 1, 4);
  sc.camera.look_at = vec3(0, 0.5, 0);
  return sc;
}

std::vector<rgb> trace(const scene& sc, integrator method, int n) {
  path_options o;
  o.method = method;
  const path_tracer tracer(sc, o);
  const auto cam = sc.prepared_camera();
  std::vector<rgb> out;
  std::uint64_t rays = 0;
  for (int i = 0; i < n; ++i) {
    rng g(5, 0, std::uint32_t(i));
    out.push_back(tracer(cam.generate(g.uniform(), g.uniform()), g, rays));
  }
  return out;
}

}  // namespace

TEST_CASE("custom_bsdf: a custom Lambert gives the built-in Lambert's paths bit for bit") {
  // Same seeds, same uniform numbers, same double arithmetic: naive and nee must agree in every
  // bit. mis also weighs by scatter_pdf, which for the built-in material is the Lambert+Phong
  // mixture's density (glossy weight 0): equal up to rounding, so 1e-5 relative there.
  const rgb rho(0.8f, 0.5f, 0.3f);
  const scene a = cornerstone(material::lambertian(rho));
  const scene b = cornerstone(material::custom(std::make_shared<my_lambert>(vec3(rho))));
  for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
    const auto la = trace(a, m, 3000), lb = trace(b, m, 3000);
    int differ = 0;
    double worst = 0;
    for (std::size_t i = 0; i < la.size(); ++i) {
      differ += std::memcmp(&la[i], &lb[i], sizeof(rgb)) != 0;
      for (int c = 0; c < 3; ++c)
        worst = std::max(worst, double(std::abs(la[i][c] - lb[i][c])) / (1e-3 + std::abs(la[i][c])));
    }
    INFO(std::string(name(m)) << ": " << differ << " of " << la.size() << " samples differ, worst relative " << worst);
    if (m == integrator::mis) CHECK(worst < 1e-5);
    else CHECK(differ == 0);
  }
}

TEST_CASE("custom_bsdf: the material functions call the BSDF, of the kind custom") {
  const material m = material::custom(std::make_shared<my_lambert>(vec3(0.5)));
  CHECK(m.is<material_kinds::custom>());
  CHECK_FALSE(is_specular(m));
  hit h;
  h.p = vec3(0);
  h.normal = vec3(0, 0, 1);
  h.set_face(vec3(0, 0, -1));
  const vec3 wo(0, 0, 1), wi = glm::normalize(vec3(1, 0, 1));
  // f cos = 0.5/pi cos 45 deg; pdf = cos 45 deg / pi (float rgb: 1e-6 relative).
  CHECK(brdf_cos(m, h, wo, wi).x == doctest::Approx(0.5 / pi<double> * std::sqrt(0.5)).epsilon(1e-6));
  CHECK(scatter_pdf(m, h, wo, wi) == doctest::Approx(std::sqrt(0.5) / pi<double>));
  CHECK(brdf_cos(m, h, wo, vec3(0, 0, -1)) == rgb(0));  // below the surface: no reflection
  rng g(3);
  const auto s = scatter(m, vec3(0, 0, -1), h, g);
  REQUIRE(s);
  CHECK(s->weight == rgb(0.5f));
  CHECK(s->pdf > 0);
  CHECK_FALSE(s->specular);
  CHECK_THROWS_AS(material::custom(nullptr), error);
}

namespace {
// Records what the renderer hands it, and reflects like a two-lobe mixture chosen by u.z.
struct recorder final : custom_bsdf {
  mutable bsdf_frame last;
  mutable vec3 last_u{-1};
  vec3 eval(const bsdf_frame& fr, const vec3&, const vec3& wi) const override {
    last = fr;
    return glm::dot(wi, fr.n) > 0 ? vec3(0.5 / pi<double>) : vec3(0);
  }
  std::optional<custom_sample> sample(const bsdf_frame& fr, const vec3&, const vec3& u) const override {
    last = fr;
    last_u = u;
    // lobe 0 (u.z < 0.5): straight up; lobe 1: cosine-weighted. Either way a valid density.
    const vec3 local = sample_cosine_hemisphere(vec2(u));
    const vec3 wi = fr.to_world(local);
    return custom_sample{wi, vec3(0.5), local.z / pi<double>};
  }
  double pdf(const bsdf_frame& fr, const vec3&, const vec3& wi) const override {
    return std::max(0.0, glm::dot(wi, fr.n)) / pi<double>;
  }
};
}  // namespace

TEST_CASE("custom_bsdf: the BSDF sees the hit point, uv, an orthonormal frame and three numbers") {
  const auto rec = std::make_shared<recorder>();
  const material m = material::custom(rec);
  hit h;
  h.p = vec3(1, 2, 3);
  h.uv = vec2(0.25, 0.75);
  h.normal = normalize_or_zero(vec3(0.3, 1, -0.2));
  h.set_face(vec3(0, 1, 0));  // from below: the frame's n must face the ray
  rng g(7), copy(7);
  REQUIRE(scatter(m, vec3(0, 1, 0), h, g));
  const vec2 u01 = copy.uniform2();
  const double u2 = copy.uniform();
  CHECK(rec->last_u == vec3(u01, u2));  // the two direction numbers, then the lobe number
  const bsdf_frame& f = rec->last;
  CHECK(f.p == h.p);
  CHECK(f.uv == h.uv);
  CHECK_FALSE(f.front_face);
  CHECK(glm::length(f.n - (-h.normal)) < 1e-12);
  CHECK(std::abs(glm::dot(f.s, f.t)) < 1e-12);
  CHECK(std::abs(glm::dot(f.s, f.n)) < 1e-12);
  CHECK(glm::length(glm::cross(f.s, f.t) - f.n) < 1e-12);  // right-handed
  const vec3 w = normalize_or_zero(vec3(0.2, -0.5, 0.7));
  CHECK(glm::length(f.to_world(f.to_local(w)) - w) < 1e-12);
}

// Every way zraka's path tracer finds light agrees with the reference, on scenes that hold every
// emitter kind, every material and every shape the scene format can express: naive and nee
// against a long mis render (the reference), per channel mean within 5 standard errors and per
// pixel within 5 of its own standard errors (allowing 0.5 % of the pixel channels outside, for
// the heavy tails of a few-sample estimate). The kernel's side of the same promise is in
// tests/test_realtime.cpp.
#include <zraka/geometry/tessellate.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

using namespace zraka;

namespace {

// A disk of radius r at height y facing down: a user shape with area sampling.
struct disk final : user_shape {
  vec3 c;
  double r;
  disk(vec3 centre, double radius) : c(centre), r(radius) {}
  std::string name() const override { return "disk"; }
  bool intersect(const ray& ray_, double t_min, double t_max, hit& h) const override {
    const double dy = ray_.direction.y;
    if (!(std::abs(dy) > 0)) return false;
    const double s = c.y - ray_.origin.y;
    if (!(std::abs(s) > 1e-12 * (std::abs(c.y) + std::abs(ray_.origin.y)))) return false;  // on its plane
    const double t = s / dy;
    if (!(t > t_min && t < t_max)) return false;
    const vec3 p = ray_.at(t);
    const double dx = p.x - c.x, dz = p.z - c.z;
    if (dx * dx + dz * dz > r * r) return false;
    h.t = t;
    h.p = vec3(p.x, c.y, p.z);
    h.p_error = vec3(0, 1e-12 * (1 + std::abs(c.y)), 0);
    h.normal = vec3(0, -1, 0);
    h.uv = vec2(dx / r, dz / r);
    h.set_face(ray_.direction);
    return true;
  }
  aabb bounds() const override { return {c - vec3(r, 0, r), c + vec3(r, 0, r)}; }
  double area() const override { return pi<double> * r * r; }
  std::optional<surface_point_t<double>> sample_area(const vec2& u) const override {
    const vec2 d = r * sample_disk_concentric(u);
    return surface_point_t<double>{c + vec3(d.x, 0, d.y), vec3(0, -1, 0), vec3(0, 1e-12 * (1 + std::abs(c.y)), 0)};
  }
};

// A glossy custom BSDF: Lambert plus a normalised Phong lobe, the lobe chosen by u.z.
struct glossy final : custom_bsdf {
  vec3 kd{0.3, 0.4, 0.5};
  double ks = 0.4, s = 20;
  std::string name() const override { return "glossy"; }
  vec3 eval(const bsdf_frame& f, const vec3& wo, const vec3& wi) const override {
    if (!(glm::dot(wi, f.n) > 0) || !(glm::dot(wo, f.n) > 0)) return vec3(0);
    const vec3 r = 2 * glm::dot(wo, f.n) * f.n - wo;
    return kd / pi<double> + vec3(ks * (s + 2) / (2 * pi<double>) * std::pow(std::max(0.0, glm::dot(r, wi)), s));
  }
  double pdf(const bsdf_frame& f, const vec3& wo, const vec3& wi) const override {
    if (!(glm::dot(wi, f.n) > 0) || !(glm::dot(wo, f.n) > 0)) return 0;
    const vec3 r = 2 * glm::dot(wo, f.n) * f.n - wo;
    const double lobe = (s + 1) / (2 * pi<double>) * std::pow(std::max(0.0, glm::dot(r, wi)), s);
    return 0.5 * glm::dot(wi, f.n) / pi<double> + 0.5 * lobe;
  }
  std::optional<custom_sample> sample(const bsdf_frame& f, const vec3& wo, const vec3& u) const override {
    if (!(glm::dot(wo, f.n) > 0)) return std::nullopt;
    vec3 wi;
    if (u.z < 0.5) {
      wi = f.to_world(sample_cosine_hemisphere(vec2(u)));
    } else {
      const vec3 r = 2 * glm::dot(wo, f.n) * f.n - wo;
      wi = onb(r).to_world(sample_phong_lobe(vec2(u), s));
    }
    const double p = pdf(f, wo, wi);
    if (!(p > 0)) return std::nullopt;
    return custom_sample{wi, eval(f, wo, wi) * glm::dot(wi, f.n) / p, p};
  }
};

scene base(bool point_light) {
  scene sc;
  const int floor = sc.add_material(material::lambertian(texture::checker(rgb(0.7f), rgb(0.3f), 0.5)));
  const int wall = sc.add_material(material::lambertian(rgb(0.6f, 0.5f, 0.4f)));
  sc.add(quad{{-3, 0, 3}, {6, 0, 0}, {0, 0, -6}}, floor);
  sc.add(plane::from_point_normal(vec3(0, 0, -2.5), vec3(0, 0, 1)), wall);
  if (point_light) sc.add(point_light_t<double>{{1.2, 2.2, 0.5}, rgb(3, 2.5, 2)});
  sc.background = rgb(0.05f, 0.07f, 0.1f);
  sc.camera.position = {0, 1.4, 4};
  sc.camera.look_at = {0, 0.8, 0};
  sc.camera.vfov_degrees = 50;
  return sc;
}

// Every emitter kind: sphere, one- and two-sided quads, triangle, mesh, a glowing plane (hit
// only), the background, and (in the second variant) a point light.
scene emitters(bool point_light) {
  scene sc = base(point_light);
  const int grey = sc.add_material(material::lambertian(rgb(0.6f)));
  const int warm = sc.add_material(material::emitter(rgb(6, 4, 2)));
  const int both = sc.add_material(material::emitter(rgb(2, 3, 4), true));
  material faint = material::lambertian(rgb(0.2f));
  faint.radiance = rgb(0.05f);
  const int glow = sc.add_material(faint);
  sc.add(sphere{{0, 0.5, 0}, 0.5}, grey);
  sc.add(sphere{{-1.4, 1.8, -0.6}, 0.2}, warm);
  sc.add(quad{{1.2, 0.2, -1}, {0, 0, 0.6}, {0, 0.7, 0}}, both);  // upright, seen from both sides
  sc.add(triangle{{-0.6, 2.2, 0.4}, {0.2, 2.2, 0.4}, {-0.2, 2.2, -0.3}}, warm);  // faces down
  mesh m;
  m.positions = {{0.4, 2.0, -1.2}, {1.0, 2.0, -1.2}, {1.0, 2.1, -0.6}, {0.4, 2.1, -0.6}};
  m.triangles = {{0, 1, 2}, {0, 2, 3}};
  if (glm::cross(m.positions[1] - m.positions[0], m.positions[2] - m.positions[0]).y > 0)
    m.triangles = {{0, 2, 1}, {0, 3, 2}};
  sc.add(m, both);
  sc.add(plane::from_point_normal(vec3(0, 4, 0), vec3(0, -1, 0)), glow);  // a faint ceiling
  sc.build_acceleration();
  return sc;
}

// Every material: checker Lambert, mirror, fuzzy metal, glass, a hollow in glass, Phong, custom.
scene materials(bool point_light) {
  scene sc = base(point_light);
  const int lamp = sc.add_material(material::emitter(rgb(8)));
  sc.add(quad{{-0.6, 2.6, -0.6}, {1.2, 0, 0}, {0, 0, 1.2}}, lamp);
  const material ms[] = {material::mirror(rgb(0.9f)), material::fuzzy_metal(rgb(0.8f, 0.6f, 0.3f), 0.3),
                         material::dielectric(1.5), material::phong(rgb(0.2f, 0.3f, 0.5f), rgb(0.3f), 30),
                         material::custom(std::make_shared<glossy>()), material::lambertian(rgb(0.8f, 0.2f, 0.2f))};
  for (int i = 0; i < 6; ++i) sc.add(sphere{{-1.5 + 0.6 * i, 0.28, 0.3 * (i % 2)}, 0.28}, sc.add_material(ms[i]));
  sc.add(sphere{{-0.3, 0.28, 0}, 0.12}, sc.add_material(material::dielectric(1 / 1.5)));  // a bubble in the glass
  sc.build_acceleration();
  return sc;
}

// Every shape: sphere, quad, plane (in base), lone triangle, a mesh with vertex normals (a
// tessellated sphere), and user shapes (a glowing disk, sampled by area, and a plain one).
scene shapes(bool point_light) {
  scene sc = base(point_light);
  const int grey = sc.add_material(material::lambertian(rgb(0.7f)));
  const int lamp = sc.add_material(material::emitter(rgb(5, 5, 4)));
  sc.add(std::make_shared<disk>(vec3(0, 2.4, 0), 0.5), lamp);
  sc.add(std::make_shared<disk>(vec3(-1, 0.9, 0.6), 0.3), grey);
  sc.add(triangle{{0.6, 0, -0.5}, {1.4, 0, -0.5}, {1.0, 1.0, -0.8}}, grey);
  mesh ball;  // a coarse sphere from a lat-long grid, with vertex normals
  const int nu = 12, nv = 8;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double th = pi<double> * j / nv, ph = 2 * pi<double> * i / nu;
      const vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      ball.positions.push_back(vec3(-0.8, 0.45, -0.4) + 0.45 * n);
      ball.normals.push_back(n);
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const std::uint32_t a = std::uint32_t(j * (nu + 1) + i), b = a + 1, c = a + std::uint32_t(nu + 1), d = c + 1;
      ball.triangles.push_back({a, b, d});
      ball.triangles.push_back({a, d, c});
    }
  sc.add(ball, grey);
  sc.add(sphere{{0.3, 0.3, 0.6}, 0.3}, grey);
  sc.add(quad{{1.3, 0, 0.8}, {0.5, 0, 0}, {0, 0.8, 0}}, grey);
  sc.build_acceleration();
  return sc;
}

struct stats_image {
  std::vector<vec3> mean, var;  // per pixel: the sample mean and its variance (of the mean)
};

stats_image render_stats_image(const scene& sc, integrator m, int W, int H, int spp, std::uint64_t seed) {
  path_options o;
  o.method = m;
  o.max_depth = 6;
  const path_tracer t(sc, o);
  camera c = sc.camera;
  c.aspect = double(W) / H;
  const auto cam = c.prepare();
  std::vector<vec3> sum2(std::size_t(W * H), vec3(0));  // each pixel is one thread's alone
  image img(W, H);
  render_options ro;
  ro.progress = false;
  const render_stats st = render(img, spp, seed, [&](sample_context& s) {
    // Pixel centres: the error is the light transport's alone (a jittered pixel on a light's edge is a
    // two-valued sample whose variance 256 samples estimate poorly).
    const rgb v = t(cam.generate((s.x + 0.5) / W, (s.y + 0.5) / H), s.random, s.rays);
    if (is_finite(v)) sum2[std::size_t(s.y * W + s.x)] += vec3(v) * vec3(v);
    return v;
  }, ro);
  REQUIRE(st.nonfinite == 0);
  stats_image out;
  for (int i = 0; i < W * H; ++i) {
    const vec3 mu(img.pixels[std::size_t(i)]);
    out.mean.push_back(mu);
    out.var.push_back(glm::max(vec3(0), sum2[std::size_t(i)] / double(spp) - mu * mu) / double(spp - 1));
  }
  return out;
}

// Per channel mean within 5 standard errors; per pixel, the mean squared difference over the
// image at most twice what the pixels' variances predict (the sample variance is unbiased, so
// its sum over the image is accurate even where one pixel's few samples missed a rare light);
// and, where the estimator has no heavy tails to hide (per_pixel), each pixel channel within 5
// of its standard errors, 0.5 % allowed outside.
void compare(const std::string& what, const stats_image& a, const stats_image& ref, bool per_pixel) {
  const double P = double(a.mean.size());
  vec3 diff(0), var(0);
  double d2 = 0, v2 = 0;
  int outside = 0;
  for (std::size_t i = 0; i < a.mean.size(); ++i) {
    const vec3 d = a.mean[i] - ref.mean[i], v = a.var[i] + ref.var[i];
    diff += d / P;
    var += v / (P * P);
    d2 += glm::dot(d, d);
    v2 += v.x + v.y + v.z;
    for (int k = 0; k < 3; ++k)
      if (std::abs(d[k]) > 5 * std::sqrt(v[k]) + 1e-6) ++outside;
  }
  for (int k = 0; k < 3; ++k) {
    INFO(what << ": channel " << k << " mean difference " << diff[k] << ", 5 sigma = " << 5 * std::sqrt(var[k]));
    CHECK(std::abs(diff[k]) < 5 * std::sqrt(var[k]));
  }
  INFO(what << ": mean squared difference " << d2 / (3 * P) << ", predicted " << v2 / (3 * P) << "; " << outside
            << " of " << 3 * a.mean.size() << " pixel channels beyond 5 of their sigmas");
  CHECK(d2 < 2 * v2);
  if (per_pixel) CHECK(outside <= int(0.005 * 3 * P) + 1);
}

}  // namespace

TEST_CASE("agreement: naive and nee match a long mis render on every emitter, material and shape") {
  const int W = 24, H = 18;
  struct named {
    const char* name;
    scene (*make)(bool);
  };
  for (const named& s : {named{"emitters", emitters}, named{"materials", materials}, named{"shapes", shapes}})
    for (bool point_light : {false, true}) {
      const scene sc = s.make(point_light);
      const std::string tag = std::string(s.name) + (point_light ? " + point light" : "");
      const stats_image ref = render_stats_image(sc, integrator::mis, W, H, 2048, 1000);
      const stats_image nee = render_stats_image(sc, integrator::nee, W, H, 256, 1);
      compare(tag + ", nee", nee, ref, true);
      if (point_light) {  // naive cannot see a point light: it says so instead of rendering dark
        path_options o;
        o.method = integrator::naive;
        CHECK_THROWS_WITH_AS(path_tracer(sc, o), doctest::Contains("point light"), error);
      } else {
        compare(tag + ", naive", render_stats_image(sc, integrator::naive, W, H, 1024, 2), ref, false);
      }
      compare(tag + ", mis (another seed)", render_stats_image(sc, integrator::mis, W, H, 256, 3), ref, true);
    }
}

// Chapter 1.8 — refraction. First the numbers: for glass (n = 1.5) in air, a sweep of incidence
// angles with the refracted angle from refract() (Snell's law checked on each), the exact
// Fresnel reflectance and Schlick's approximation, both ways: air into glass and glass into
// air, where beyond the critical angle asin(1/1.5) = 41.8 degrees there is no refracted ray
// (total internal reflection) and R = 1. Then a path-traced glass ball on a checkered floor,
// where each hit on the glass reflects with probability R and refracts otherwise.
#include <zraka/core/error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/sampling/pixel_sampling.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>

using namespace zraka;

namespace {

constexpr double deg = pi<double> / 180;

// One line of the table for incidence angle theta_i (degrees), eta = n_i / n_t. Returns the
// Snell residual |n_i sin(theta_i) - n_t sin(theta_t)| (relative to n_t), or 0 under TIR.
double table_row(double theta_i, double n_i, double n_t) {
  const double eta = n_i / n_t;
  const vec3 n(0, 0, 1);
  const vec3 d(std::sin(theta_i * deg), 0, -std::cos(theta_i * deg));  // travelling down onto +z
  const double cos_i = -glm::dot(d, n);
  const auto t = refract(d, n, eta);
  const double R = fresnel_dielectric(cos_i, eta), S = fresnel_schlick(cos_i, eta);
  if (!t) {
    std::printf("%8.1f %14s %12.6f %12.6f   total internal reflection\n", theta_i, "none", R, S);
    return 0;
  }
  const double sin_t = std::sqrt(t->x * t->x + t->y * t->y);
  const double theta_t = std::atan2(sin_t, -t->z) / deg;
  std::printf("%8.1f %14.4f %12.6f %12.6f\n", theta_i, theta_t, R, S);
  return std::abs(n_i * std::sin(theta_i * deg) - n_t * sin_t) / n_t;
}

scene glass_scene(int width, int height, double ior) {
  scene sc;
  const int checks = sc.add_material(material::lambertian(texture::checker(rgb(0.85f), rgb(0.08f), 0.5)));
  const int glass = sc.add_material(material::dielectric(ior));
  const int red = sc.add_material(material::lambertian(rgb(0.7f, 0.15f, 0.1f)));
  const int lamp = sc.add_material(material::emitter(rgb(4.0f)));
  sc.add(quad{{-8, 0, 8}, {16, 0, 0}, {0, 0, -16}}, checks);       // y = 0, up
  sc.add(sphere{{0, 0.8, 0}, 0.8}, glass);
  sc.add(sphere{{1.4, 0.4, -1.6}, 0.4}, red);
  sc.add(quad{{-2, 4, -2}, {4, 0, 0}, {0, 0, 2}}, lamp);            // above, facing down
  sc.background = rgb(0.45f, 0.55f, 0.75f);
  sc.camera.position = {0, 1.5, 5};
  sc.camera.look_at = {0, 0.6, 0};
  sc.camera.vfov_degrees = 32;
  sc.settings.width = width;
  sc.settings.height = height;
  return sc;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.8: refraction - Snell, Fresnel, Schlick and total internal reflection; a glass ball", take::image | take::depth};
  cli.width = 240, cli.height = 150, cli.spp = 32, cli.depth = 10, cli.out = "refraction.png";
  double ior = 1.5;
  cli.app.add_option("--ior", ior, "refractive index of the glass (air is 1)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height, spp = cli.spp, depth = cli.depth;
  const std::uint64_t seed = cli.seed;
  const render_options opt = cli.render();
  const std::string& out = cli.out;

  return guarded([&] {
    if (!(ior >= 1 && ior <= 4)) throw error("--ior must be between 1 and 4, got " + std::to_string(ior));
    stopwatch total;

    const double angles[] = {0, 10, 20, 30, 40, 41, 41.5, 42, 45, 50, 60, 70, 80, 85, 89, 90};
    double worst = 0;
    std::printf("air -> glass (eta = 1/%.2f): incidence, refracted angle (degrees), Fresnel R exact, Schlick\n", ior);
    std::printf("%8s %14s %12s %12s\n", "theta_i", "theta_t", "R exact", "R Schlick");
    for (double a : angles) worst = std::max(worst, table_row(a, 1.0, ior));
    std::printf("\nglass -> air (eta = %.2f)\n%8s %14s %12s %12s\n", ior, "theta_i", "theta_t", "R exact", "R Schlick");
    for (double a : angles) worst = std::max(worst, table_row(a, ior, 1.0));
    const auto crit = critical_angle(ior);
    std::printf("critical angle asin(1/%.2f) = %.2f degrees: beyond it, no refracted ray\n", ior,
                crit ? *crit / deg : 90.0);
    std::printf("Snell's law n_i sin(theta_i) = n_t sin(theta_t): worst relative residual %.2e\n\n", worst);

    const scene sc = glass_scene(width, height, ior);
    const auto cam = sc.prepared_camera();
    path_options po;
    po.max_depth = depth;
    const path_tracer tracer(sc, po);
    image img(width, height);
    const render_stats st = render(img, spp, seed, [&](sample_context& c) {
      const vec2 o = pixel_sample(pixel_pattern::stratified, c.sample, c.spp, c.random);
      return tracer(cam.generate((c.x + o.x) / width, (c.y + o.y) / height), c.random, c.rays);
    }, opt);
    write_image(img, out);
    std::printf("%s\nwrote %s\n", summary(img, spp, st).c_str(), out.c_str());
    std::printf("summary: %.2f s; critical angle %.2f degrees; Snell residual %.1e; %llu NaN/inf samples\n",
                total.seconds(), crit ? *crit / deg : 90.0, worst, static_cast<unsigned long long>(st.nonfinite));
    return 0;
  });
}

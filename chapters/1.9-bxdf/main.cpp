// Chapter 1.9 — BxDFs. Two parts.
// 1. The Phong and Blinn-Phong local models: a grid of balls under one point light, Phong in the
//    top row and Blinn-Phong below, shininess 1, 8, 32, 128, 512 from left to right. Local
//    shading only (no shadows, no reflections): I = I_a rho_a + I (rho_d max(0, N.L) + rho_s s),
//    with s = max(0, V.R)^p or max(0, N.H)^p (bxdf.hpp).
// 2. The white furnace: the albedo a(wo) = integral of f(wi, wo) cos(theta_i) dwi of each BRDF
//    with reflectance 1, estimated by Monte Carlo with its standard error, over shininess and
//    view angle. A BRDF with albedo above 1 reflects more light than it receives. Lambert (1/pi)
//    is exactly 1; the normalised Phong lobe ((p+2)/(2 pi) cos^p) is 1 at normal incidence and
//    less at grazing angles; the unnormalised lobe cos^p, which is what the local model's
//    (V.R)^p amounts to, is 2 pi/(p+2) at normal incidence: above 1 for p < 4.3, far below for
//    shiny surfaces.
#include <zraka/core/error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/materials/bxdf.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>

using namespace zraka;

namespace {

constexpr double shininess[] = {1, 8, 32, 128, 512};
constexpr double deg = pi<double> / 180;

// [listing local-shading]
// Local model at a hit: ambient plus one point light, no shadow ray (book 1.9).
rgb local_shade(const material_kinds::phong& m, const hit& h, const vec3& view_dir, const vec3& light_pos, bool blinn) {
  const vec3 n = h.facing_normal(), v = -view_dir, l = glm::normalize(light_pos - h.p);
  const auto k = blinn ? blinn_phong_terms(n, l, v, m.shininess) : phong_terms(n, l, v, m.shininess);
  const phong_material_t<double, vec3> coeffs{vec3(0.1) * vec3(m.kd), vec3(m.kd), vec3(m.ks), m.shininess};
  return rgb(phong_shade(coeffs, k, vec3(1.0), vec3(1.0)));  // white light, white ambient
}
// [end]

// [listing furnace]
// Albedo of f for a view direction at theta_o from the normal: the mean of f cos / p over
// directions sampled with density p.
template <class Sampler> estimator albedo(int n, std::uint64_t seed, std::uint32_t stream, double theta_o, Sampler&& draw) {
  const vec3 normal(0, 0, 1), wo(std::sin(theta_o * deg), 0, std::cos(theta_o * deg));
  estimator e;
  for (int i = 0; i < n; ++i) {
    rng g(seed, stream, std::uint32_t(i));
    e.add(draw(wo, normal, g));  // f cos / p of one sample, 0 if it fell below the surface
  }
  return e;
}
// [end]

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.9: Phong and Blinn-Phong local shading; white-furnace albedo of BRDFs", take::image};
  cli.width = 360, cli.height = 150, cli.spp = 4, cli.out = "bxdf.png";
  int furnace_samples = 20000;
  cli.app.add_option("--furnace-samples", furnace_samples, "Monte Carlo samples per albedo estimate");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height, spp = cli.spp;
  const std::uint64_t seed = cli.seed;
  const render_options opt = cli.render();
  const std::string& out = cli.out;

  return guarded([&] {
    if (furnace_samples < 2) throw error("--furnace-samples must be at least 2");
    stopwatch total;

    // Part 1: a 5 x 2 grid of balls, Phong (top) and Blinn-Phong (bottom).
    scene sc;
    for (int row = 0; row < 2; ++row)
      for (int col = 0; col < 5; ++col)
        sc.add(sphere{{-2.2 + 1.1 * col, 0.55 - 1.1 * row, 0}, 0.45},
               sc.add_material(material::phong(rgb(0.55f, 0.12f, 0.08f), rgb(0.45f), shininess[col])));
    sc.camera.position = {0, 0, 30};
    sc.camera.look_at = {0, 0, 0};
    sc.camera.vfov_degrees = 4.6;  // far and narrow: nearly orthographic, every ball seen alike
    sc.settings.width = width;
    sc.settings.height = height;
    sc.background = rgb(0.02f);
    const vec3 light_pos(-20, 20, 30);
    const auto cam = sc.prepared_camera();
    image img(width, height);
    const render_stats st = render(img, spp, seed, [&](sample_context& c) {
      const vec2 o = pixel_sample(pixel_pattern::stratified, c.sample, c.spp, c.random);
      const ray r = cam.generate((c.x + o.x) / width, (c.y + o.y) / height);
      scene_hit sh;
      ++c.rays;
      if (!nearest_hit(sc, r, sh)) return sc.background;
      const bool blinn = sh.object.index >= 5;  // the second row
      return local_shade(*sc.materials[sh.material].get<material_kinds::phong>(), sh.h, r.direction, light_pos, blinn);
    }, opt);
    write_image(img, out);
    std::printf("%s\nwrote %s: top row Phong, bottom row Blinn-Phong, shininess 1 8 32 128 512\n\n",
                summary(img, spp, st).c_str(), out.c_str());

    // Part 2: the white furnace.
    const double views[] = {0, 30, 60, 85};
    std::printf("white furnace: albedo of each BRDF with reflectance 1 (mean +- standard error, %d samples)\n",
                furnace_samples);
    std::printf("%-22s %6s", "BRDF", "p");
    for (double v : views) std::printf("   theta_o=%2.0f deg    ", v);
    std::printf("\n");
    int above_one = 0, normalised_above = 0;
    auto print_row = [&](const char* label, double p, auto&& draw, bool normalised) {
      std::printf("%-22s %6.0f", label, p);
      for (std::size_t k = 0; k < 4; ++k) {
        const estimator e = albedo(furnace_samples, seed, std::uint32_t(k), views[k], draw);
        const bool over = e.mean() - 4 * e.standard_error() > 1.0;  // above 1 beyond doubt
        above_one += over ? 1 : 0;
        normalised_above += over && normalised ? 1 : 0;
        std::printf("  %7.4f +- %6.4f%s", e.mean(), e.standard_error(), over ? " >1" : "   ");
      }
      std::printf("\n");
    };
    print_row("Lambert 1/pi", 0, [](const vec3& wo, const vec3& n, rng& g) {
      const auto s = lambert_brdf{vec3(1)}.sample(wo, n, g.uniform2());
      return s ? s->weight.x : 0.0;
    }, true);
    for (double p : shininess)
      print_row("normalised Phong", p, [p](const vec3& wo, const vec3& n, rng& g) {
        const auto s = phong_brdf{vec3(1), p}.sample(wo, n, g.uniform2());
        return s ? s->weight.x : 0.0;
      }, true);
    for (double p : shininess)
      print_row("unnormalised cos^p", p, [p](const vec3& wo, const vec3& n, rng& g) {
        // f = cos^p(alpha): the normalised lobe without its (p+2)/(2 pi); same sampler.
        const phong_brdf f{vec3(1), p};
        const auto s = f.sample(wo, n, g.uniform2());
        return s ? s->f.x * (2 * pi<double> / (p + 2)) * glm::dot(s->wi, n) / s->pdf : 0.0;
      }, false);
    std::printf("estimates above 1 (by more than 4 standard errors): %d, of them normalised BRDFs: %d\n", above_one,
                normalised_above);
    std::printf("summary: %.2f s; image %dx%d; albedo above 1: %d estimates, %d of them normalised BRDFs; "
                "%llu NaN/inf samples\n",
                total.seconds(), width, height, above_one, normalised_above,
                static_cast<unsigned long long>(st.nonfinite));
    return 0;
  });
}

// Chapter 5.4 — microfacets. Rough metal and rough glass as a carpet of tiny mirrors with GGX
// normals (microfacet.hpp): the material balls of the page (rough gold at four roughnesses,
// rough glass) path traced with naive, nee and mis, each against a reference rendered in the
// same run with another seed (error against run time), and a table of directional albedos: how
// much light one bounce off each surface keeps, by Monte Carlo over the material's own sampler.
// A GGX mirror (F = 1) keeps less than all of it: light that the facets send into other facets
// is lost, as the single-scattering model counts only one bounce among them.
//
// Scenes (--scene): scenes/material-balls.yaml by default, or any scene (a name or a file).
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/materials/microfacet.hpp>
#include <zraka/sampling/convergence.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace zraka;

namespace {

// [listing albedo]
// The directional albedo a(wo) = integral f(wo, wi) |cos theta_i| dwi: the mean of the sampled
// weight f |cos| / pdf (a lost sample counts 0). sample(u, u_lobe) is a BSDF's sampler.
template <class Sampler> vec3 albedo(Sampler&& sample, int n, rng& g) {
  vec3 sum(0);
  for (int i = 0; i < n; ++i) {
    const vec2 u = g.uniform2();
    if (const auto s = sample(u, g.uniform())) sum += vec3(s->weight);
  }
  return sum / double(n);
}
// [end]

vec3 incident(double degrees) {
  const double t = degrees * pi<double> / 180;
  return {std::sin(t), 0, std::cos(t)};
}

void albedo_table(int n, std::uint64_t seed) {
  const double alphas[] = {0.05, 0.15, 0.3, 0.6, 1.0};
  const double angles[] = {0, 60, 85};
  std::printf("directional albedo, %d samples each (GGX, height-correlated Smith G2, visible normals)\n", n);
  std::printf("%6s | %-26s | %-26s | %s\n", "alpha", "   mirror F = 1, theta_o", "  gold (mean RGB), theta_o",
              "glass 1.5 (R + T), theta_o");
  std::printf("%6s |", "");
  for (int k = 0; k < 3; ++k) {
    for (double a : angles) std::printf(" %6.0f  ", a);
    std::printf(k < 2 ? "|" : "\n");
  }
  rng g(seed);
  for (const double a : alphas) {
    std::printf("%6.2f |", a);
    const ggx_t<double> d(a);
    const rough_conductor_t<double> mirror{d, conductor_fresnel::from_f0(rgb(1))};
    const rough_conductor_t<double> gold{d, *find_metal("gold")};
    const rough_dielectric_t<double> glass{d, 1.5};
    for (double t : angles)
      std::printf(" %7.4f ", albedo([&](vec2 u, double) { return mirror.sample(incident(t), u); }, n, g).x);
    std::printf("|");
    for (double t : angles) {
      const vec3 c = albedo([&](vec2 u, double) { return gold.sample(incident(t), u); }, n, g);
      std::printf(" %7.4f ", (c.x + c.y + c.z) / 3);
    }
    std::printf("|");
    for (double t : angles)
      std::printf(" %7.4f ", albedo([&](vec2 u, double ul) { return glass.sample(incident(t), u, ul); }, n, g).x);
    std::printf("\n");
  }
  std::printf("(1 - ln 2 = %.4f is the mirror's exact albedo at alpha = 1, theta_o = 0)\n", 1 - std::log(2.0));
}

}  // namespace

int main(int argc, char** argv) {
  program_options opt{"Chapter 5.4: rough metals and glass (GGX microfacets), error against run time",
                      take::scene | take::image | take::depth};
  opt.scene = "scenes/material-balls.yaml", opt.out = "microfacets.png", opt.scene_settings = true;
  opt.min_depth = 0, opt.max_depth = 1000;
  int ref_spp = 256, albedo_samples = 100000;
  opt.app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference (mis, its own seed)");
  opt.app.add_option("--albedo-samples", albedo_samples, "samples per entry of the albedo table (0: no table)");
  if (const auto done = opt.parse(argc, argv)) return *done;

  return guarded([&] {
    const stopwatch clock;
    if (ref_spp < 1 || ref_spp > 65536) throw error("--ref-spp must be in 1..65536, got " + std::to_string(ref_spp));
    if (albedo_samples < 0 || albedo_samples > 100000000)
      throw error("--albedo-samples must be in 0..100000000, got " + std::to_string(albedo_samples));
    scene sc = load_scene_argument(opt.scene).sc;
    opt.apply_to(sc.settings);
    const int W = opt.width, H = opt.height;
    if (albedo_samples > 0) albedo_table(albedo_samples, opt.seed);

    // Every pixel at its centre, as in 4.2: the error against the reference is then the light
    // transport's alone, not the anti-aliasing's.
    const auto cam = sc.prepared_camera();
    auto draw_with = [&](integrator m) {
      path_options o;
      o.method = m;
      o.max_depth = opt.depth;
      return path_tracer(sc, o);
    };
    const path_tracer reference_tracer = draw_with(integrator::mis);
    render_options ro;
    ro.threads = opt.threads;
    ro.progress = false;
    image ref(W, H);
    const render_stats rs = render(ref, ref_spp, opt.seed + 1000, [&](sample_context& c) {
      return reference_tracer(cam.generate((c.x + 0.5) / W, (c.y + 0.5) / H), c.random, c.rays);
    }, ro);
    std::printf("\nscene %s, %dx%d, at most %d bounces; %s\n", opt.scene.c_str(), W, H, opt.depth,
                reference_tracer.lights.describe().c_str());
    std::printf("reference: mis, %d spp, seed %llu, %.2f s\n", ref_spp,
                static_cast<unsigned long long>(opt.seed + 1000), rs.seconds);

    // [listing error-time]
    std::printf("\nerror against run time, up to %d spp\n", opt.spp);
    double target = 0, naive_seconds = 0;
    std::uint64_t bad = rs.nonfinite;
    image last;
    for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
      const path_tracer t = draw_with(m);
      progressive_options po;
      po.max_spp = opt.spp;
      po.seed = opt.seed;
      po.render = ro;
      convergence_log log(std::string(name(m)), {"rmse", "relmse"}, "rmse", "spp");
      progressive_totals tot;
      last = render_progressive(W, H, po, [&](sample_context& c) {
        return t(cam.generate((c.x + 0.5) / W, (c.y + 0.5) / H), c.random, c.rays);
      }, [&](const image& mean, const progressive_totals& tt) {
        log.add(std::uint64_t(tt.spp), tt.seconds, {rmse(mean, ref), relmse(mean, ref)});
      }, &tot);
      bad += tot.stats.nonfinite;
      std::printf("%s%s\n", log.table().c_str(), log.slope_line().c_str());
      log.write_csv(opt.sibling("-" + std::string(name(m)), ".csv"));
      if (m == integrator::naive) target = log.rows().back().values[0], naive_seconds = log.rows().back().seconds;
      const double secs = m == integrator::naive ? naive_seconds : seconds_to_reach(log, target);
      std::printf("%s reaches naive's final RMSE %.5f in %.3f s (%.2fx naive's time)\n\n", name(m), target, secs,
                  secs / std::max(naive_seconds, 1e-9));
    }
    // [end]
    write_image(last, opt.out);
    write_image(ref, opt.sibling("-reference"));
    const vec3 mean = channel_mean(ref);
    std::printf("wrote %s (mis, %d spp), %s, %s\n", opt.out.c_str(), opt.spp, opt.sibling("-reference").c_str(),
                opt.sibling("-mis", ".csv").c_str());
    std::printf("summary: %dx%d, reference mean %.5f %.5f %.5f; %llu NaN/inf samples; total %.2f s\n", W, H,
                mean.x, mean.y, mean.z, static_cast<unsigned long long>(bad), clock.seconds());
    return 0;
  });
}

// Chapter 6.3 — photon mapping. Light is traced from the lights as photons (photons.hpp),
// stored in a hash grid (photon_map.hpp), and the radiance a camera sees at a diffuse point is
// estimated from the photons around it: a density estimate. The program shows
//   1. error against run time of stochastic progressive photon mapping (sppm.hpp) on --scene
//      against a long mis reference rendered in the same run: passes, photons, mean radius,
//      RMSE, seconds; and mis path tracing given the same time;
//   2. the same at equal time on the Cornell box with a glass sphere (--caustic-scene), where
//      the caustic under the sphere is light mis finds only by chance: RMSE over the image and
//      over a window on the caustic;
//   3. two-pass photon mapping (photon_mapping.hpp: global and caustic maps, final gathering)
//      with a fixed radius: its error stops falling when its bias is reached.
// --window shows the SPPM estimate of part 1 after every doubling of its passes (preview_window.hpp).
#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/app/reference.hpp>  // render_mis: the path tracer of 2.3, as the part-6 references
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/photon_mapping.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/integrators/sppm.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/scene/cornell.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace zraka;

namespace {

struct window {
  int x0, y0, x1, y1;
};

double window_mean(const image& img, const window& w) {
  double s = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x) s += (double(img.at(x, y).x) + img.at(x, y).y + img.at(x, y).z) / 3;
  return s / double((w.x1 - w.x0) * (w.y1 - w.y0));
}
double window_rmse(const image& a, const image& ref, const window& w) {
  double s = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x) {
      const vec3 d = vec3(a.at(x, y)) - vec3(ref.at(x, y));
      s += glm::dot(d, d) / 3;
    }
  return std::sqrt(s / double((w.x1 - w.x0) * (w.y1 - w.y0)));
}

// The reference as the mean of two halves with seeds of their own; their difference tells its
// own noise (RMSE of the mean = RMSE(half a - half b) / 2), the floor under every error below.
image reference_of(const scene& sc, int spp, std::uint64_t seed, const render_options& ro, double& noise,
                   double& seconds);

// mis, doubling its samples until `seconds` would be overrun: the equal-time competitor.
image mis_for(const scene& sc, double seconds, std::uint64_t seed, const render_options& ro, int& spp_out) {
  const path_tracer tracer(sc, path_options{});
  const auto cam = sc.prepared_camera();
  const int W = sc.settings.width, H = sc.settings.height;
  progressive_options po;
  po.max_spp = 65536;
  po.time_budget = seconds;
  po.seed = seed;
  po.render = ro;
  progressive_totals tot;
  image img = render_progressive(W, H, po, [&](sample_context& c) {
    const vec2 u = c.random.uniform2();
    return tracer(cam.generate((c.x + u.x) / W, (c.y + u.y) / H), c.random, c.rays);
  }, [](const image&, const progressive_totals&) {}, &tot);
  spp_out = tot.spp;
  return img;
}

image reference_of(const scene& sc, int spp, std::uint64_t seed, const render_options& ro, double& noise,
                   double& seconds) {
  render_stats a, b;
  const image ha = render_mis(sc, std::max(1, spp / 2), seed ^ 0x5eed5eed5eedull, path_options{}, ro, a);
  const image hb = render_mis(sc, std::max(1, spp / 2), seed ^ 0xfeedfeedfeedull, path_options{}, ro, b);
  image ref(ha.width, ha.height);
  for (std::size_t i = 0; i < ref.pixels.size(); ++i) ref.pixels[i] = (ha.pixels[i] + hb.pixels[i]) * 0.5f;
  noise = rmse(ha, hb) / 2;
  seconds = a.seconds + b.seconds;
  return ref;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 6.3: photon mapping - SPPM error against time vs mis, caustics, global + caustic maps (--spp: SPPM passes)",
                      take::image | take::scene | take::window};
  cli.width = 32, cli.height = 32, cli.spp = 64, cli.out = "photons.png";
  std::uint64_t photons = 5000;
  double radius = 0.08, alpha = 2.0 / 3.0;
  int ref_spp = 256, caustic_ref_spp = 512;
  std::string caustic_scene = "cornell-glass";
  cli.app.add_option("--photons", photons, "photons per SPPM pass (and 16x that for the two-pass photon map)");
  cli.app.add_option("--radius", radius, "initial SPPM radius r_0 and the photon map's radius (scene units)");
  cli.app.add_option("--alpha", alpha, "SPPM: fraction of new photons kept, in (0, 1)");
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the mis reference for --scene");
  cli.app.add_option("--caustic-ref-spp", caustic_ref_spp, "samples per pixel of the mis reference for the caustic scene");
  cli.app.add_option("--caustic-scene", caustic_scene, "the equal-time comparison's scene (a glass sphere's caustic)");
  cli.scene_names = named_scene_list();
  if (const auto done = cli.parse(argc, argv)) return *done;

  return guarded([&] {
    if (!(radius > 0) || !std::isfinite(radius)) throw error("--radius must be positive, got " + std::to_string(radius));
    if (photons == 0) throw error("--photons must be positive, got 0");
    if (ref_spp < 1 || caustic_ref_spp < 1) throw error("--ref-spp and --caustic-ref-spp must be at least 1");
    const render_options ro = cli.render();
    stopwatch total;
    scene sc = load_scene_argument(cli.scene).sc;
    sc.settings.width = cli.width, sc.settings.height = cli.height;
    check_photon_scene(sc, light_set(sc));  // before the reference is rendered

    // [listing sppm-options]
    sppm_options so;
    so.photons_per_pass = photons;
    so.radius = radius;
    so.alpha = alpha;
    so.seed = cli.seed;
    so.threads = cli.threads;
    // [end]

    // 1. SPPM against time on --scene.
    double ref_noise = 0, ref_seconds = 0;
    const image reference = reference_of(sc, ref_spp, cli.seed, ro, ref_noise, ref_seconds);
    std::printf("reference: %s, %dx%d, mis, %d spp, %.2f s, its own noise (RMSE) %.5f\n", cli.scene.c_str(),
                cli.width, cli.height, ref_spp, ref_seconds, ref_noise);
    convergence_log log("sppm on " + cli.scene, {"rmse", "radius"}, "rmse", "passes");
    sppm s(sc, so);
    std::printf("%s\n%8s %10s %8s %9s %8s\n", s.lights().describe().c_str(), "passes", "photons", "radius", "rmse",
                "seconds");
    const stopwatch clock;
    preview_window preview(cli, cli.width, cli.height, &reference, "passes");  // --window: each estimate
    for (int next = 1; s.passes() < cli.spp;) {
      while (s.passes() < next) s.run_pass();
      const image est = s.estimate();
      log.add(std::uint64_t(s.passes()), clock.seconds(), {rmse(est, reference), s.mean_radius()});
      const auto& r = log.rows().back();
      std::printf("%8d %10llu %8.4f %9.5f %8.3f\n", s.passes(), static_cast<unsigned long long>(s.photons_emitted()),
                  r.values[1], r.values[0], r.seconds);
      next = std::min(cli.spp, next * 2);
      if (!preview.show(est, s.passes(), r.seconds)) break;  // stopped in the window
    }
    const double sppm_seconds = log.rows().back().seconds;
    const image sppm_image = s.estimate();
    int mis_spp = 0;
    const image mis_image = mis_for(sc, sppm_seconds, cli.seed, ro, mis_spp);
    std::printf("%s\nequal time (%.2f s): sppm RMSE %.5f, mis (%d spp) RMSE %.5f\n", log.slope_line().c_str(),
                sppm_seconds, log.rows().back().values[0], mis_spp, rmse(mis_image, reference));

    // 2. The caustic: SPPM and mis at equal time on the glass sphere's Cornell box.
    scene glass = load_scene_argument(caustic_scene).sc;
    glass.settings.width = cli.width, glass.settings.height = cli.height;
    double g_noise = 0, g_ref_seconds = 0;
    const image glass_ref = reference_of(glass, caustic_ref_spp, cli.seed, ro, g_noise, g_ref_seconds);
    sppm g(glass, so);
    const stopwatch gclock;
    while (g.passes() < cli.spp) g.run_pass();
    const double g_seconds = gclock.seconds();
    const image g_sppm = g.estimate();
    int g_mis_spp = 0;
    const image g_mis = mis_for(glass, g_seconds, cli.seed, ro, g_mis_spp);
    // The caustic of cornell-glass: on the floor in front of the sphere (x 0.38, z 0.35),
    // the window in image fractions (found in the reference: its brightest floor patch).
    const window cw{int(0.62 * cli.width), int(0.86 * cli.height), int(0.78 * cli.width), int(0.94 * cli.height)};
    std::printf("caustic scene %s: reference mis %d spp (%.2f s, its own noise %.5f); caustic window mean: "
                "reference %.4f\n", caustic_scene.c_str(), caustic_ref_spp, g_ref_seconds, g_noise,
                window_mean(glass_ref, cw));
    std::printf("  equal time %.2f s: sppm %d passes RMSE %.5f, window mean %.4f, window RMSE %.5f\n", g_seconds,
                g.passes(), rmse(g_sppm, glass_ref), window_mean(g_sppm, cw), window_rmse(g_sppm, glass_ref, cw));
    std::printf("  equal time %.2f s: mis %d spp   RMSE %.5f, window mean %.4f, window RMSE %.5f\n", g_seconds,
                g_mis_spp, rmse(g_mis, glass_ref), window_mean(g_mis, cw), window_rmse(g_mis, glass_ref, cw));

    // 3. Two-pass photon mapping with a fixed radius: global + caustic maps, final gathering.
    // [listing two-pass]
    photon_map_options pm;
    pm.photons = 16 * photons;
    pm.radius = radius;
    pm.seed = cli.seed;
    pm.threads = cli.threads;
    const stopwatch pclock;
    const photon_mapper_t<double> mapper(glass, pm);
    const auto cam = glass.prepared_camera();
    const int W = cli.width, H = cli.height;
    image g_pm(W, H);
    render(g_pm, 4, cli.seed, [&](sample_context& c) {
      const vec2 u = c.random.uniform2();
      return mapper(cam.generate((c.x + u.x) / W, (c.y + u.y) / H), c.random, c.rays);
    }, ro);
    // [end]
    std::printf("photon map: %llu photons, %zu in the global map, %zu in the caustic map, radius %.3f, "
                "final gathering at 4 spp: %.2f s, RMSE %.5f, window mean %.4f\n",
                static_cast<unsigned long long>(pm.photons), mapper.global_size(), mapper.caustic_size(), radius,
                pclock.seconds(), rmse(g_pm, glass_ref), window_mean(g_pm, cw));

    write_image(side_by_side({glass_ref, g_sppm, g_mis, g_pm}), cli.out);
    write_image(side_by_side({reference, sppm_image, mis_image}), cli.sibling("-diffuse"));
    log.write_csv(cli.sibling("-sppm", ".csv"));
    std::printf("wrote %s (caustic scene: reference, sppm, mis at equal time, photon map), %s, %s\n", cli.out.c_str(),
                cli.sibling("-diffuse").c_str(), cli.sibling("-sppm", ".csv").c_str());
    std::printf("summary: %.2f s; sppm RMSE %.5f after %d passes vs mis %.5f at equal time on %s\n", total.seconds(),
                log.rows().back().values[0], s.passes(), rmse(mis_image, reference), cli.scene.c_str());
    return 0;
  });
}

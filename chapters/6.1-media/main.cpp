// Chapter 6.1 — participating media. Fog, smoke and milk do not stop light at a surface: along a
// ray through them light is absorbed and scattered out (Beer-Lambert: T_r = exp(-tau)) and
// scattered in from every other direction (the phase function). The path tracer of 2.3 handles
// this in its one loop (path.hpp): inside a medium each segment first samples where the light
// next interacts; a medium event is a vertex with the phase function as its BSDF, lit by
// next-event estimation through the medium and by phase sampling, weighted by MIS.
//
// This program compares the two ways a course meets to follow a heterogeneous medium (a smoke
// cloud on a density grid, medium.hpp):
//   march  ray marching with a fixed step (the thesis's word): the density sampled at the middle
//          of each step. Cheap per step, but biased where the density changes within a step;
//   delta  delta tracking for distances and ratio tracking for shadow rays: unbiased.
// Two measurements, each with error against run time:
//  1. transmittance: what the camera sees of a white backdrop through the smoke, T_r along each
//     camera ray (through the pixel centre) to the first surface. March is deterministic, so its
//     RMSE is its bias alone; ratio tracking's is noise, falling as 1/sqrt(spp). The reference
//     is the march at a step of 1e-3 (the midpoint rule converged: its error is below 1e-5),
//     computed in this run.
//  2. the rendered image (path.hpp with media), at 1, 4, 16, ... spp up to --spp, against a
//     reference rendered in the same run by delta tracking with --ref-spp samples and another
//     seed (so its noise is independent). Here the noise of the light transport hides the bias
//     at every step in these sample counts: the page says what that means.
// --window shows each image of table 2 as it is rendered (preview_window.hpp).
#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/samplers.hpp>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

using namespace zraka;

namespace {

struct run_result {
  image img;
  render_stats stats;
};

// [listing media-render]
run_result draw(const scene& sc, media_estimator est, double step, int spp, std::uint64_t seed, int width,
                int height, const render_options& ro, sampler_kind sampler) {
  path_options o;
  o.max_depth = sc.settings.max_depth;
  o.media.estimator = est;
  o.media.step = step;
  const path_tracer tracer(sc, o);
  scene s = sc;
  s.settings.width = width, s.settings.height = height;
  const auto cam = s.prepared_camera();
  run_result r{image(width, height), {}};
  r.stats = render(r.img, spp, seed, [&](sample_context& c) {
    sample_point point(sampler, seed, std::uint32_t(c.y * width + c.x), std::uint32_t(c.sample), std::uint32_t(spp));
    point.drive(c.random);  // --sampler (book 5.1); independent leaves the stream alone
    const double u = (c.x + c.random.uniform()) / width, v = (c.y + c.random.uniform()) / height;
    return tracer(cam.generate(u, v), c.random, c.rays);
  }, ro);
  return r;
}
// [end]

// [listing transmittance-view]
// T_r from the camera to the first surface through pixel (x, y)'s centre, in the global medium.
image transmittance_view(const scene& sc, const medium_options& o, int spp, std::uint64_t seed, int width,
                         int height, const render_options& ro, render_stats& stats) {
  scene s = sc;
  s.settings.width = width, s.settings.height = height;
  const auto cam = s.prepared_camera();
  const medium& m = sc.media[std::size_t(sc.global_medium)];
  image img(width, height);
  stats = render(img, spp, seed, [&](sample_context& c) {
    const ray r = cam.generate((c.x + 0.5) / width, (c.y + 0.5) / height);
    scene_hit sh;
    const double t = nearest_hit(sc, r, sh) ? sh.h.t : infinity<double>;
    ++c.rays;
    return segment_transmittance(m, r, t, c.random, o);
  }, ro);
  return img;
}
// [end]

double image_mean(const image& a) {
  const vec3 m = channel_mean(a);
  return (m.x + m.y + m.z) / 3;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 6.1: participating media - ray marching at several steps against delta tracking",
                      take::image | take::scene | take::sampler | take::window};
  cli.width = 32, cli.height = 32, cli.spp = 16, cli.out = "media.png", cli.scene = "fog-cornell";
  int ref_spp = 192;
  std::vector<double> steps{0.5, 0.2, 0.05};
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference (delta tracking, seed + 1000)");
  cli.app.add_option("--steps", steps, "ray-marching step lengths, in scene units")->delimiter(',');
  if (const auto done = cli.parse(argc, argv)) return *done;
  const render_options ro = [&] {
    render_options r = cli.render();
    r.progress = false;
    return r;
  }();

  return guarded([&] {
    if (cli.spp < 1 || cli.spp > 65536) throw error("--spp must be in 1..65536, got " + std::to_string(cli.spp));
    if (ref_spp < 1) throw error("--ref-spp must be at least 1, got " + std::to_string(ref_spp));
    if (steps.empty() || steps.size() > 8) throw error("--steps needs 1 to 8 step lengths");
    for (double s : steps)
      if (!(s > 0 && s < 1e6)) throw error("--steps: a step must be positive, got " + std::to_string(s));
    const loaded_scene ls = load_scene_argument(cli.scene);
    const scene& sc = ls.sc;
    if (sc.media.empty()) throw error("scene '" + cli.scene + "' has no media: this chapter compares media estimators");
    std::printf("scene %s: %zu medium(s)", cli.scene.c_str(), sc.media.size());
    for (const medium& m : sc.media)
      std::printf("; '%s' %s, sigma_t [%g %g %g], g %g", m.name.c_str(), m.homogeneous() ? "homogeneous" : "density grid",
                  m.sigma_t().x, m.sigma_t().y, m.sigma_t().z, m.g);
    std::printf("\n%s\n", light_set(sc).describe().c_str());

    if (sc.global_medium >= 0) {
      medium_options fine;
      fine.estimator = media_estimator::march;
      fine.step = 1e-3;
      render_stats st;
      const image tref = transmittance_view(sc, fine, 1, cli.seed, cli.width, cli.height, ro, st);
      std::printf("\n1. transmittance of '%s' along the camera rays; reference: march at step 0.001 (%.2f s), "
                  "mean %.5f\n%-12s %6s %10s %10s\n",
                  sc.media[std::size_t(sc.global_medium)].name.c_str(), st.seconds, image_mean(tref), "estimator",
                  "spp", "seconds", "RMSE");
      for (int n = 1; n <= 4 * cli.spp; n *= 4) {
        medium_options o;  // delta: ratio tracking
        const image a = transmittance_view(sc, o, n, cli.seed, cli.width, cli.height, ro, st);
        std::printf("%-12s %6d %10.4f %10.6f\n", "ratio", n, st.seconds, rmse(a, tref));
      }
      for (double step : steps) {
        medium_options o;
        o.estimator = media_estimator::march;
        o.step = step;
        const image a = transmittance_view(sc, o, 1, cli.seed, cli.width, cli.height, ro, st);
        std::printf("march %-6g %6d %10.4f %10.6f\n", step, 1, st.seconds, rmse(a, tref));
      }
      std::printf("\n2. the image\n");
    }
    const run_result ref = draw(sc, media_estimator::delta, 0, ref_spp, cli.seed + 1000, cli.width, cli.height, ro,
                                  sampler_kind::independent);
    std::printf("reference: delta tracking, %dx%d, %d spp, seed %llu, computed in this run: %.2f s, mean %.5f, "
                "%llu NaN/inf samples\n",
                cli.width, cli.height, ref_spp, (unsigned long long)(cli.seed + 1000), ref.stats.seconds,
                image_mean(ref.img), (unsigned long long)ref.stats.nonfinite);

    std::printf("sampler %s (the reference's: independent)\n", cli.sampler.c_str());
    // [listing media-table]
    std::printf("\n%-12s %6s %10s %10s %12s\n", "estimator", "spp", "seconds", "RMSE", "mean - ref");
    struct row {
      std::string name;
      media_estimator est;
      double step;
    };
    std::vector<row> rows{{"delta", media_estimator::delta, 0}};
    for (double s : steps) rows.push_back({"march " + std::to_string(s).substr(0, 6), media_estimator::march, s});
    std::uint64_t nonfinite = 0;
    std::vector<double> last_rmse;
    image figure;
    preview_window preview(cli, cli.width, cli.height, &ref.img);  // --window: each image of the table
    bool stopped = false;
    for (const row& w : rows) {
      double rmse_last = 0;
      for (int n = 1; n <= cli.spp && !stopped; n *= 4) {
        const run_result r = draw(sc, w.est, w.step, n, cli.seed, cli.width, cli.height, ro, cli.sampler_choice());
        nonfinite += r.stats.nonfinite;
        rmse_last = rmse(r.img, ref.img);
        std::printf("%-12s %6d %10.3f %10.5f %+12.5f\n", w.name.c_str(), n, r.stats.seconds, rmse_last,
                    image_mean(r.img) - image_mean(ref.img));
        if (w.est == media_estimator::delta) figure = r.img;  // at the largest spp in the end
        stopped = !preview.show(r.img, n, r.stats.seconds);  // stopped in the window
      }
      if (stopped) break;
      last_rmse.push_back(rmse_last);
    }
    // [end]
    if (stopped) std::printf("stopped in the window\n");
    if (!last_rmse.empty()) std::printf("\nat the largest spp: delta RMSE %.5f", last_rmse[0]);
    for (std::size_t i = 1; i < last_rmse.size(); ++i)
      std::printf("; %s %.5f (%.2fx delta's)", rows[i].name.c_str(), last_rmse[i], last_rmse[i] / last_rmse[0]);
    std::printf("\n%llu NaN/inf samples\n", (unsigned long long)nonfinite);
    write_image(figure, cli.out);
    write_image(ref.img, cli.sibling("-reference"));
    std::printf("wrote %s (delta tracking) and %s\n", cli.out.c_str(), cli.sibling("-reference").c_str());
    return nonfinite == 0 ? 0 : 1;
  });
}

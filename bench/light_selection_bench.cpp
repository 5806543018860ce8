// What choosing lights by power buys (lights.hpp, book 2.3). Not a test: it takes a minute.
// A room lit by one bright lamp and eight dim ones under the ceiling; mis with the lights chosen
// uniformly, then by power. A reference (by power, many samples, its own seed) is rendered
// first; uniform choice renders to --spp and its RMSE there is the target; choice by power
// renders until it reaches that RMSE. The table gives both times and their ratio.
#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>

#include <zraka/app/cli.hpp>

#include <cstdio>

using namespace zraka;

namespace {
// [listing bright-and-dim]
scene bright_and_dim(int dim_lights, float bright, float dim) {
  scene sc;
  const int white = sc.add_material(material::lambertian(rgb(0.7f)));
  const int strong = sc.add_material(material::emitter(rgb(bright)));
  const int weak = sc.add_material(material::emitter(rgb(dim)));
  sc.add(quad{{-2, 0, 2}, {4, 0, 0}, {0, 0, -4}}, white);    // floor
  sc.add(quad{{-2, 0, -2}, {4, 0, 0}, {0, 3, 0}}, white);    // back wall
  sc.add(quad{{-2, 3, -2}, {4, 0, 0}, {0, 0, 4}}, white);    // ceiling, facing down
  sc.add(sphere{{0.4, 0.6, -0.5}, 0.6}, white);
  sc.add(quad{{-1.6, 2.99, -1.6}, {0.4, 0, 0}, {0, 0, 0.4}}, strong);
  for (int i = 0; i < dim_lights; ++i) {
    const double x = -1.8 + 3.4 * (i + 0.5) / dim_lights;
    sc.add(quad{{x, 2.99, 1.0}, {0.3, 0, 0}, {0, 0, 0.3}}, weak);
  }
  sc.camera.position = {0, 1.5, 5};
  sc.camera.look_at = {0, 1.2, 0};
  sc.camera.vfov_degrees = 45;
  return sc;
}
// [end]
}  // namespace

int main(int argc, char** argv) {
  int W = 64, H = 64, spp = 256, ref_spp = 4096, threads = 2, dim_lights = 8;
  float bright = 200, dim = 2;
  std::uint64_t seed = 1;
  zraka::cli_app app{"Light selection benchmark: uniform against by power, time to equal error"};
  app.add_option("--width", W, "image width")->capture_default_str();
  app.add_option("--height", H, "image height")->capture_default_str();
  app.add_option("--spp", spp, "uniform choice's samples per pixel: its RMSE there is the target")->capture_default_str();
  app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference")->capture_default_str();
  app.add_option("--threads", threads, "threads")->capture_default_str();
  app.add_option("--dim-lights", dim_lights, "number of dim lamps")->capture_default_str();
  app.add_option("--bright", bright, "radiance of the bright lamp")->capture_default_str();
  app.add_option("--dim", dim, "radiance of each dim lamp")->capture_default_str();
  app.add_option("--seed", seed, "random seed (the reference uses seed + 1000)")->capture_default_str();
  if (const auto done = parse_command_line(app, argc, argv)) return *done;

  return guarded([&] {
    const stopwatch clock;
    if (dim_lights < 0 || dim_lights > 64) throw error("--dim-lights must be in 0..64");
    scene sc = bright_and_dim(dim_lights, bright, dim);
    image::check_size(W, H);
    sc.settings.width = W, sc.settings.height = H;
    const auto cam = sc.prepared_camera();
    auto tracer_for = [&](light_selection sel) {
      path_options o;
      o.lights = sel;
      return path_tracer(sc, o);
    };
    auto sampler = [&](const path_tracer& t) {
      return [&t, &cam, W, H](sample_context& c) {
        return t(cam.generate((c.x + 0.5) / W, (c.y + 0.5) / H), c.random, c.rays);
      };
    };
    std::printf("one lamp of radiance %g and %d of radiance %g, %dx%d, mis\n%s\n", bright, dim_lights, dim, W, H,
                tracer_for(light_selection::power).lights.describe().c_str());
    image ref(W, H);
    {
      const path_tracer t = tracer_for(light_selection::power);
      render_options ro;
      ro.threads = threads, ro.progress = false;
      const render_stats s = render(ref, ref_spp, seed + 1000, sampler(t), ro);
      std::printf("reference: by power, %d spp, %.1f s\n", ref_spp, s.seconds);
    }
    // [listing selection-efficiency]
    double target = 0, uniform_seconds = 0;
    std::printf("\n%-8s %8s %10s %10s %9s\n", "choice", "spp", "RMSE", "seconds", "speed-up");
    for (light_selection sel : {light_selection::uniform, light_selection::power}) {
      const path_tracer t = tracer_for(sel);
      progressive_options po;
      po.max_spp = sel == light_selection::uniform ? spp : 64 * spp;
      po.seed = seed;
      po.render.threads = threads, po.render.progress = false;
      convergence_log log(sel == light_selection::uniform ? "uniform" : "power", {"rmse"}, "rmse", "spp");
      render_progressive(W, H, po, sampler(t), [&](const image& mean, const progressive_totals& tot) {
        const double e = rmse(mean, ref);
        log.add(std::uint64_t(tot.spp), tot.seconds, {e});
        return sel == light_selection::uniform || e > target;
      });
      const auto& last = log.rows().back();
      if (sel == light_selection::uniform) target = last.values[0], uniform_seconds = last.seconds;
      const double secs = sel == light_selection::uniform ? uniform_seconds : seconds_to_reach(log, target);
      std::printf("%-8s %8llu %10.5f %10.3f %8.2fx\n", sel == light_selection::uniform ? "uniform" : "power",
                  static_cast<unsigned long long>(last.n), last.values[0], secs, uniform_seconds / secs);
    }
    // [end]
    std::printf("summary: target RMSE %.5f (uniform at %d spp); total %.1f s\n", target, spp, clock.seconds());
    return 0;
  });
}

// The path tracer's speed and efficiency on a Cornell box (book 4.2). Not a test: it takes one
// to two minutes and its numbers depend on the machine.
//  1. Throughput: samples/s and rays/s of each integrator on 1 and on 2 threads.
//  2. Efficiency: a reference (mis, many samples, its own seed), then naive rendered
//     progressively to --naive-spp; its RMSE there is the target. nee and mis render
//     progressively until they reach that RMSE; the table gives the time each needed
//     (interpolated between passes, progressive.hpp) and its speed-up over naive. Pixels are
//     sampled at their centres here, so the error is the light transport's alone (with jitter,
//     the edges of the directly seen light add the same noise to every integrator).
#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/scene/cornell.hpp>

#include <zraka/app/cli.hpp>

#include <cmath>
#include <cstdio>

using namespace zraka;

int main(int argc, char** argv) {
  std::string variant = "glass", reference, save_reference;
  int W = 64, H = 64, naive_spp = 1024, ref_spp = 4096, threads = 2, depth = 8;
  std::uint64_t seed = 1;
  zraka::cli_app app{"Path tracer benchmark: throughput, and time to reach naive's error (book 4.2)"};
  app.add_option("--variant", variant, "Cornell box: boxes, glass or spheres");
  app.add_option("--width", W, "image width");
  app.add_option("--height", H, "image height");
  app.add_option("--naive-spp", naive_spp, "naive's samples per pixel: its RMSE there is the target");
  app.add_option("--ref-spp", ref_spp, "samples per pixel of the mis reference");
  app.add_option("--reference", reference, "read the reference from this PFM instead of rendering it");
  app.add_option("--save-reference", save_reference, "write the rendered reference as PFM");
  app.add_option("--threads", threads, "threads for the efficiency runs");
  app.add_option("--depth", depth, "maximum bounces");
  app.add_option("--seed", seed, "random seed (the reference uses seed + 1000)");
  if (const auto done = parse_command_line(app, argc, argv)) return *done;

  return guarded([&] {
    const stopwatch clock;
    scene sc = cornell_box<double>(parse_cornell_variant(variant));
    image::check_size(W, H);
    sc.settings.width = W, sc.settings.height = H;
    const auto cam = sc.prepared_camera();
    const integrator methods[] = {integrator::naive, integrator::nee, integrator::mis};
    auto tracer_for = [&](integrator m) {
      path_options o;
      o.method = m;
      o.max_depth = depth;
      return path_tracer(sc, o);
    };
    auto sampler = [&](const path_tracer& t) {
      return [&t, &cam, W, H](sample_context& c) {
        return t(cam.generate((c.x + 0.5) / W, (c.y + 0.5) / H), c.random, c.rays);  // pixel centres
      };
    };
    std::printf("Cornell box (%s), %dx%d, at most %d bounces, Russian roulette from bounce 3\n",
                variant.c_str(), W, H, depth);

    // [listing throughput]
    std::printf("\nthroughput (%d spp per run)\n%-6s %7s %12s %12s %11s %8s\n", 16, "method", "threads",
                "M samples/s", "M rays/s", "rays/sample", "NaN/inf");
    for (integrator m : methods)
      for (int th : {1, 2}) {
        const path_tracer t = tracer_for(m);
        image img(W, H);
        render_options ro;
        ro.threads = th, ro.progress = false;
        const render_stats s = render(img, 16, seed, sampler(t), ro);
        std::printf("%-6s %7d %12.3f %12.3f %11.2f %8llu\n", name(m), th, double(s.samples) / s.seconds * 1e-6,
                    double(s.rays) / s.seconds * 1e-6, double(s.rays) / double(s.samples),
                    static_cast<unsigned long long>(s.nonfinite));
      }
    // [end]

    image ref;
    if (!reference.empty()) {
      ref = read_pfm(reference);
      check_same_size(image(W, H), ref);
      std::printf("\nreference: %s\n", reference.c_str());
    } else {
      const path_tracer t = tracer_for(integrator::mis);
      image img(W, H);
      render_options ro;
      ro.threads = threads, ro.progress = false;
      const render_stats s = render(img, ref_spp, seed + 1000, sampler(t), ro);
      ref = img;
      std::printf("\nreference: mis, %d spp, seed %llu, %.1f s\n", ref_spp,
                  static_cast<unsigned long long>(seed + 1000), s.seconds);
      if (!save_reference.empty()) write_pfm(ref, save_reference);
    }

    // [listing efficiency]
    double target = 0, naive_seconds = 0;
    std::printf("\ntime to reach the RMSE naive has at %d spp (%d thread%s)\n%-6s %8s %10s %12s %9s\n", naive_spp,
                threads, threads == 1 ? "" : "s", "method", "spp", "RMSE", "seconds", "speed-up");
    for (integrator m : methods) {
      const path_tracer t = tracer_for(m);
      progressive_options po;
      po.max_spp = naive_spp;
      po.seed = seed;
      po.render.threads = threads, po.render.progress = false;
      convergence_log log(name(m), {"rmse", "relmse"}, "rmse", "spp");
      render_progressive(W, H, po, sampler(t), [&](const image& mean, const progressive_totals& tot) {
        const double e = rmse(mean, ref);
        log.add(std::uint64_t(tot.spp), tot.seconds, {e, relmse(mean, ref)});
        return m == integrator::naive || e > target;  // the others stop once they are there
      });
      const auto& last = log.rows().back();
      if (m == integrator::naive) target = last.values[0], naive_seconds = last.seconds;
      const double secs = m == integrator::naive ? naive_seconds : seconds_to_reach(log, target);
      std::printf("%-6s %8llu %10.5f %12.3f %8.1fx\n", name(m), static_cast<unsigned long long>(last.n),
                  last.values[0], secs, naive_seconds / secs);
    }
    // [end]
    std::printf("summary: Cornell box (%s) %dx%d; the target RMSE %.5f is naive's at %d spp; total %.1f s\n",
                variant.c_str(), W, H, target, naive_spp, clock.seconds());
    return 0;
  });
}

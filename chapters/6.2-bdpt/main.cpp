// Chapter 6.2 — bidirectional path tracing (Lafortune and Willems 1993, Veach and Guibas 1994;
// erratum E2). A camera subpath and a light subpath per sample, joined in every way (s, t) and
// weighted by multiple importance sampling (include/zraka/integrators/bdpt.hpp). The program renders one
// scene with BDPT and with the path tracer of chapter 2.3 (`mis`), at 1, 2, 4, ... samples per
// pixel, and prints each one's error against run time against a reference: a long `mis` render
// (--ref-spp samples in two halves with seeds of their own, whose difference measures the
// reference's own noise, taken out of the errors; reference.hpp), kept in two PFM files next to --out
// and read back on the next run with the same scene, size, depth and reference samples. From the largest run, MSE x
// seconds is each method's cost, and the RMSE at equal time follows.
// --strategies N also writes the weighted image of every strategy of path length 1..N as a grid
// (row k = path length, column s = light vertices), so a student sees which strategy carries
// which light.
// --window shows bdpt | mis after each doubling of the samples (preview_window.hpp).
#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/app/reference.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/scene/scene_query.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

using namespace zraka;

namespace {

// Row k - 1 holds path length k; column s the strategy (s, k + 1 - s); gaps grey.
image strategy_grid(const std::vector<image>& strategies, int K, int W, int H) {
  const int gap = 2;
  image grid(K * W + (K - 1) * gap + W + gap, K * H + (K - 1) * gap, rgb(0.2f));
  for (int k = 1; k <= K; ++k)
    for (int s = 0; s <= k; ++s) {
      const image& im = strategies[std::size_t(strategy_slot(s, k + 1 - s))];
      for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) grid.at(s * (W + gap) + x, (k - 1) * (H + gap) + y) = im.at(x, y);
    }
  return grid;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 6.2: bidirectional path tracing against path tracing with MIS",
                      take::image | take::scene | take::depth | take::window};
  cli.scene_names = named_scene_list();
  cli.scene = "caustic-box", cli.out = "bdpt.png";
  cli.width = 48, cli.height = 48, cli.spp = 8, cli.depth = 8;
  int ref_spp = 256, strategies = 0;
  std::string heuristic = "power";
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference (mis, seed + 1000; cached as PFM)");
  cli.app.add_option("--strategies", strategies, "write the weighted image of every strategy of path length 1..N as a grid");
  cli.app.add_option("--heuristic", heuristic, "MIS over the strategies: power or balance");
  if (const auto done = cli.parse(argc, argv)) return *done;

  return guarded([&] {
    if (cli.spp & (cli.spp - 1)) throw error("--spp must be a power of 2, got " + std::to_string(cli.spp));
    const mis_heuristic mis_rule = parse_enum<mis_heuristic>(heuristic, "--heuristic");
    if (strategies < 0 || strategies > cli.depth + 1)
      throw error("--strategies must be from 0 to depth + 1 = " + std::to_string(cli.depth + 1));
    scene sc = load_scene_argument(cli.scene).sc;
    sc.settings.width = cli.width, sc.settings.height = cli.height;
    check_bdpt_scene(sc);  // before the reference is rendered
    sc.build_acceleration();
    const int W = cli.width, H = cli.height;
    const render_options ro = cli.render();
    path_options po;
    po.max_depth = cli.depth;
    bdpt_options bo;
    bo.max_depth = cli.depth;
    bo.heuristic = mis_rule;
    bo.threads = ro.threads;
    std::printf("scene %s, %dx%d, at most %d bounces; %s\n%s\n", cli.scene.c_str(), W, H, cli.depth,
                describe_built(sc).c_str(), light_set(sc).describe().c_str());
    std::uint64_t bad = 0;

    // The reference (reference.hpp): two halves of ref_spp / 2 samples with seeds of their own,
    // read back when an earlier run made them for the same scene file and settings.
    const mis_reference ref = program_reference(cli, sc, ref_spp, po, ro, bad);
    const image& reference = ref.img;
    // relMSE divides each pixel's squared error by ref^2 + 0.01, so fireflies in dark regions
    // count and the noise at the edges of a directly seen light (the pixel's jitter, the same
    // for both) counts less.
    auto error_of = [&](const image& img) { return ref.errors_of(img); };

    // [listing error-against-time]
    convergence_log log_b("bdpt on " + cli.scene, {"rmse", "relmse"}, "relmse", "spp");
    convergence_log log_m("mis on " + cli.scene, {"rmse", "relmse"}, "relmse", "spp");
    image last_b, last_m;
    std::vector<image> grid_images;
    const image both_ref = side_by_side({reference, reference});
    preview_window preview(cli, both_ref.width, H, &both_ref);  // --window: bdpt | mis after each run
    double shown_seconds = 0;
    for (int spp = 1; spp <= cli.spp; spp *= 2) {
      bo.strategy_length = spp == cli.spp ? strategies : 0;
      bdpt_render_t b = render_bdpt(sc, spp, cli.seed, bo);
      render_stats ms;
      image m = render_mis(sc, spp, cli.seed, po, ro, ms);
      bad += b.stats.nonfinite + ms.nonfinite;
      log_b.add(std::uint64_t(spp), b.stats.seconds, error_of(b.img));
      log_m.add(std::uint64_t(spp), ms.seconds, error_of(m));
      shown_seconds += b.stats.seconds + ms.seconds;
      last_b = std::move(b.img), last_m = std::move(m), grid_images = std::move(b.strategies);
      if (!preview.show(side_by_side({last_b, last_m}), spp, shown_seconds)) break;  // stopped in the window
    }
    // [end]
    const int done_spp = int(log_b.rows().back().n);  // cli.spp unless stopped in the window

    std::printf("\nerror against the reference, its own noise taken out [seconds]\n%6s %32s %32s\n", "spp",
                "bdpt: rmse relmse", "mis: rmse relmse");
    for (std::size_t i = 0; i < log_b.rows().size(); ++i) {
      const auto& b = log_b.rows()[i];
      const auto& m = log_m.rows()[i];
      std::printf("%6llu %10.5f %10.5f [%6.3f s] %10.5f %10.5f [%6.3f s]\n", static_cast<unsigned long long>(b.n),
                  b.values[0], b.values[1], b.seconds, m.values[0], m.values[1], m.seconds);
    }
    std::printf("bdpt: %s\nmis:  %s\n", log_b.slope_line().c_str(), log_m.slope_line().c_str());

    // [listing equal-time]
    // Equal time: relMSE ~ c / seconds for an unbiased estimator, c from the largest run.
    const auto& rb = log_b.rows().back();
    const auto& rm = log_m.rows().back();
    const double cost_b = rb.values[1] * std::max(rb.seconds, 1e-6);
    const double cost_m = rm.values[1] * std::max(rm.seconds, 1e-6);
    const double T = std::max(rb.seconds, rm.seconds);
    // [end]
    if (cost_b > 0 && cost_m > 0)
      std::printf("\nequal time (%.2f s): relMSE bdpt %.5f, mis %.5f: %s wins, %.2fx lower relMSE (%.2fx the time to "
                  "the same error)\n",
                  T, cost_b / T, cost_m / T, cost_b < cost_m ? "bdpt" : "mis",
                  std::max(cost_b, cost_m) / std::min(cost_b, cost_m), std::max(cost_b, cost_m) / std::min(cost_b, cost_m));
    else
      std::printf("\nequal time: an error is below the reference's own noise; use a larger --ref-spp\n");

    // Figure: bdpt | mis | reference at the largest spp.
    const image fig = side_by_side({last_b, last_m, reference});
    write_image(fig, cli.out);
    log_b.write_csv(cli.sibling("-bdpt", ".csv"));
    log_m.write_csv(cli.sibling("-mis", ".csv"));
    std::printf("wrote %s (bdpt, mis at %d spp, reference), %s, %s\n", cli.out.c_str(), done_spp,
                cli.sibling("-bdpt", ".csv").c_str(), cli.sibling("-mis", ".csv").c_str());
    if (strategies > 0 && done_spp < cli.spp)
      std::printf("%s not written: stopped in the window before the %d-spp run\n", cli.sibling("-strategies").c_str(),
                  cli.spp);
    else if (strategies > 0) {
      write_image(strategy_grid(grid_images, strategies, W, H), cli.sibling("-strategies"));
      std::printf("wrote %s: row k = path length 1..%d, column s = 0..k light vertices (t = k + 1 - s); "
                  "(1, 1) is left out (the camera path finds visible lights)\n",
                  cli.sibling("-strategies").c_str(), strategies);
    }
    std::printf("summary: %s %dx%d, %d spp: relMSE bdpt %.5f in %.2f s, mis %.5f in %.2f s; %llu NaN/inf samples\n",
                cli.scene.c_str(), W, H, done_spp, rb.values[1], rb.seconds, rm.values[1], rm.seconds,
                static_cast<unsigned long long>(bad));
    return 0;
  });
}

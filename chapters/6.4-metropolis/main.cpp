// Chapter 6.4 — Metropolis light transport in primary sample space (Kelemen et al. 2002, after
// Veach and Guibas 1997; errata E1–E4). Markov chains over the random numbers of the path tracer
// of chapter 2.3 (include/zraka/sampling/pss.hpp, include/zraka/integrators/metropolis.hpp): once a chain has found
// light that comes through a small opening, its small steps stay near that path and explore its
// neighbours, where independent samples would have to find the opening again each time.
// The program renders one scene with MLT, with BDPT (chapter 6.2) and with the path tracer
// (`mis`) at 1, 2, 4, ... mutations or samples per pixel and prints each one's error against run
// time against a long `mis` reference (reference.hpp: two cached halves, whose difference takes
// the reference's own noise out of the errors), then the bootstrap's normalisation and the
// acceptance rates. From the largest run, relMSE x seconds is each method's cost.
// --window shows mlt | bdpt | mis after each doubling (preview_window.hpp).
#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/app/reference.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/metropolis.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/scene/scene_query.hpp>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

using namespace zraka;

int main(int argc, char** argv) {
  program_options cli{"Chapter 6.4: Metropolis light transport (PSSMLT) against BDPT and path tracing with MIS "
                      "(--spp: mutations per pixel of the largest run)",
                      take::image | take::scene | take::depth | take::window};
  cli.scene_names = named_scene_list();
  cli.scene = "scenes/ajar-door.yaml", cli.out = "metropolis.png";
  cli.width = 64, cli.height = 48, cli.spp = 32, cli.depth = 8;
  int ref_spp = 512;
  metropolis_options mo;
  double bootstrap = 0.25;
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference (mis, seed + 1000; cached as PFM)");
  cli.app.add_option("--sigma", mo.pss.sigma, "standard deviation of a small step in primary sample space");
  cli.app.add_option("--large-step", mo.pss.large_step_prob, "probability of a large step (an independent sample)");
  cli.app.add_option("--chains", mo.chains, "Markov chains (fixed: the image does not depend on --threads)");
  cli.app.add_option("--bootstrap", bootstrap, "bootstrap samples per mutation (at least 1024 in all)");
  if (const auto done = cli.parse(argc, argv)) return *done;

  return guarded([&] {
    if (cli.spp & (cli.spp - 1)) throw error("--spp must be a power of 2, got " + std::to_string(cli.spp));
    if (!(bootstrap > 0 && bootstrap <= 16)) throw error("--bootstrap must be in (0, 16]");
    scene sc = load_scene_argument(cli.scene).sc;
    sc.settings.width = cli.width, sc.settings.height = cli.height;
    sc.build_acceleration();
    const int W = cli.width, H = cli.height;
    const render_options ro = cli.render();
    path_options po;
    po.max_depth = cli.depth;
    mo.threads = ro.threads;
    bdpt_options bo;
    bo.max_depth = cli.depth;
    bo.threads = ro.threads;
    std::optional<std::string> no_bdpt;  // BDPT refuses media and environment maps by name
    try {
      check_bdpt_scene(sc);
    } catch (const error& e) {
      no_bdpt = e.what();
    }
    check_pss_options(mo.pss);  // a bad --sigma before the reference
    std::printf("scene %s, %dx%d, at most %d bounces; %s\n%s\n", cli.scene.c_str(), W, H, cli.depth,
                describe_built(sc).c_str(), light_set(sc).describe().c_str());
    std::uint64_t bad = 0;
    const mis_reference ref = program_reference(cli, sc, ref_spp, po, ro, bad);
    if (no_bdpt) std::printf("bdpt: not compared on this scene (%s)\n", no_bdpt->c_str());

    // [listing mlt-error-against-time]
    convergence_log log_mlt("mlt on " + cli.scene, {"rmse", "relmse"}, "relmse", "mpp");
    convergence_log log_b("bdpt on " + cli.scene, {"rmse", "relmse"}, "relmse", "spp");
    convergence_log log_m("mis on " + cli.scene, {"rmse", "relmse"}, "relmse", "spp");
    image last_mlt, last_b, last_m;
    metropolis_render_t last;
    const image refs = side_by_side(std::vector<image>(no_bdpt ? 2 : 3, ref.img));
    preview_window preview(cli, refs.width, H, &refs, "per pixel");  // --window: each run, side by side
    double shown_seconds = 0;
    for (int n = 1; n <= cli.spp; n *= 2) {
      const std::uint64_t M = std::uint64_t(n) * std::uint64_t(W) * std::uint64_t(H);
      mo.bootstrap = std::max<std::uint64_t>(1024, std::uint64_t(bootstrap * double(M)));
      metropolis_render_t mlt = render_metropolis(sc, po, std::uint64_t(n), cli.seed, mo);
      log_mlt.add(std::uint64_t(n), mlt.seconds, ref.errors_of(mlt.img));
      render_stats ms;
      image m = render_mis(sc, n, cli.seed, po, ro, ms);
      log_m.add(std::uint64_t(n), ms.seconds, ref.errors_of(m));
      bad += mlt.nonfinite + ms.nonfinite;
      shown_seconds += mlt.seconds + ms.seconds;
      if (!no_bdpt) {
        bdpt_render_t b = render_bdpt(sc, n, cli.seed, bo);
        log_b.add(std::uint64_t(n), b.stats.seconds, ref.errors_of(b.img));
        bad += b.stats.nonfinite;
        shown_seconds += b.stats.seconds;
        last_b = std::move(b.img);
      }
      last_mlt = mlt.img, last_m = std::move(m), last = std::move(mlt);
      std::vector<image> shown{last_mlt};
      if (!no_bdpt) shown.push_back(last_b);
      shown.push_back(last_m);
      if (!preview.show(side_by_side(shown), n, shown_seconds)) break;  // stopped in the window
    }
    // [end]
    const int done_n = int(log_m.rows().back().n);  // cli.spp unless stopped in the window

    std::printf("\nerror against the reference, its own noise taken out [seconds]\n%6s %32s %32s %32s\n", "n",
                "mlt: rmse relmse", "bdpt: rmse relmse", "mis: rmse relmse");
    for (std::size_t i = 0; i < log_m.rows().size(); ++i) {
      auto cell = [](const convergence_log& log, std::size_t k) {
        char buf[64];
        if (k >= log.rows().size()) return std::string(32, ' ');
        const auto& r = log.rows()[k];
        std::snprintf(buf, sizeof buf, "%10.5f %10.5f [%6.3f s]", r.values[0], r.values[1], r.seconds);
        return std::string(buf);
      };
      std::printf("%6llu %s %s %s\n", static_cast<unsigned long long>(log_m.rows()[i].n), cell(log_mlt, i).c_str(),
                  cell(log_b, i).c_str(), cell(log_m, i).c_str());
    }
    std::printf("mlt:  %s\n", log_mlt.slope_line().c_str());
    if (!no_bdpt) std::printf("bdpt: %s\n", log_b.slope_line().c_str());
    std::printf("mis:  %s\n", log_m.slope_line().c_str());
    std::printf("\nmetropolis at %d mutations per pixel: %llu mutations in %d chains, sigma %.4g, large steps %.2f; "
                "bootstrap %llu samples in %.3f s, b = %.6g; acceptance %.3f (small steps %.3f, large steps %.3f)\n",
                done_n, static_cast<unsigned long long>(last.mutations), mo.chains, mo.pss.sigma,
                mo.pss.large_step_prob, static_cast<unsigned long long>(mo.bootstrap), last.bootstrap_seconds, last.b,
                last.acceptance, last.small_acceptance, last.large_acceptance);

    // [listing mlt-equal-time]
    // Equal time: relMSE ~ c / seconds, c from each method's largest run (for MLT only
    // asymptotically: its samples are correlated, so the constant is what the run measured).
    struct cost_t { const char* name; double cost; };
    std::vector<cost_t> costs;
    for (const auto* log : {&log_mlt, &log_b, &log_m})
      if (!log->rows().empty())
        costs.push_back({log == &log_mlt ? "mlt" : log == &log_b ? "bdpt" : "mis",
                         log->rows().back().values[1] * std::max(log->rows().back().seconds, 1e-6)});
    double T = 0;
    for (const auto* log : {&log_mlt, &log_b, &log_m})
      if (!log->rows().empty()) T = std::max(T, log->rows().back().seconds);
    // [end]
    std::printf("\nequal time (%.2f s), relMSE:", T);
    for (const auto& c : costs) std::printf(" %s %.5f", c.name, c.cost / T);
    std::printf("\n");
    const double cm = costs.front().cost, cmis = costs.back().cost;  // mlt first, mis last
    if (cm > 0 && cmis > 0) {
      std::printf("mlt reaches the same error as mis in %.2fx the time", cm / cmis);
      if (!no_bdpt) std::printf("; bdpt in %.3fx", costs[1].cost / cmis);
      std::printf("\n");
    } else
      std::printf("an error is below the reference's own noise; use a larger --ref-spp\n");

    std::vector<image> tiles{last_mlt};
    if (!no_bdpt) tiles.push_back(last_b);
    tiles.push_back(last_m), tiles.push_back(ref.img);
    write_image(side_by_side(tiles), cli.out);
    log_mlt.write_csv(cli.sibling("-mlt", ".csv"));
    if (!no_bdpt) log_b.write_csv(cli.sibling("-bdpt", ".csv"));
    log_m.write_csv(cli.sibling("-mis", ".csv"));
    std::printf("wrote %s (mlt, %smis at %d per pixel, reference), %s\n", cli.out.c_str(), no_bdpt ? "" : "bdpt, ",
                done_n, cli.sibling("-{mlt,bdpt,mis}", ".csv").c_str());
    std::printf("summary: %s %dx%d, %d per pixel: relMSE mlt %.5f in %.2f s, mis %.5f in %.2f s; acceptance %.3f; "
                "%llu NaN/inf samples\n",
                cli.scene.c_str(), W, H, done_n, log_mlt.rows().back().values[1], log_mlt.rows().back().seconds,
                log_m.rows().back().values[1], log_m.rows().back().seconds, last.acceptance,
                static_cast<unsigned long long>(bad));
    return 0;
  });
}

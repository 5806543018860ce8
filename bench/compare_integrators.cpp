// Every integrator zraka has, on the stiff scenes, in one run (book 6.5). Not a test: it takes
// minutes. For each scene a `mis` reference (reference.hpp: two halves, its own noise taken out)
// is made first; then naive, nee and mis path tracing (2.3), BDPT (6.2), SPPM (6.3) and MLT (6.4)
// each render at 1, 2, 4, ... samples (passes, mutations) per pixel until their RMSE is at most
// --target or a run takes more than --max-seconds. The time to reach the target is interpolated
// log-log between the two rows that bracket it. One table per scene; one CSV per scene and
// integrator (build/out/compare-<scene>-<integrator>.csv, for tools/plot_convergence.py).
//   build/bin/compare_integrators [--scenes a,b,c] [--width W --height H] [--target RMSE]
//                                 [--max-seconds S] [--ref-spp N] [--threads T] [--seed S]
#include <zraka/app/cli.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/app/reference.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/metropolis.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/integrators/sppm.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/convergence.hpp>

#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

using namespace zraka;


int main(int argc, char** argv) {
  program_options cli{"Every integrator on the stiff scenes: time to reach an RMSE (book 6.5)",
                      take::size | take::seed | take::threads | take::depth};
  cli.width = 48, cli.height = 36, cli.depth = 8;
  std::string scenes = "ajar-door,caustic-box,tiny-light";
  double target = 0.05, max_seconds = 4;
  int ref_spp = 2048;
  std::uint64_t photons = 5000;
  cli.app.add_option("--scenes", scenes, "comma-separated scene names or .yaml files");
  cli.app.add_option("--target", target, "the RMSE to reach (the reference's own noise taken out)");
  cli.app.add_option("--max-seconds", max_seconds, "an integrator stops after a run longer than this");
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of each scene's mis reference (cached)");
  cli.app.add_option("--photons", photons, "SPPM photons per pass");
  if (const auto done = cli.parse(argc, argv)) return *done;

  return guarded([&] {
    if (!(target > 0)) throw error("--target must be positive");
    if (!(max_seconds > 0)) throw error("--max-seconds must be positive");
    std::vector<std::string> names;
    std::stringstream ss(scenes);
    for (std::string s; std::getline(ss, s, ',');)
      if (!s.empty()) names.push_back(s);
    if (names.empty()) throw error("--scenes names no scene");
    render_options ro;
    ro.threads = cli.threads, ro.progress = false;
    const stopwatch total;
    std::printf("target RMSE %.4f at %dx%d, at most %d bounces, seed %llu; time in seconds on %d threads "
                "(interpolated log-log; '>' = not reached, with the RMSE of the last run)\n",
                target, cli.width, cli.height, cli.depth, static_cast<unsigned long long>(cli.seed), cli.threads);
    for (const std::string& name : names) {
      scene sc = load_scene_argument(name).sc;
      sc.settings.width = cli.width, sc.settings.height = cli.height;
      sc.build_acceleration();
      path_options po;
      po.max_depth = cli.depth;
      std::uint64_t bad = 0;
      const std::string tag = reference_tag(name, cli.width, cli.height, cli.depth, ref_spp);
      const mis_reference ref = make_mis_reference(
          sc, ref_spp, cli.seed, po, ro, [&](const std::string& h) { return output_file("compare" + tag + h + ".pfm").string(); },
          bad);
      std::printf("\nscene %s: reference mis %d spp, its own RMSE %.5f\n%-8s %12s %8s %10s\n", name.c_str(), ref_spp,
                  std::sqrt(ref.mse_noise), "method", "seconds", "n", "rmse");

      // Each integrator: image at budget n (spp, passes or mutations per pixel), in the same run.
      struct method_t {
        std::string name;
        std::function<image(int)> at;
        std::optional<std::string> refused;
      };
      std::vector<method_t> methods;
      for (const integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
        path_options p = po;
        p.method = m;
        methods.push_back({zraka::name(m), [&sc, p, &ro, &cli](int n) {
                             render_stats st;
                             return render_mis(sc, n, cli.seed, p, ro, st);
                           }, std::nullopt});
      }
      bdpt_options bo;
      bo.max_depth = cli.depth, bo.threads = cli.threads;
      methods.push_back({"bdpt", [&](int n) { return render_bdpt(sc, n, cli.seed, bo).img; }, std::nullopt});
      sppm_options so;
      so.photons_per_pass = photons, so.seed = cli.seed, so.threads = cli.threads, so.max_depth = cli.depth;
      methods.push_back({"sppm", [&](int n) {
                           sppm_t<double> s(sc, so);  // a fresh estimator: each row is a run of its own
                           while (s.passes() < n) s.run_pass();
                           return s.estimate();
                         }, std::nullopt});
      metropolis_options mo;
      mo.threads = cli.threads;
      methods.push_back({"mlt", [&](int n) {
                           mo.bootstrap = std::max<std::uint64_t>(1024, std::uint64_t(n) * std::uint64_t(cli.width * cli.height) / 4);
                           return render_metropolis(sc, po, std::uint64_t(n), cli.seed, mo).img;
                         }, std::nullopt});

      for (method_t& m : methods) {
        convergence_log log(m.name + " on " + name, {"rmse", "relmse"}, "rmse", "n");
        try {
          for (int n = 1; n <= 65536; n *= 2) {
            const stopwatch clock;
            const image img = m.at(n);
            const double secs = clock.seconds();
            const auto e = ref.errors_of(img);
            log.add(std::uint64_t(n), secs, e);
            if (e[0] <= target || secs > max_seconds) break;
          }
        } catch (const error& e) {
          m.refused = e.what();
        }
        if (m.refused) {
          std::printf("%-8s refused: %s\n", m.name.c_str(), m.refused->c_str());
          continue;
        }
        log.write_csv(output_file("compare-" + std::filesystem::path(name).stem().string() + "-" + m.name + ".csv"));
        const convergence_row& last = log.rows().back();
        if (const double t = seconds_to_reach(log, target); !std::isnan(t))
          std::printf("%-8s %12.3f %8llu %10.5f\n", m.name.c_str(), t, static_cast<unsigned long long>(last.n),
                      last.values[0]);
        else
          std::printf("%-8s %12s %8llu %10.5f\n", m.name.c_str(), (">" + std::to_string(last.seconds).substr(0, 6)).c_str(),
                      static_cast<unsigned long long>(last.n), last.values[0]);
      }
      if (bad) std::printf("  %llu NaN/inf samples in the reference\n", static_cast<unsigned long long>(bad));
    }
    std::printf("\nsummary: %zu scenes, 6 integrators in %.1f s\n", names.size(), total.seconds());
    return 0;
  });
}

#pragma once
// The `pathtrace` program (book 2.3) as a function: chapter 2.3's main.cpp calls it with an
// empty registry, and a course's own program calls it with the registry of its shapes,
// materials and integrators (scene_registry.hpp), so the course's binary has pathtrace's whole
// command line (--scene names, .yaml and Mitsuba .xml files, --integrator, --sampler,
// --reference, --report, --window, --time-budget, --seed, --export, ...) and scene files that
// name its own kinds:
//
//     int main(int argc, char** argv) {
//       zraka::scene_registry reg;
//       mycourse::register_types(reg);  // reg.add_shape("torus", ...), reg.add_material(...)
//       return zraka::pathtrace_main(argc, argv, reg);
//     }
//
// What it does: renders a scene with one of three integrators of the rendering equation
// (path.hpp): `naive` (bounce until a light is hit by chance), `nee` (next-event estimation: ask
// a light at every diffuse hit) and `mis` (light and BSDF sampling combined by multiple
// importance sampling), or with an integrator the course registered (reg.add_integrator;
// integrators/integrator_door.hpp looks the name up among both). The image is refined in passes
// that double the samples per pixel (progressive.hpp); with --reference it prints, after every
// pass, the error against that image and the time so far, and --report writes the same table as
// CSV for tools/plot_convergence.py.
// --time-budget stops the doubling early. --window shows the image as the passes finish
// (preview_window.hpp). --sampler picks where each sample's numbers come from (samplers.hpp,
// book 5.1). For `--scene furnace` (named_scenes.hpp) it checks the closed form.
//
// Compiled once into zraka::compiled where zraka was built with yaml-cpp (ZRAKA_COMPILED_SCENE_FILE:
// the scene argument needs the scene reader), in a unit of its own (src/pathtrace_main.cpp), so a
// program that calls it compiles only this declaration; header-only, inline. The resource root is
// the calling program's (compiled.hpp), passed by the inline wrapper.
#include <zraka/core/compiled.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <filesystem>

#if defined(ZRAKA_COMPILED_SCENE_FILE)
#define ZRAKA_PATHTRACE_MAIN_FN
#else
#define ZRAKA_PATHTRACE_MAIN_FN inline
#endif
#if !defined(ZRAKA_COMPILED_SCENE_FILE) || defined(ZRAKA_COMPILING_PATHTRACE_MAIN)
#define ZRAKA_PATHTRACE_MAIN_DEFINITIONS 1
#else
#define ZRAKA_PATHTRACE_MAIN_DEFINITIONS 0
#endif

#if ZRAKA_PATHTRACE_MAIN_DEFINITIONS
#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/integrator_door.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/io/mitsuba_export.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/named_scenes.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#endif

namespace zraka {

namespace detail {
ZRAKA_PATHTRACE_MAIN_FN int pathtrace_main_in(int argc, char** argv, const scene_registry& registry,
                                              const std::filesystem::path& root)
#if ZRAKA_PATHTRACE_MAIN_DEFINITIONS
{
  program_options opt{"Chapter 2.3: path tracing with the naive, nee or mis integrator, error against run time",
                      take::scene | take::image | take::depth | take::window | take::sampler};
  opt.scene_names = named_scene_list();
  opt.scene = "cornell-glass", opt.out = "pathtrace.png", opt.scene_settings = true;
  opt.min_depth = 0, opt.max_depth = 1000;
  std::string method = "mis", selection = "power", pfm, reference, report, json;
  int rr_depth = 3;
  double budget = 0;
  bool centre = false;
  zraka::cli_app& app = opt.app;
  app.add_option("--integrator", method, integrator_choices(registry));  // the course's too
  app.add_option("--rr-depth", rr_depth, "Russian roulette from this many bounces on");
  app.add_option("--lights", selection, "how next-event estimation chooses a light: power or uniform");
  app.add_flag("--centre", centre, "sample every pixel at its centre (no anti-aliasing): the error against a "
               "reference made the same way is then the light transport's alone");
  app.add_option("--time-budget", budget, "stop doubling the samples after this many seconds (0 = no limit)");
  app.add_option("--reference", reference, "reference image (.pfm or .exr): print the error after every pass");
  app.add_option("--report", report, "write the error table as CSV (needs --reference)");
  app.add_option("--pfm", pfm, "also write the linear image as PFM (e.g. to be a reference)");
  app.add_option("--export", json, "write the scene as JSON for tools/mitsuba_reference.py and stop");
  if (const auto done = opt.parse(argc, argv, root)) return *done;

  return guarded([&] {
    const stopwatch clock;
    const std::string& scene_name = opt.scene;
    scene sc = load_scene_argument_in(scene_name, root, registry).sc;  // the course's kinds too
    opt.apply_to(sc.settings);
    method = chosen_integrator(method, opt.given("--integrator"), sc, scene_name, registry);  // or the scene's
    const int W = opt.width, H = opt.height;
    for (std::string* f : {&pfm, &report, &json})
      if (!f->empty()) {  // checked before the render, so a failed run leaves no image behind
        *f = output_file_under(*f, root).string();
        check_output_name(*f);
      }
    path_options io;
    const auto& make_integrator = find_integrator(method, registry);  // built in or the course's
    if (builtin_integrators().integrator_type(method)) io.method = parse_integrator(method);
    io.max_depth = opt.depth;
    io.rr_depth = rr_depth;
    io.lights = parse_enum<light_selection>(selection, "--lights");
    if (!report.empty() && reference.empty()) throw error("--report needs --reference");
    if (!json.empty()) {  // for the Mitsuba reference (mitsuba_export.hpp), then stop
      write_file_atomically(json, mitsuba_scene_json(sc, W, H, io.max_depth));
      std::printf("wrote %s (%zu spheres, %zu quads, %zu materials)\n", json.c_str(), sc.spheres.size(),
                  sc.quads.size(), sc.materials.size());
      return 0;
    }
    std::optional<image> ref;
    if (!reference.empty()) {
      ref = read_float_image(input_file(reference));
      check_same_size(image(W, H), *ref);
    }

    // [listing render]
    // The integrator (integrator_door.hpp); a built-in is the path tracer, called directly.
    const scene_registry::radiance_fn radiance = make_integrator(sc, io);
    const path_tracer* const tracer = radiance.target<path_tracer>();
    const auto cam = sc.prepared_camera();
    const sampler_kind sampler = opt.sampler_choice();
    progressive_options po;
    po.max_spp = opt.spp;
    po.time_budget = budget;
    po.seed = opt.seed;
    po.render.threads = opt.threads;
    convergence_log log("error of " + scene_name + " (" + method + ") against " + reference,
                        {"rmse", "relmse"}, "rmse", "spp");
    progressive_totals tot;
    preview_window preview(opt, W, H, ref ? &*ref : nullptr, "spp", root);  // --window: the passes as they finish
    auto render_with = [&](const auto& estimate) {  // estimate(camera ray, stream, rays) -> radiance
      auto sample = [&](sample_context& c) {
        sample_point point(sampler, opt.seed, std::uint32_t(c.y) * std::uint32_t(W) + std::uint32_t(c.x),
                           std::uint32_t(c.sample), std::uint32_t(c.spp));
        point.drive(c.random);  // the sampler's numbers for this sample (independent: the stream's own)
        const vec2 o = centre ? vec2(0.5) : pixel_sample(pixel_pattern::uniform, c.sample, c.spp, c.random);
        return estimate(cam.generate((c.x + o.x) / W, (c.y + o.y) / H), c.random, c.rays);
      };
      return render_progressive(W, H, po, sample, [&](const image& mean, const progressive_totals& t) {
        if (ref) log.add(std::uint64_t(t.spp), t.seconds, {rmse(mean, *ref), relmse(mean, *ref)});
        return preview.show(mean, t.spp, t.seconds);  // false: stopped in the window
      }, &tot);
    };
    const image img = tracer ? render_with(*tracer) : render_with(radiance);
    // [end]

    if (tracer) {
      std::printf("scene %s, %dx%d; %s\n%s\n", scene_name.c_str(), W, H, describe_built(sc).c_str(),
                  tracer->lights.describe().c_str());
      std::printf("integrator %s%s, at most %d bounces, Russian roulette from bounce %d\n", name(io.method),
                  io.method == integrator::mis ? " (power heuristic)" : "", io.max_depth, io.rr_depth);
    } else {
      std::printf("scene %s, %dx%d; %s\n", scene_name.c_str(), W, H, describe_built(sc).c_str());
      std::printf("integrator %s (the course's own), depth %d\n", method.c_str(), io.max_depth);
    }
    std::printf("sampler %s\n", name(sampler));
    if (ref) {
      std::printf("%s", log.table().c_str());
      std::printf("%s\n", log.slope_line().c_str());
      if (!report.empty()) {
        log.write_csv(report);
        std::printf("wrote %s\n", report.c_str());
      }
    }
    if (tot.out_of_time)
      std::printf("time budget %.3g s: stopped at %d spp\n", budget, tot.spp);
    const vec3 mean = channel_mean(img);
    std::printf("mean radiance: %.5f %.5f %.5f\n", mean.x, mean.y, mean.z);
    if (scene_name == "furnace") {
      const double a = furnace_albedo, truncated = furnace_Le * (1 - std::pow(a, io.max_depth + 1)) / (1 - a);
      std::printf("furnace: expected Le/(1-a) = %.5f, with %d bounces Le(1-a^%d)/(1-a) = %.5f; "
                  "measured/expected - 1 = %+.2e\n",
                  furnace_Le / (1 - a), io.max_depth, io.max_depth + 1, truncated, mean.x / truncated - 1);
      // A loose bound (2%) that a few thousand samples meet many times over: a gross check only;
      // tests/test_path.cpp holds the statistical one.
      if (tot.stats.samples >= 4096)
        std::printf("furnace check: %s (|measured/expected - 1| < 2%%)\n",
                    std::abs(mean.x / truncated - 1) < 0.02 ? "ok" : "FAILED");
    }
    write_image(img, opt.out);
    std::printf("wrote %s\n", opt.out.c_str());
    if (!pfm.empty()) {
      write_pfm(img, pfm);
      std::printf("wrote %s\n", pfm.c_str());
    }
    const double secs = std::max(tot.seconds, 1e-9);
    std::printf("summary: %s %s %dx%d, %d spp in %.2f s on %d thread%s: %.3f M samples/s, %.3f M rays/s, "
                "%.2f rays/sample, %llu NaN/inf samples; total %.2f s; scene choices: %s\n",
                scene_name.c_str(), method.c_str(), W, H, tot.spp, tot.seconds, tot.stats.threads,
                tot.stats.threads == 1 ? "" : "s", double(tot.stats.samples) / secs * 1e-6,
                double(tot.stats.rays) / secs * 1e-6, double(tot.stats.rays) / double(std::max<std::uint64_t>(tot.stats.samples, 1)),
                static_cast<unsigned long long>(tot.stats.nonfinite), clock.seconds(),
                tracer ? tracer->choices().c_str() : ("integrator " + method + ", the course's own").c_str());
    return 0;
  });
}
#else
    ;
#endif
}  // namespace detail

// The whole `pathtrace` program: parses argv, renders, writes; returns main's exit code (0, or 1
// with "error: ..." on stderr for bad input). `registry`: the program's own kinds for --scene files.
inline int pathtrace_main(int argc, char** argv, const scene_registry& registry = {}) {
  return detail::pathtrace_main_in(argc, argv, registry, resource_root());
}

}  // namespace zraka

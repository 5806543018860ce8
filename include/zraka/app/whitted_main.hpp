#pragma once
// The `whitted` program (book 2.2) as a function: chapter 2.2's main.cpp calls it without a
// registry, and a course's own program calls it with the registry of its shapes and materials
// (scene_registry.hpp), so that its binary offers the Whitted ray tracer on its scene files too.
// Whitted renders a course's shapes (they go through scene_query.hpp like any shape); a custom BSDF
// it cannot shade, and it refuses the scene by the material's name and says which program can
// (whitted.hpp's check_whitted_scene).
//
// What it does: takes a scene (--scene: a name such as `default` or `box`, or a scene file, book
// 4.1), builds what the scene needs (an object BVH only when it pays, a triangle BVH per mesh),
// renders it on all cores with whitted.hpp, and writes the image (and optionally a linear PFM).
// The image is the same for the same seed on any number of threads.
//
// Compiled once into zraka::compiled where zraka was built with yaml-cpp (ZRAKA_COMPILED_SCENE_FILE),
// in a unit of its own (src/whitted_main.cpp); header-only, inline. The resource root is the
// calling program's (compiled.hpp), passed by the inline wrapper.
#include <zraka/core/compiled.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <filesystem>

#if defined(ZRAKA_COMPILED_SCENE_FILE)
#define ZRAKA_WHITTED_MAIN_FN
#else
#define ZRAKA_WHITTED_MAIN_FN inline
#endif
#if !defined(ZRAKA_COMPILED_SCENE_FILE) || defined(ZRAKA_COMPILING_WHITTED_MAIN)
#define ZRAKA_WHITTED_MAIN_DEFINITIONS 1
#else
#define ZRAKA_WHITTED_MAIN_DEFINITIONS 0
#endif

#if ZRAKA_WHITTED_MAIN_DEFINITIONS
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/integrator_door.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/scene/named_scenes.hpp>

#include <algorithm>
#include <cstdio>
#include <string>
#endif

namespace zraka {

namespace detail {
ZRAKA_WHITTED_MAIN_FN int whitted_main_in(int argc, char** argv, const scene_registry& registry,
                                          const std::filesystem::path& root)
#if ZRAKA_WHITTED_MAIN_DEFINITIONS
{
  program_options po{"Chapter 2.2: a Whitted ray tracer (shadows, mirrors, glass)",
                     take::scene | take::image | take::depth};
  po.scene_names = named_scene_list();
  po.scene = "default", po.out = "whitted.png", po.scene_settings = true;
  std::string pfm;
  bool blinn = false;
  po.app.add_option("--pfm", pfm, "also write the linear image to this PFM file");
  po.app.add_flag("--blinn", blinn, "Blinn-Phong highlights instead of Phong");
  if (const auto done = po.parse(argc, argv, root)) return *done;

  return guarded([&] {
    stopwatch total;
    if (!pfm.empty()) {  // checked before the render, so a failed run leaves no image behind
      pfm = output_file_under(pfm, root).string();
      check_output_name(pfm);
    }
    loaded_scene ls = load_scene_argument_in(po.scene, root, registry);  // the course's kinds too
    scene& sc = ls.sc;
    po.apply_to(sc.settings);
    // A scene file's settings.integrator is the path tracers'; a course's is refused by name.
    refuse_course_integrator(chosen_integrator("", false, sc, po.scene, registry), registry, "whitted",
                             "the Whitted ray tracer");
    render_options ro;
    ro.threads = po.threads;
    whitted_options opt;
    opt.max_depth = sc.settings.max_depth;
    opt.model = blinn ? local_model::blinn_phong : local_model::phong;
    std::printf("scene: %s\n%s\n%s\n", po.scene.c_str(), describe_built(sc).c_str(), light_set(sc).describe().c_str());
    std::fflush(stdout);

    image img(sc.settings.width, sc.settings.height);
    const render_stats st = render_whitted(sc, img, opt, ro);
    write_image(img, po.out);
    if (!pfm.empty()) write_pfm(img, pfm);
    std::printf("%s\nwrote %s%s%s\n", summary(img, sc.settings.spp, st).c_str(), po.out.c_str(),
                pfm.empty() ? "" : " and ", pfm.c_str());
    std::printf("summary: %.2f s in all; %dx%d, %d spp, depth %d, %s; %.2f M rays/s; %llu NaN/inf samples\n",
                total.seconds(), img.width, img.height, sc.settings.spp, opt.max_depth,
                blinn ? "Blinn-Phong" : "Phong", double(st.rays) / std::max(st.seconds, 1e-9) * 1e-6,
                static_cast<unsigned long long>(st.nonfinite));
    return 0;
  });
}
#else
    ;
#endif
}  // namespace detail

// The whole `whitted` program: parses argv, renders, writes; returns main's exit code (0, or 1
// with "error: ..." on stderr for bad input). `registry`: the program's own kinds for --scene files.
inline int whitted_main(int argc, char** argv, const scene_registry& registry = {}) {
  return detail::whitted_main_in(argc, argv, registry, resource_root());
}

}  // namespace zraka

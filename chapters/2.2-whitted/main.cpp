// Chapter 2.2 — the Whitted ray tracer. Reads a scene file (book 4.1, scenes/README.md), builds
// what the scene needs (an object BVH only when it pays, a triangle BVH per mesh), renders it
// on all cores with whitted.hpp, and writes a PNG (and optionally a linear PFM).
//
//   whitted                        renders scenes/default.yaml to whitted.png
//   whitted scenes/box.yaml --out box.png --spp 4
//
// The image is the same for the same seed on any number of threads.
#include <zraka/cli.hpp>
#include <zraka/error.hpp>
#include <zraka/image_io.hpp>
#include <zraka/render.hpp>
#include <zraka/scene_file.hpp>
#include <zraka/whitted.hpp>

#include <cstdio>
#include <filesystem>
#include <optional>

using namespace zraka;

int main(int argc, char** argv) {
  std::string scene_path = "scenes/default.yaml", out = "whitted.png", pfm;
  std::optional<int> width, height, spp, depth;
  std::optional<std::uint64_t> seed;
  bool blinn = false;
  render_options ro;
  CLI::App app{"Chapter 2.2: a Whitted ray tracer for YAML scenes (shadows, mirrors, glass)"};
  app.add_option("scene", scene_path, "scene file (default scenes/default.yaml)");
  app.add_option("--out", out, "output image (.png, .ppm or .pfm)");
  app.add_option("--pfm", pfm, "also write the linear image to this PFM file");
  app.add_option("--width", width, "override settings.width");
  app.add_option("--height", height, "override settings.height");
  app.add_option("--spp", spp, "override settings.spp (samples per pixel)");
  app.add_option("--depth", depth, "override settings.max_depth (depth of the ray tree)");
  app.add_option("--seed", seed, "override settings.seed");
  app.add_option("--threads", ro.threads, "threads (0 = all cores)");
  app.add_flag("--blinn", blinn, "Blinn-Phong highlights instead of Phong");
  if (const auto done = parse_command_line(app, argc, argv)) return *done;

  return guarded([&] {
    stopwatch total;
    resolve_threads(ro.threads);  // bad arguments fail before any work
    const std::string ext = std::filesystem::path(out).extension().string();
    if (ext != ".png" && ext != ".ppm" && ext != ".pfm")
      throw error("--out " + out + ": unknown image type '" + ext + "' (use .png, .ppm or .pfm)");
    loaded_scene ls = load_scene_file(scene_path);
    scene& sc = ls.sc;
    if (width) sc.settings.width = *width;
    if (height) sc.settings.height = *height;
    image::check_size(sc.settings.width, sc.settings.height);
    if (spp) {
      if (*spp < 1 || *spp > scene_file_defaults::max_spp) throw error("--spp must be in 1..65536");
      sc.settings.spp = *spp;
    }
    if (depth) {
      if (*depth < 1 || *depth > scene_file_defaults::max_depth) throw error("--depth must be in 1..64");
      sc.settings.max_depth = *depth;
    }
    if (seed) sc.settings.seed = *seed;
    whitted_options opt;
    opt.max_depth = sc.settings.max_depth;
    opt.model = blinn ? local_model::blinn_phong : local_model::phong;
    std::printf("scene: %s\n%s\n%s\n", scene_path.c_str(), describe_built(sc).c_str(), light_set(sc).describe().c_str());
    std::fflush(stdout);

    image img(sc.settings.width, sc.settings.height);
    const render_stats st = render_whitted(sc, img, opt, ro);
    write_image(img, out);
    if (!pfm.empty()) write_pfm(img, pfm);
    std::printf("%s\nwrote %s%s%s\n", summary(img, sc.settings.spp, st).c_str(), out.c_str(),
                pfm.empty() ? "" : " and ", pfm.c_str());
    std::printf("summary: %.2f s in all; %dx%d, %d spp, depth %d, %s; %.2f M rays/s; %llu NaN/inf samples\n",
                total.seconds(), img.width, img.height, sc.settings.spp, opt.max_depth,
                blinn ? "Blinn-Phong" : "Phong", double(st.rays) / std::max(st.seconds, 1e-9) * 1e-6,
                static_cast<unsigned long long>(st.nonfinite));
    return 0;
  });
}

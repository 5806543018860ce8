// Chapter 2.2 — the Whitted ray tracer. Takes a scene (--scene: a name such as `default` or
// `box`, or a scene file, book 4.1, scenes/README.md), builds what the scene needs (an object
// BVH only when it pays, a triangle BVH per mesh), renders it on all cores with whitted.hpp,
// and writes the image (and optionally a linear PFM).
//
//   whitted                                   renders the default scene to whitted.png
//   whitted --scene box --out box.png --spp 4
//
// The image is the same for the same seed on any number of threads.
#include <zraka/core/error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/integrators/whitted.hpp>

#include <cstdio>

using namespace zraka;

int main(int argc, char** argv) {
  program_options po{"Chapter 2.2: a Whitted ray tracer (shadows, mirrors, glass)",
                     take::scene | take::image | take::depth};
  po.scene_names = named_scene_list();
  po.scene = "default", po.out = "whitted.png", po.scene_settings = true;
  std::string pfm;
  bool blinn = false;
  po.app.add_option("--pfm", pfm, "also write the linear image to this PFM file");
  po.app.add_flag("--blinn", blinn, "Blinn-Phong highlights instead of Phong");
  if (const auto done = po.parse(argc, argv)) return *done;

  return guarded([&] {
    stopwatch total;
    if (!pfm.empty()) pfm = output_file(pfm).string();
    loaded_scene ls = load_scene_argument(po.scene);
    scene& sc = ls.sc;
    po.apply_to(sc.settings);
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

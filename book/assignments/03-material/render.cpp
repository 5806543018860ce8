// Assignment 03: the Cornell box with two spheres of the student's Oren–Nayar material, Lambert
// (sigma = 0, left) and rough (sigma = 1, right), path-traced with MIS, as a PNG (the target
// image is this program built against solution/: `assignment-03-material-render --out target.png`).
#include "oren_nayar.hpp"

#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/scene/cornell.hpp>

#include <cstdio>
#include <memory>

int main(int argc, char** argv) {
  using namespace zraka;
  int size = 128, spp = 64;
  double sigma = 1.0;
  std::uint64_t seed = 1;
  std::string out = "oren_nayar.png";
  zraka::cli_app app{"Assignment 03: two Oren-Nayar spheres (sigma 0 and --sigma) in the Cornell box, as a PNG"};
  app.add_option("--size", size, "width and height of the image in pixels");
  app.add_option("--spp", spp, "samples per pixel");
  app.add_option("--sigma", sigma, "roughness of the right sphere, radians");
  app.add_option("--seed", seed, "random seed");
  app.add_option("--out", out, "output file (.png, .ppm or .pfm)");
  if (const auto done = parse_command_line(app, argc, argv)) return *done;
  return guarded([&] {
    const stopwatch clock;
    image::check_size(size, size);
    if (!(sigma >= 0) || !std::isfinite(sigma)) throw error("--sigma must be finite and not negative");
    // The "spheres" box, its mirror and glass balls turned into the new material.
    scene sc = cornell_box<double>(cornell_variant::spheres);
    sc.materials[std::size_t(sc.spheres[0].material)] =
        material::custom(std::make_shared<course::oren_nayar>(vec3(0.8), 0.0));
    sc.materials[std::size_t(sc.spheres[1].material)] =
        material::custom(std::make_shared<course::oren_nayar>(vec3(0.8), sigma));
    path_options o;
    o.method = integrator::mis;
    const path_tracer tracer(sc, o);
    const auto cam = sc.prepared_camera();
    image img(size, size);
    const render_stats st = render(img, spp, seed, [&](sample_context& c) {
      const vec2 u = c.random.uniform2();
      return tracer(cam.generate((c.x + u.x) / size, (c.y + u.y) / size), c.random, c.rays);
    });
    write_image(img, out);
    std::printf("wrote %s (%dx%d, %d spp): Oren-Nayar sigma 0 (left) and %g (right), rho 0.8\n",
                out.c_str(), size, size, spp, sigma);
    std::printf("summary: %.3f s, %llu rays\n", clock.seconds(), (unsigned long long)st.rays);
    return 0;
  });
}

// Assignment 01: draw the cylinder shaded by its normal and write a PNG (the target image is
// this program built against solution/: `assignment-01-cylinder-render --out target.png`).
#include "render.hpp"

#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_io.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  int width = 160, height = 120;
  std::string out = "cylinder.png";
  zraka::cli_app app{"Assignment 01: ray-cast a cylinder shaded by its normal, write a PNG"};
  app.add_option("--width", width, "image width in pixels");
  app.add_option("--height", height, "image height in pixels");
  app.add_option("--out", out, "output file (.png, .ppm or .pfm)");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;
  return zraka::guarded([&] {
    const zraka::stopwatch clock;
    zraka::image::check_size(width, height);
    long hits = 0;
    const zraka::image img = course::render_normals(course::demo_cylinder(), width, height, hits);
    zraka::write_image(img, out);
    std::printf("wrote %s (%dx%d): %ld of %d pixels hit the cylinder\n", out.c_str(), width,
                height, hits, width * height);
    std::printf("summary: %.3f s, cylinder covers %.1f%% of the image\n", clock.seconds(),
                100.0 * double(hits) / (double(width) * height));
    return 0;
  });
}

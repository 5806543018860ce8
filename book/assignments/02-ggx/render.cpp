// Assignment 02: the GGX lobe from above, D(h) (left) against a histogram of sample() (right),
// as a PNG (the target image is this program built against solution/:
// `assignment-02-ggx-render --out target.png`).
#include "render.hpp"

#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_io.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  int size = 100;
  long samples = 400000;
  double alpha = 0.3;
  std::uint64_t seed = 1;
  std::string out = "ggx.png";
  zraka::cli_app app{"Assignment 02: the GGX lobe, D(h) against a histogram of its samples, as a PNG"};
  app.add_option("--size", size, "height of the image (each half is size x size)");
  app.add_option("--samples", samples, "number of samples in the histogram");
  app.add_option("--alpha", alpha, "roughness");
  app.add_option("--seed", seed, "random seed");
  app.add_option("--out", out, "output file (.png, .ppm or .pfm)");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;
  return zraka::guarded([&] {
    const zraka::stopwatch clock;
    zraka::image::check_size(2LL * size, size);
    if (!(samples > 0)) throw zraka::error("--samples must be positive");
    if (!(alpha > 0 && alpha <= 1)) throw zraka::error("--alpha must be in (0, 1]");
    const zraka::image img = course::render_lobe(course::ggx{alpha}, size, samples, seed);
    zraka::write_image(img, out);
    std::printf("wrote %s (%dx%d): alpha %g, %ld samples\n", out.c_str(), 2 * size, size, alpha, samples);
    std::printf("summary: %.3f s\n", clock.seconds());
    return 0;
  });
}

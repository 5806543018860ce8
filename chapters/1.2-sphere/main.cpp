// Chapter 1.2 — the sphere. Ray-cast one sphere: every pixel sends a ray, and the pixel is
// shaded where the ray hits (by the normal, so the shape reads) and white where it misses.
// Writes the image as PPM (the thesis's text pixel matrix) and PNG, and checks every hit point
// lies on the sphere.
#include <zraka/camera.hpp>
#include <zraka/error.hpp>
#include <zraka/image_io.hpp>
#include <zraka/sphere.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  int width = 320, height = 240;
  double radius = 1.0;
  std::string out = "sphere";
  CLI::App app{"Chapter 1.2: ray-cast a sphere, write <out>.ppm and <out>.png"};
  app.add_option("--width", width, "image width in pixels");
  app.add_option("--height", height, "image height in pixels");
  app.add_option("--radius", radius, "sphere radius (the camera is 4 units away)");
  app.add_option("--out", out, "output name without extension");
  CLI11_PARSE(app, argc, argv);

  return zraka::guarded([&] {
    using namespace zraka;
    if (!(radius > 0)) throw error("--radius must be positive, got " + std::to_string(radius));
    image img(width, height);

    // [listing cast]
    const sphere ball{{0, 0, 0}, radius};
    camera cam_settings;
    cam_settings.position = {0, 0, 4};
    cam_settings.look_at = {0, 0, 0};
    cam_settings.aspect = double(width) / height;
    const auto cam = cam_settings.prepare();

    long hits = 0;
    double worst_off_surface = 0;  // | ||p - c|| - r | over all hit points
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const ray r = cam.generate((x + 0.5) / width, (y + 0.5) / height);
        hit h;
        if (intersect(ball, r, 0.0, infinity<double>, h)) {
          ++hits;
          worst_off_surface = std::max(worst_off_surface,
                                       std::abs(glm::length(h.p - ball.center) - radius));
          img.at(x, y) = rgb(0.5f * (vec3f(h.normal) + 1.0f));  // normal -> colour
        } else {
          img.at(x, y) = rgb(1.0f);
        }
      }
    // [end]

    write_ppm(img, out + ".ppm");
    write_png(img, out + ".png");
    std::printf("pixels hit: %ld of %d (%.1f%%)\n", hits, width * height,
                100.0 * hits / (double(width) * height));
    std::printf("worst distance of a hit point from the sphere: %.3g (radius %g)\n",
                worst_off_surface, radius);
    std::printf("wrote %s.ppm and %s.png\n", out.c_str(), out.c_str());
    return 0;
  });
}

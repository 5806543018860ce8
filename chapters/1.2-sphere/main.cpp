// Chapter 1.2 — the sphere. Ray-cast one sphere: every pixel sends a ray, and the pixel is
// shaded where the ray hits (by the normal, so the shape reads) and white where it misses.
// Writes the image (--out: .ppm is the thesis's text pixel matrix, or .png), checks every hit point
// lies on the sphere, and compares the fraction of pixels hit with the fraction the sphere's
// projected disc covers, computed in closed form.
#include <zraka/cameras/camera.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/image/image_io.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>

namespace {

// [listing disc-fraction]
// Area of the part of a disc of radius R (centred at 0) inside the rectangle [-W,W] x [-H,H],
// divided by the rectangle's area. By symmetry it is 4 times the quarter in x, y >= 0:
// the integral over x in [0, min(W,R)] of min(H, sqrt(R^2 - x^2)).
double disc_fraction(double R, double W, double H) {
  const auto F = [R](double x) {  // antiderivative of sqrt(R^2 - x^2)
    return 0.5 * (x * std::sqrt(std::max(0.0, R * R - x * x)) + R * R * std::asin(std::min(1.0, x / R)));
  };
  const double x_end = std::min(W, R);
  const double x_flat = R > H ? std::min(std::sqrt(R * R - H * H), x_end) : 0.0;  // min is H there
  return (H * x_flat + F(x_end) - F(x_flat)) / (W * H);
}
// [end]

}  // namespace

int main(int argc, char** argv) {
  zraka::program_options opt{"Chapter 1.2: ray-cast a sphere", zraka::take::size | zraka::take::out};
  opt.width = 320, opt.height = 240, opt.out = "sphere.png";
  double radius = 1.0;
  opt.app.add_option("--radius", radius, "sphere radius (the camera is 4 units away)");
  if (const auto done = opt.parse(argc, argv)) return *done;
  const int width = opt.width, height = opt.height;

  return zraka::guarded([&] {
    using namespace zraka;
    const stopwatch clock;
    if (!(radius > 0) || !std::isfinite(radius))
      throw error("--radius must be positive, got " + std::to_string(radius));
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

    // The expected fraction. Seen from distance d, the sphere fills a cone of half-angle
    // alpha = asin(r/d); on an image plane at distance 1 that is a disc of radius tan(alpha),
    // and the image is the rectangle of half-sizes aspect * tan(vfov/2) by tan(vfov/2).
    // [listing expected]
    const double d = glm::length(cam_settings.position - ball.center);
    const double half_h = std::tan(cam_settings.vfov_degrees * pi<double> / 360);
    const double half_w = cam_settings.aspect * half_h;
    const double disc_r = radius < d ? radius / std::sqrt(d * d - radius * radius) : infinity<double>;
    const double expected = radius < d ? disc_fraction(disc_r, half_w, half_h) : 1.0;
    // [end]
    const double measured = double(hits) / (double(width) * height);
    // Pixel-centre sampling is exact except in pixels the silhouette crosses; a circle of
    // radius R px crosses at most 8 R + 12 of them (4 monotone arcs, R + 1 lines each way).
    const double disc_px = disc_r / (2 * half_h) * height;  // infinite with the camera inside
    const double bound = std::min(1.0, (8 * std::min(disc_px, double(width + height)) + 12) /
                                           (double(width) * height));

    if (std::abs(measured - expected) > bound)
      throw error("the measured fraction is outside its bound: a bug in the camera or the sphere");
    write_image(img, opt.out);
    std::printf("pixels hit: %ld of %d (%.1f%%)\n", hits, width * height, 100 * measured);
    std::printf("expected from the projected disc (radius %.4g px): %.2f%%; difference %.3f%% "
                "(at most %.2f%%: pixels the silhouette crosses)\n",
                disc_px, 100 * expected, 100 * (measured - expected), 100 * bound);
    std::printf("worst distance of a hit point from the sphere: %.3g (radius %g)\n",
                worst_off_surface, radius);
    std::printf("wrote %s\n", opt.out.c_str());
    std::printf("summary: %dx%d rays in %.3f s, %.2f%% hit (expected %.2f%%), hit points within "
                "%.3g of the sphere\n", width, height, clock.seconds(), 100 * measured,
                100 * expected, worst_off_surface);
    return 0;
  });
}

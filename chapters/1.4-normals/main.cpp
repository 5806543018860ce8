// Chapter 1.4 — normals. Loads the Utah teapot's 32 Bezier patches, compares the analytic patch
// normals with finite-difference ones, shows what the degenerate normal guard does at the lid
// knob and the bottom centre, tessellates the patches into triangles with per-vertex patch
// normals, and ray-casts the mesh shaded by its normals (colour = 0.5 (n + 1)) on white.
// Each patch gets a bounding box, and a ray tests a patch's triangles only when it hits the box:
// a one-level preview of the BVH of book 5.2.
#include <zraka/cameras/camera.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/aabb.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/io/bpt.hpp>

#include <zraka/app/program_options.hpp>

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

using namespace zraka;

namespace {
double angle(const vec3& a, const vec3& b) {
  return 2 * std::atan2(glm::length(a - b), glm::length(a + b));  // accurate for small angles
}
// The normal from central differences of the patch's points (h ~ cbrt(eps)); zero if the
// differences are parallel (at a collapsed row).
vec3 finite_difference_normal(const bezier_patch& p, double u, double v) {
  const double h = 1e-5;
  const vec3 du = (evaluate(p, u + h, v) - evaluate(p, u - h, v)) / (2 * h);
  const vec3 dv = (evaluate(p, u, v + h) - evaluate(p, u, v - h)) / (2 * h);
  return normalize_or_zero(glm::cross(du, dv));
}
}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.4: teapot normals: analytic vs finite differences, ray-cast by normal", take::size | take::out};
  cli.width = 400, cli.height = 300, cli.out = "normals.png";
  int divs = 8, aa = 3;
  cli.app.add_option("--divs", divs, "grid cells per patch side (2 divs^2 triangles per patch)");
  cli.app.add_option("--aa", aa, "aa x aa rays in pixels at edges, on a regular grid (anti-aliasing)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height;
  const std::string& out = cli.out;

  return guarded([&] {
    stopwatch total;
    if (divs < 1 || divs > 256)
      throw error("--divs must be in 1..256, got " + std::to_string(divs));
    if (aa < 1 || aa > 16) throw error("--aa must be in 1..16, got " + std::to_string(aa));
    image img(width, height, rgb(1));  // white background; checks the size first

    const auto set = load_bpt(resource_path("scenes/teapot.bpt"));
    const auto patches = set.all_patches();
    std::printf("teapot: %zu patches, %zu control points\n", patches.size(), set.vertices.size());

    // 1. Analytic normals (fast derivative scheme) against finite differences, on a 21 x 21
    // grid per patch. At the 8 collapsed rows both are 0/0; they are measured separately below.
    double worst = 0;
    int worst_patch = 0, compared = 0;
    for (std::size_t k = 0; k < patches.size(); ++k)
      for (int j = 0; j <= 20; ++j)
        for (int i = 0; i <= 20; ++i) {
          const double u = i / 20.0, v = j / 20.0;
          const vec3 fd = finite_difference_normal(patches[k], u, v);
          if (fd == vec3(0)) continue;
          ++compared;
          const double a = angle(patch_normal(patches[k], u, v), fd);
          if (a > worst) worst = a, worst_patch = int(k) + 1;
        }
    std::printf(
        "worst angle, analytic vs finite-difference normal: %.3g rad (patch %d; %d points)\n",
        worst, worst_patch, compared);

    // 2. The degenerate rows: the guarded normal at v = 0 against the plain formula just inside.
    double worst_pole = 0, worst_length = 0;
    int nan_count = 0;
    for (const int k : {21, 22, 23, 24, 29, 30, 31, 32})
      for (int i = 0; i <= 20; ++i) {
        const auto& p = patches[std::size_t(k - 1)];
        const vec3 n = patch_normal(p, i / 20.0, 0.0);
        nan_count += !is_finite(n);
        worst_length = std::max(worst_length, std::abs(glm::length(n) - 1));
        const auto d = differentiate(p, i / 20.0, 1e-4);
        worst_pole = std::max(worst_pole, angle(n, glm::normalize(glm::cross(d.du, d.dv))));
      }
    std::printf(
        "collapsed rows (lid knob, bottom centre): %d NaN normals, worst | |n| - 1 | = "
        "%.2g, worst angle to the normal at v = 1e-4: %.3g rad\n",
        nan_count, worst_length, worst_pole);

    // 3. Tessellate: divs x divs cells per patch, two triangles per cell.
    stopwatch clock;
    const mesh m = tessellate(patches, divs);
    std::size_t zero_area = 0;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) zero_area += m.triangle(i).area() == 0;
    std::printf(
        "tessellated with divs = %d: %zu triangles (32 * %d^2 * 2 = %d; %zu of zero area, "
        "kept) in %.3f s\n",
        divs, m.triangle_count(), divs, 32 * divs * divs * 2, zero_area, clock.seconds());

    // [listing patch-boxes]
    // 4. One box per patch. A ray visits the boxes it enters, nearest entry first, and tests a
    // patch's triangles only if its box starts before the nearest hit found so far.
    const std::size_t per_patch = triangles_per_patch(divs);
    std::vector<aabb> boxes;
    for (std::size_t k = 0; k < patches.size(); ++k)
      boxes.push_back(m.bounds(k * per_patch, (k + 1) * per_patch));

    camera settings;
    settings.position = {6.5, -8.0, 5.0};  // a three-quarter view from the spout's side, above
    settings.look_at = {0.2, 0.0, 1.35};
    settings.up = {0, 0, 1};  // the teapot is z-up
    settings.vfov_degrees = 27;
    settings.aspect = double(width) / height;
    const auto cam = settings.prepare();

    clock.restart();
    long long triangle_tests = 0, rays = 0, hits = 0;
    std::vector<std::pair<double, std::size_t>> entered;  // (t where the ray enters, patch)
    auto trace = [&](const ray& r) -> rgb {
      ++rays;
      const box_ray_t<double> br(r);
      entered.clear();
      for (std::size_t k = 0; k < boxes.size(); ++k)
        if (double t0; intersect(boxes[k], br, 0.0, infinity<double>, &t0))
          entered.push_back({t0, k});
      std::sort(entered.begin(), entered.end());
      hit h;
      mesh_shading_t<double> shading;
      double t_max = infinity<double>;
      bool found = false;
      for (const auto& [t0, k] : entered) {
        if (t0 > t_max) break;  // this box, and all after it, start beyond the nearest hit
        triangle_tests += static_cast<long long>(per_patch);
        if (intersect(m, k * per_patch, (k + 1) * per_patch, r, 0.0, t_max, h, shading)) {
          found = true;
          t_max = h.t;
        }
      }
      if (!found) return rgb(1);  // white background
      ++hits;
      const vec3 n = h.front_face ? shading.normal : -shading.normal;  // the side we see
      return rgb(0.5f * (vec3f(n) + 1.0f));
    };
    // [end]
    // One ray through each pixel's centre; then aa x aa rays only where a pixel differs from a
    // neighbour (the silhouette and sharp creases), since elsewhere they would all agree.
    image centre(width, height);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        centre.at(x, y) = trace(cam.generate((x + 0.5) / width, (y + 0.5) / height));
    long long refined = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        float contrast = 0;
        for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, height - 1); ++ny)
          for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, width - 1); ++nx)
            contrast =
                std::max(contrast, max_component(glm::abs(centre.at(nx, ny) - centre.at(x, y))));
        if (aa == 1 || contrast < 0.05f) {  // 0.05: below that, edges no longer look stepped
          img.at(x, y) = centre.at(x, y);
          continue;
        }
        ++refined;
        rgb sum(0);
        for (int sy = 0; sy < aa; ++sy)
          for (int sx = 0; sx < aa; ++sx)
            sum +=
                trace(cam.generate((x + (sx + 0.5) / aa) / width, (y + (sy + 0.5) / aa) / height));
        img.at(x, y) = sum / float(aa * aa);
      }
    const double cast_seconds = clock.seconds();
    const double brute = double(m.triangle_count()) * double(rays);
    std::printf(
        "ray cast %dx%d (%lld edge pixels with %d rays): %lld of %lld rays hit; %.1f triangle "
        "tests per ray (brute force %zu, %.1fx fewer) in %.2f s\n",
        width, height, refined, aa * aa, hits, rays, double(triangle_tests) / double(rays),
        m.triangle_count(), brute / double(std::max(triangle_tests, 1LL)), cast_seconds);

    write_image(img, out);
    std::printf("wrote %s\n", out.c_str());
    std::printf(
        "done in %.2f s: %zu triangles, worst normal angle vs finite differences %.2g rad, "
        "%d NaN normals at the poles\n",
        total.seconds(), m.triangle_count(), worst, nan_count);
    return 0;
  });
}

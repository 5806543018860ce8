// Chapter 1.5 — ray-object intersections. Renders a floor (a plane), a few triangles and spheres
// with N.L shading from one directional light (or, with --mask, the black-on-white silhouette of
// the thesis's section 2.1 "shader"), then compares the three triangle methods of triangle.hpp
// on random rays: how often they agree, how many rays slip through the shared edges and vertices
// of a triangle fan and a grid ("cracks"), and how long one test takes (compare.cpp).
#include <zraka/cameras/camera.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/plane.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/geometry/triangle.hpp>
#include <zraka/image/image_io.hpp>

#include <zraka/app/program_options.hpp>

#include "compare.hpp"

#include <array>
#include <cstdio>
#include <filesystem>
#include <vector>

using namespace zraka;

namespace {

// The scene: one floor, a pyramid of four triangles, a standing triangle, three spheres.
struct scene {
  plane floor = plane::from_point_normal({0, -1, 0}, {0, 1, 0});
  std::vector<triangle> triangles;
  std::vector<sphere> spheres = {{{1.3, -0.4, 0.2}, 0.6}, {{0.1, -0.65, 1.3}, 0.35},
                                 {{0.3, 0.0, -1.6}, 1.0}};
  scene() {
    const vec3 apex{-1.4, 0.3, 0.3};
    const std::array<vec3, 4> base = {vec3{-2.1, -1, 1.0}, vec3{-0.7, -1, 1.0},
                                      vec3{-0.7, -1, -0.4}, vec3{-2.1, -1, -0.4}};
    for (int k = 0; k < 4; ++k) triangles.push_back({base[k], base[(k + 1) % 4], apex});
    triangles.push_back({{-2.6, -1, -2.5}, {-0.6, -1, -2.8}, {-1.7, 1.4, -2.6}});
  }
};

enum class kind { none, floor, triangle, sphere };

// [listing nearest]
// The nearest hit over all objects: each test only looks in (t_min, t), so t shrinks as
// nearer objects are found (the loop of the thesis's Listing 2.2 returned the first one hit).
kind trace(const scene& s, const ray& r, triangle_method m, hit& h, bool with_floor) {
  kind found = kind::none;
  double t = infinity<double>;
  if (with_floor && intersect(s.floor, r, 0.0, t, h)) found = kind::floor, t = h.t;
  for (const triangle& tri : s.triangles)
    if (intersect(tri, r, 0.0, t, h, m)) found = kind::triangle, t = h.t;
  for (const sphere& sp : s.spheres)
    if (intersect(sp, r, 0.0, t, h)) found = kind::sphere, t = h.t;
  return found;
}
// [end]

// [listing shade]
rgb shade(kind k, const hit& h, const vec3& to_light) {
  rgb albedo(0.8f, 0.5f, 0.3f);                       // triangles
  if (k == kind::sphere) albedo = rgb(0.3f, 0.5f, 0.8f);
  if (k == kind::floor)                               // a checkerboard from the plane's uv
    albedo = (int(std::floor(h.uv.x)) + int(std::floor(h.uv.y))) % 2 ? rgb(0.75f) : rgb(0.35f);
  const double n_dot_l = std::max(0.0, glm::dot(h.facing_normal(), to_light));  // clamped (A6)
  return albedo * float(0.15 + 0.85 * n_dot_l);
}
// [end]

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.5: ray-object intersections; renders a scene and compares the three "
               "ray-triangle methods", take::size | take::seed | take::out};
  cli.width = 320, cli.height = 240, cli.out = "intersections.png";
  int rays = 200000;
  std::string method_name = "watertight";
  bool mask = false;
  cli.app.add_option("--method", method_name, "triangle method for the image: edge, mt or watertight");
  cli.app.add_option("--rays", rays, "random rays per method in the comparison");
  cli.app.add_flag("--mask", mask, "black-on-white silhouettes of the objects (thesis 2.1), no floor");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height;
  const std::uint64_t seed = cli.seed;
  const std::string& out = cli.out;

  return guarded([&] {
    const triangle_method method = parse_enum<triangle_method>(method_name, "--method");
    const std::string ext = std::filesystem::path(out).extension().string();
    if (ext != ".png" && ext != ".ppm" && ext != ".pfm" && ext != ".exr")
      throw error("unknown image type '" + ext + "' for " + out + " (use .png, .ppm, .pfm or .exr)");
    if (rays < 1 || rays > 10000000) throw error("--rays must be in 1..10000000");
    stopwatch total;
    image img(width, height);

    const scene s;
    camera cam_settings;
    cam_settings.position = {0.4, 1.6, 6};
    cam_settings.look_at = {-0.3, -0.3, 0};
    cam_settings.aspect = double(width) / height;
    const auto cam = cam_settings.prepare();
    const vec3 to_light = glm::normalize(vec3(-0.6, 1.0, 0.8));

    std::array<long, 4> pixels{};
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const ray r = cam.generate((x + 0.5) / width, (y + 0.5) / height);
        hit h;
        const kind k = trace(s, r, method, h, !mask);
        ++pixels[int(k)];
        if (mask) img.at(x, y) = k == kind::none ? rgb(1.0f) : rgb(0.0f);  // the 2.1 "shader"
        else img.at(x, y) = k == kind::none ? rgb(0.55f, 0.7f, 0.9f) : shade(k, h, to_light);
      }
    write_image(img, out);
    std::printf("image %dx%d, triangles by %s%s: floor %ld, triangles %ld, spheres %ld, sky %ld "
                "pixels\n",
                width, height, method_name.c_str(), mask ? " (mask)" : "", pixels[1], pixels[2],
                pixels[3], pixels[0]);
    std::printf("wrote %s\n\n", out.c_str());

    // The comparison of the three methods (compare.cpp), in float (where they differ most) and double.
    const method_comparison c = compare_triangle_methods(seed, rays);
    std::printf("\nsummary: %.2f s; agreement edge/mt/watertight %.4f/%.4f/%.4f %%, cracks "
                "%ld/%ld/%ld of %ld rays, ns per test (float) %.1f/%.1f/%.1f\n",
                total.seconds(), c.agree[0], c.agree[1], c.agree[2], c.cracks[0], c.cracks[1], c.cracks[2],
                c.crack_rays, c.ns_float[0], c.ns_float[1], c.ns_float[2]);
    return 0;
  });
}

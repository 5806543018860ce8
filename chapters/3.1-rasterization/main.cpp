// Chapter 3.1 — rasterization and ray casting, the two loop orders. The same triangles are drawn
// twice: by a tiny software rasterizer (objects outer: each triangle asks which pixels it
// covers, with edge functions, the top-left fill rule and a depth buffer) and by a ray caster
// (pixels outer: each pixel's ray asks which triangle it hits first, with the watertight test
// of book 1.5). The view is orthographic along -z, one unit per pixel, y down, so both see the
// same 2-D triangles; vertices are snapped to 1/256 pixel as GPUs do, which makes every edge
// function exact. The program counts the pixels where the two images differ and checks that
// each such pixel has its centre exactly on a triangle edge, where the two methods use
// different tie rules, then prints both times.
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/triangle.hpp>
#include <zraka/image/image_io.hpp>

#include <zraka/app/program_options.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <limits>
#include <utility>
#include <vector>

namespace {

using zraka::rgb;
using zraka::vec3;

struct colored_triangle {
  vec3 a, b, c;  // x, y in pixels (y down), z towards the viewer: larger z is nearer
  rgb colour;
};

double snap(double v) { return std::round(v * 256.0) / 256.0; }  // 1/256-pixel grid

// [listing edge-function]
// E(a, b, p): twice the signed area of the triangle (a, b, p). It is zero on the line through
// a and b and has one sign on each side, so p is inside (a, b, c) when E(b, c, p), E(c, a, p)
// and E(a, b, p) all have the sign of E(a, b, c), the triangle's own doubled area.
// Exact here: snapped coordinates below 2^12 pixels have at most 20 significant bits.
double edge(const vec3& a, const vec3& b, double px, double py) {
  return (b.x - a.x) * (py - a.y) - (b.y - a.y) * (px - a.x);
}

// The top-left rule decides pixels whose centre lies exactly on an edge (E = 0): they belong to
// the triangle when the edge is a left edge (the inside is towards +x) or a top edge
// (horizontal, the inside is towards +y, down). A shared edge is left for one of its two
// triangles and right for the other, so its pixels are drawn exactly once.
bool inside(double e, const vec3& a, const vec3& b) {
  if (e != 0) return e > 0;
  const double dx_inside = -(b.y - a.y), dy_inside = b.x - a.x;  // the gradient of E
  return dx_inside > 0 || (dx_inside == 0 && dy_inside > 0);
}
// [end]

// [listing rasterize]
// Objects outer: every triangle visits the pixels of its bounding box.
void rasterize(const std::vector<colored_triangle>& tris, zraka::image& img,
               std::vector<int>& writes) {
  std::vector<double> depth(img.pixels.size(), -std::numeric_limits<double>::infinity());
  for (const auto& t : tris) {
    vec3 a = t.a, b = t.b, c = t.c;
    double area = edge(a, b, c.x, c.y);
    if (area == 0) continue;  // seen edge-on: covers nothing
    if (area < 0) {           // wind every triangle the same way, so inside is E > 0
      std::swap(b, c);
      area = -area;
    }
    const int x0 = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(img.width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(img.height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5, py = y + 0.5;  // the pixel centre
        const double wa = edge(b, c, px, py), wb = edge(c, a, px, py), wc = edge(a, b, px, py);
        if (!inside(wa, b, c) || !inside(wb, c, a) || !inside(wc, a, b)) continue;
        const std::size_t i = std::size_t(y) * std::size_t(img.width) + std::size_t(x);
        ++writes[i];
        const double z = (wa * a.z + wb * b.z + wc * c.z) / area;  // barycentric depth
        if (z > depth[i]) {  // nearer than what the pixel holds
          depth[i] = z;
          img.pixels[i] = t.colour;
        }
      }
  }
}
// [end]

// [listing ray-cast]
// Pixels outer: every pixel's ray tests every triangle and keeps the nearest hit.
void ray_cast(const std::vector<colored_triangle>& tris, zraka::image& img, rgb background) {
  const double eye_z = 1e4;  // the rays start in front of every triangle
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const zraka::ray r({x + 0.5, y + 0.5, eye_z}, {0, 0, -1});
      double nearest = zraka::infinity<double>;
      rgb colour = background;
      for (const auto& t : tris) {
        zraka::hit h;
        if (zraka::intersect(zraka::triangle{t.a, t.b, t.c}, r, 0.0, nearest, h)) {
          nearest = h.t;
          colour = t.colour;
        }
      }
      img.at(x, y) = colour;
    }
}
// [end]

// How many triangles have the centre of pixel (x, y) exactly on one of their edges?
int edge_owners(const std::vector<colored_triangle>& tris, int x, int y) {
  const double px = x + 0.5, py = y + 0.5;
  int n = 0;
  for (const auto& t : tris) {
    const double ea = edge(t.b, t.c, px, py), eb = edge(t.c, t.a, px, py),
                 ec = edge(t.a, t.b, px, py);
    const bool in = (ea >= 0 && eb >= 0 && ec >= 0) || (ea <= 0 && eb <= 0 && ec <= 0);
    n += in && (ea == 0 || eb == 0 || ec == 0);
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  zraka::program_options cli{"Chapter 3.1: the same triangles rasterized and ray cast; the images compared",
                            zraka::take::size | zraka::take::seed | zraka::take::out};
  cli.width = 320, cli.height = 240, cli.out = "raster.png";
  int count = 60;
  cli.app.add_option("--triangles", count, "number of random triangles (besides a split square)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height;
  const std::uint64_t seed = cli.seed;
  // --out x.png names the three images x-raster.png, x-raycast.png and x-diff.png.
  const std::string raster_file = cli.sibling("-raster"), cast_file = cli.sibling("-raycast"), diff_file = cli.sibling("-diff");

  return zraka::guarded([&] {
    using namespace zraka;
    const stopwatch clock;
    if (width < 1 || height < 1 || width > 4096 || height > 4096)
      throw error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                  " is out of range (1..4096 each side: the exact edge functions need < 2^12)");
    if (count < 0 || count > 100000)
      throw error("--triangles must be in 0..100000, got " + std::to_string(count));

    // A square split along its diagonal, corners on pixel centres: its edges pass exactly through
    // pixel centres, where the tie rules matter. Then random triangles, each at its own depth.
    std::vector<colored_triangle> tris;
    const double L = std::floor(width * 0.1) + 0.5, R = std::floor(width * 0.45) + 0.5;
    const double T = std::floor(height * 0.1) + 0.5, B = std::floor(height * 0.5) + 0.5;
    const rgb white(0.9f), grey(0.6f);
    tris.push_back({{L, T, 0.5}, {R, B, 0.5}, {L, B, 0.5}, grey});
    tris.push_back({{L, T, 0.5}, {R, T, 0.5}, {R, B, 0.5}, white});
    for (int k = 0; k < count; ++k) {
      rng g(seed, std::uint32_t(k));
      const double cx = g.uniform() * width, cy = g.uniform() * height;
      const double size = (0.03 + 0.1 * g.uniform()) * std::min(width, height);
      const double z = 1.0 + k;  // distinct depths: no ties but on exact edges
      vec3 v[3];  // around the centre, at roughly a third of a turn from each other
      const double turn = 2 * pi<double> * g.uniform();
      for (int i = 0; i < 3; ++i) {
        const double phi = turn + 2 * pi<double> * (i + 0.3 * (g.uniform() - 0.5)) / 3;
        v[i] = {snap(cx + size * std::cos(phi)), snap(cy + size * std::sin(phi)), z};
      }
      const rgb colour(0.2f + 0.8f * g.uniform_float(), 0.2f + 0.8f * g.uniform_float(),
                       0.2f + 0.8f * g.uniform_float());
      tris.push_back({v[0], v[1], v[2], colour});
    }

    const rgb background(0.05f);
    image raster(width, height, background), cast(width, height, background);
    std::vector<int> writes(raster.pixels.size(), 0);
    stopwatch t_raster;
    rasterize(tris, raster, writes);
    const double raster_seconds = t_raster.seconds();
    stopwatch t_cast;
    ray_cast(tris, cast, background);
    const double cast_seconds = t_cast.seconds();

    // The split square alone: the top-left rule draws each of its pixels exactly once.
    image square(width, height, background);
    std::vector<int> square_writes(square.pixels.size(), 0);
    rasterize({tris[0], tris[1]}, square, square_writes);
    long square_pixels = 0, square_twice = 0;
    for (int w : square_writes) {
      square_pixels += w > 0;
      square_twice += w > 1;
    }

    long differ = 0, differ_on_edge = 0, differ_shared = 0;
    image diff(width, height);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const bool d = raster.at(x, y) != cast.at(x, y);
        diff.at(x, y) = d ? rgb(1, 0, 1) : raster.at(x, y) * 0.3f;
        if (!d) continue;
        ++differ;
        const int owners = edge_owners(tris, x, y);
        differ_on_edge += owners > 0;
        differ_shared += owners > 1;
      }

    write_image(raster, raster_file);
    write_image(cast, cast_file);
    write_image(diff, diff_file);
    std::printf("triangles: %zu (a split square and %d random), image %dx%d\n", tris.size(), count,
                width, height);
    std::printf("split square: %ld pixels, %ld drawn twice (expected %ld = %d x %d, 0 twice)\n",
                square_pixels, square_twice, long(R - L) * long(B - T), int(R - L), int(B - T));
    std::printf("pixels that differ: %ld of %d; with the centre exactly on an edge: %ld\n", differ,
                width * height, differ_on_edge);
    std::printf("  on an edge two triangles share: %ld (the ray caster keeps the first triangle "
                "in the list, the rasterizer the one the top-left rule gives the pixel)\n",
                differ_shared);
    std::printf("  on an outer right or bottom edge: %ld (the ray caster's edges are inclusive, "
                "the top-left rule leaves these out)\n", differ_on_edge - differ_shared);
    std::printf("rasterizer (objects outer): %.4f s; ray caster (pixels outer): %.4f s\n",
                raster_seconds, cast_seconds);
    std::printf("wrote %s, %s, %s\n", raster_file.c_str(), cast_file.c_str(), diff_file.c_str());
    if (differ != differ_on_edge)
      throw error(std::to_string(differ - differ_on_edge) +
                  " pixel(s) differ away from any edge: a bug in one of the two loops");
    std::printf("summary: %zu triangles at %dx%d: rasterized in %.4f s, ray cast in %.4f s; %ld "
                "pixels differ, all on exact edges; %.3f s in total\n", tris.size(), width, height,
                raster_seconds, cast_seconds, differ, clock.seconds());
    return 0;
  });
}

// Chapter 5.2 — the BVH. The thesis argues that a bounding volume hierarchy makes a ray cost
// O(log n) instead of O(n). Here we measure it: the teapot tessellated ever finer (about 1k to
// 1M triangles), a BVH built over it (triangle_bvh.hpp), and two ray sets: camera rays and
// incoherent random rays (teapot_rays.hpp). For each size: build time, nodes, bytes per
// triangle, rays per second with the BVH and by brute force (on a subset of rays when testing
// every triangle would be slow; the table marks those), boxes and triangles tested per ray, and a
// check that the BVH's hits equal brute force's. Then the growth exponent of the cost per ray
// against n, a sliver scene where the argument fails (errata C10), and a heat map of boxes tested
// per pixel, --out (bvh-heat.png).
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/io/bpt.hpp>

#include "teapot_rays.hpp"

#include <zraka/app/program_options.hpp>

#include <algorithm>
#include <ctime>
#include <cstdio>
#include <string>
#include <vector>

using namespace zraka;

namespace {

struct settings {
  std::vector<int> divs{4, 8, 16, 32, 64, 128};
  int width = 320, height = 240;    // camera rays, and the heat map
  int random_rays = 16384;
  double brute_tests = 1e7;         // triangle tests brute force may spend per ray set
  int check_rays = 256;             // rays whose BVH hit is compared with brute force
  int heat_divs = 32;
  std::uint64_t seed = 1;
  std::string out = "bvh-heat.png";  // the heat map
  bvh_build_options build = triangle_bvh::default_options();
};

// Processor time of this (single-threaded) program: steadier than wall-clock time on a machine
// that is busy with other work.
double cpu_seconds() { return double(std::clock()) / CLOCKS_PER_SEC; }

struct measurement {
  double bvh_rays_per_s = 0, boxes_per_ray = 0, triangles_per_ray = 0;
  double brute_rays_per_s = 0;
  int brute_rays = 0;  // how many rays brute force traced (all, or a subset)
  int checked = 0, mismatches = 0;
};

// [listing measure]
measurement measure(const triangle_bvh& bvh, const std::vector<rayf>& rays, const settings& s,
                    std::vector<std::uint32_t>* boxes_per_ray = nullptr) {
  measurement m;
  triangle_bvh_hit h;
  double start = cpu_seconds();
  std::size_t hits = 0;  // used, so the loop cannot be optimised away
  for (const rayf& r : rays) hits += bvh.intersect(r, 0.0f, infinity<float>, h);
  m.bvh_rays_per_s = double(rays.size()) / (cpu_seconds() - start);

  bvh_stats total;  // a second pass counts (counting costs a little time, so not timed)
  for (const rayf& r : rays) {
    bvh_stats one;
    bvh.intersect(r, 0.0f, infinity<float>, h, &one);
    total.nodes += one.nodes;
    total.primitives += one.primitives;
    if (boxes_per_ray) boxes_per_ray->push_back(std::uint32_t(one.nodes));
  }
  m.boxes_per_ray = double(total.nodes) / double(rays.size());
  m.triangles_per_ray = double(total.primitives) / double(rays.size());

  // Brute force on an evenly spread subset when all rays would exceed the test budget.
  const double n = double(std::max<std::size_t>(1, bvh.triangle_count()));
  m.brute_rays = int(std::clamp(s.brute_tests / n, 16.0, double(rays.size())));
  const std::size_t stride = rays.size() / std::size_t(m.brute_rays);
  std::vector<triangle_bvh_hit> brute(std::size_t(m.brute_rays));
  start = cpu_seconds();
  for (int k = 0; k < m.brute_rays; ++k)
    hits += bvh.intersect_brute_force(rays[k * stride], 0.0f, infinity<float>, brute[k]);
  m.brute_rays_per_s = m.brute_rays / (cpu_seconds() - start);

  // The same t, triangle and barycentrics, bit for bit.
  for (int k = 0; k < std::min(m.brute_rays, s.check_rays); ++k, ++m.checked) {
    bvh.intersect(rays[k * stride], 0.0f, infinity<float>, h);
    const triangle_bvh_hit& b = brute[k];
    m.mismatches += h.triangle != b.triangle || h.t != b.t || h.u != b.u || h.v != b.v;
  }
  if (hits == std::size_t(-1)) std::printf("\n");
  return m;
}
// [end]

// [listing fit]
// Least-squares slope of y against x: with x = ln n and y = ln(cost per ray) it is the growth
// exponent b of cost ~ n^b (1 for brute force; near 0 for logarithmic growth).
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double k = double(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i], sy += y[i], sxx += x[i] * x[i], sxy += x[i] * y[i];
  }
  const double d = k * sxx - sx * sx;
  return d > 0 ? (k * sxy - sx * sy) / d : 0.0;
}
// [end]

// n long, thin triangles through one point in random directions: every box is nearly the whole
// scene, siblings overlap, and a ray through the middle enters almost all of them (C10).
std::vector<triangle_t<float>> slivers(int n, std::uint64_t seed) {
  std::vector<triangle_t<float>> tris;
  for (int i = 0; i < n; ++i) {
    rng g(seed, std::uint32_t(i), 7);
    auto unit = [&] {
      const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
      const double s = std::sqrt(1 - z * z);
      return vec3(s * std::cos(phi), s * std::sin(phi), z);
    };
    const vec3 u = unit(), w = unit();
    tris.push_back({vec3f(u), vec3f(-u), vec3f(0.01 * w)});
  }
  return tris;
}

// A colour ramp for the heat map: black, blue, red, yellow, white as x goes from 0 to 1.
rgb heat(double x) {
  const rgb stops[] = {{0, 0, 0}, {0.05f, 0.1f, 0.8f}, {0.9f, 0.1f, 0.1f}, {1, 0.9f, 0.1f}, {1, 1, 1}};
  x = std::clamp(x, 0.0, 1.0) * 4;
  const int k = std::min(3, int(x));
  const float f = float(x - k);
  const rgb c = (1 - f) * stops[k] + f * stops[k + 1];
  return c * c;  // the stops are picked by eye in sRGB; roughly linearise
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 5.2: a BVH over the teapot, ~1k to 1M triangles, against brute force", take::size | take::seed | take::out};
  settings s;
  cli.width = s.width, cli.height = s.height, cli.seed = s.seed, cli.out = s.out;
  cli.app.add_option("--divs", s.divs, "teapot tessellation levels (32 * 2 * divs^2 triangles)");
  cli.app.add_option("--rays", s.random_rays, "number of incoherent random rays");
  cli.app.add_option("--brute-tests", s.brute_tests,
                     "triangle tests brute force may spend per ray set (then a subset of rays)");
  cli.app.add_option("--check-rays", s.check_rays, "rays per set whose hits are compared to brute force");
  cli.app.add_option("--heat-divs", s.heat_divs, "the divs of the heat map (must be one of --divs)");
  cli.app.add_option("--leaf", s.build.max_leaf_size, "most triangles per leaf");
  cli.app.add_option("--traversal-cost", s.build.traversal_cost, "SAH cost of a box test (a triangle test = 1)");
  cli.app.add_option("--leaf-block", s.build.leaf_block, "SAH prices a leaf by its blocks of this many triangles");
  cli.app.add_option("--wide-leaf", s.build.wide_leaf_size, "most triangles in a leaf of the wide tree (collapse by cost)");
  cli.app.add_option("--node-cost", s.build.wide_node_cost, "a wide node's cost in leaf blocks (collapse by cost)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  s.width = cli.width, s.height = cli.height, s.seed = cli.seed, s.out = cli.out;

  return guarded([&] {
    stopwatch total;
    if (s.divs.empty()) throw error("--divs needs at least one value");
    for (const int d : s.divs)
      if (d < 1 || d > 256) throw error("--divs must be in 1..256, got " + std::to_string(d));
    if (std::find(s.divs.begin(), s.divs.end(), s.heat_divs) == s.divs.end())
      throw error("--heat-divs " + std::to_string(s.heat_divs) + " is not one of --divs");
    if (s.random_rays < 16) throw error("--rays must be at least 16");
    if (!(s.brute_tests > 0)) throw error("--brute-tests must be positive");
    if (s.check_rays < 0) throw error("--check-rays must not be negative");
    image::check_size(s.width, s.height);
    if (std::size_t(s.width) * s.height < 16) throw error("--width x --height must be at least 16 rays");

    const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
    std::printf("teapot: %zu patches; BVH: SAH with %d bins, leaves of at most %d in blocks of %d, C_trav %g; "
                "%d-wide nodes chosen by cost (leaves of at most %d, a node %g blocks), %s box tests; "
                "q: nodes in half the bytes (trees over %.0f MiB)\n",
                patches.size(), s.build.bins, s.build.max_leaf_size, s.build.leaf_block, s.build.traversal_cost,
                triangle_bvh::width, s.build.wide_leaf_size, s.build.wide_node_cost, to_string(cpu_simd()),
                double(detail::quantize_above_bytes()) / (1 << 20));
    std::printf("rays: camera %dx%d = %d, random %d (origins in the teapot's box grown 20%%)\n\n",
                s.width, s.height, s.width * s.height, s.random_rays);
    std::printf("%5s %9s %8s %8s %6s %5s | %-6s %9s %8s %8s | %9s %6s %9s %7s\n", "divs",
                "triangles", "build s", "nodes", "B/tri", "depth", "rays", "BVH Mr/s", "boxes/r",
                "tris/r", "brute r/s", "of", "speed-up", "agree");

    struct row {
      double n;
      measurement m[2];
    };
    std::vector<row> rows;
    std::vector<std::uint32_t> heat_counts;
    int total_mismatches = 0;
    for (const int divs : s.divs) {
      const mesh m = tessellate(patches, divs);
      const double start = cpu_seconds();
      const triangle_bvh bvh(m, s.build);
      const double build_s = cpu_seconds() - start;
      const std::vector<rayf> sets[2] = {chapter_5_2::camera_rays(m.bounds(), s.width, s.height),
                                         chapter_5_2::random_rays(m.bounds(), s.random_rays, s.seed)};
      row r{double(m.triangle_count()), {}};
      for (int k = 0; k < 2; ++k) {
        const measurement& x = r.m[k] = measure(bvh, sets[k], s, k == 0 && divs == s.heat_divs ? &heat_counts : nullptr);
        total_mismatches += x.mismatches;
        const std::string of = x.brute_rays == int(sets[k].size()) ? "all" : std::to_string(x.brute_rays) + "*";
        std::printf("%5d %9zu %8.3f %8zu %5.1f%c %5d | %-6s %9.3f %8.1f %8.1f | %9.3g %6s %9.0f %3d/%-3d\n",
                    divs, m.triangle_count(), build_s, bvh.node_count(), bvh.bytes_per_triangle(),
                    bvh.quantized() ? 'q' : ' ',
                    bvh.depth(), k == 0 ? "camera" : "random", x.bvh_rays_per_s * 1e-6,
                    x.boxes_per_ray, x.triangles_per_ray, x.brute_rays_per_s, of.c_str(),
                    x.bvh_rays_per_s / x.brute_rays_per_s, x.checked - x.mismatches, x.checked);
      }
      rows.push_back(r);
    }
    std::printf("(* brute force timed on that many evenly spread rays only: its cost per ray is the\n"
                "   same for every ray, n triangle tests, so the rate is an estimate for all)\n\n");

    // Growth exponents over the sizes measured.
    double exponent[2][3] = {};  // [set][boxes, time, brute time]
    if (rows.size() >= 2) {
      std::printf("growth of the cost per ray with n (slope of ln cost against ln n):\n");
      for (int k = 0; k < 2; ++k) {
        std::vector<double> x, log2n, tests, boxes, time, brute;
        for (const row& r : rows) {
          x.push_back(std::log(r.n));
          log2n.push_back(std::log2(r.n));
          tests.push_back(r.m[k].boxes_per_ray + r.m[k].triangles_per_ray);
          boxes.push_back(std::log(r.m[k].boxes_per_ray + r.m[k].triangles_per_ray));
          time.push_back(-std::log(r.m[k].bvh_rays_per_s));
          brute.push_back(-std::log(r.m[k].brute_rays_per_s));
        }
        exponent[k][0] = slope(x, boxes);
        exponent[k][1] = slope(x, time);
        exponent[k][2] = slope(x, brute);
        const double per_doubling = slope(log2n, tests);  // fit of tests = a + b log2 n
        std::printf("  %-6s BVH tests (boxes + triangles) ~ n^%.3f, BVH time ~ n^%.3f, brute force"
                    " time ~ n^%.2f; tests ~ a %+.2f log2 n\n",
                    k == 0 ? "camera" : "random", exponent[k][0], exponent[k][1], exponent[k][2],
                    per_doubling);
      }
    }

    // [listing slivers]
    // Where O(log n) fails (errata C10): n slivers through one point. Rays aimed near it.
    std::printf("\nslivers through one point (every box overlaps every other):\n");
    std::vector<double> sx, sy;
    for (const int n : {256, 1024, 4096}) {
      const triangle_bvh bvh(slivers(n, s.seed), s.build);
      bvh_stats st;
      const int count = 2000;
      for (int i = 0; i < count; ++i) {
        rng g(s.seed, std::uint32_t(i), 9);
        const vec3 o(4 * g.uniform() - 2, 4 * g.uniform() - 2, 3);
        const vec3 aim(0.2 * g.uniform() - 0.1, 0.2 * g.uniform() - 0.1, 0);
        triangle_bvh_hit h;
        bvh.intersect(rayf(vec3f(o), vec3f(aim - o)), 0.0f, infinity<float>, h, &st);
      }
      const double per_ray = double(st.nodes + st.primitives) / count;
      sx.push_back(std::log(double(n)));
      sy.push_back(std::log(per_ray));
      std::printf("  n %5d: %8.1f boxes and %8.1f triangles tested per ray (%.0f%% of n)\n", n,
                  double(st.nodes) / count, double(st.primitives) / count,
                  100.0 * double(st.primitives) / count / n);
    }
    const double sliver_exponent = slope(sx, sy);
    std::printf("  tests per ray ~ n^%.2f: linear, not logarithmic\n", sliver_exponent);
    // [end]

    // The heat map: boxes tested per camera ray; white from the 99.5th percentile up.
    image img(s.width, s.height);
    std::vector<std::uint32_t> sorted = heat_counts;
    std::sort(sorted.begin(), sorted.end());
    const std::uint32_t most = std::max(1u, sorted[sorted.size() * 995 / 1000]);
    for (int y = 0; y < s.height; ++y)
      for (int x = 0; x < s.width; ++x)
        img.at(x, y) = heat(double(heat_counts[std::size_t(y) * s.width + x]) / most);
    write_image(img, s.out);
    std::printf("\nwrote %s: boxes tested per camera ray at divs %d (white: %u or more,"
                " the most: %u)\n", s.out.c_str(), s.heat_divs, most, sorted.back());

    char growth[96] = "growth needs two --divs";
    if (rows.size() >= 2)
      std::snprintf(growth, sizeof growth, "camera cost ~ n^%.3f, random ~ n^%.3f", exponent[0][0],
                    exponent[1][0]);
    std::printf("summary: %.1f s (wall clock; rates above in CPU time); %zu sizes, %.0f to %.0f "
                "triangles; %s, slivers ~ n^%.2f; %d hits differ from brute force\n",
                total.seconds(), rows.size(), rows.front().n, rows.back().n, growth,
                sliver_exponent, total_mismatches);
    return 0;
  });
}

// Chapter 1.5 — ray-object intersections. Renders a floor (a plane), a few triangles and spheres
// with N.L shading from one directional light (or, with --mask, the black-on-white silhouette of
// the thesis's section 2.1 "shader"), then compares the three triangle methods of triangle.hpp
// on random rays: how often they agree, how many rays slip through the shared edges and vertices
// of a triangle fan and a grid ("cracks"), and how long one test takes.
#include <zraka/camera.hpp>
#include <zraka/error.hpp>
#include <zraka/image_io.hpp>
#include <zraka/plane.hpp>
#include <zraka/rng.hpp>
#include <zraka/sphere.hpp>
#include <zraka/stopwatch.hpp>
#include <zraka/triangle.hpp>

#include <zraka/program_options.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
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

// --- comparison of the triangle methods ---------------------------------------------------

constexpr std::array<triangle_method, 3> methods = {
    triangle_method::edge_tests, triangle_method::moller_trumbore, triangle_method::watertight};

template <class T> vec3_t<T> random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(1 - z * z);
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}

template <class T> struct ray_case {
  triangle_t<T> tri;
  ray_t<T> r;
};

// Random triangles in the unit ball, rays from 1 to 10 away aimed at random barycentrics in
// [-0.25, 1.25] (so about a quarter hit).
template <class T> std::vector<ray_case<T>> random_cases(std::uint64_t seed, int n) {
  rng g(seed);
  std::vector<ray_case<T>> cases;
  for (int i = 0; i < n; ++i) {
    const triangle_t<T> tri{random_unit<T>(g), random_unit<T>(g), random_unit<T>(g)};
    const T u = T(-0.25 + 1.5 * g.uniform()), v = T(-0.25 + 1.5 * g.uniform());
    const vec3_t<T> target = (1 - u - v) * tri.a + u * tri.b + v * tri.c;
    const vec3_t<T> o = target + T(1 + 9 * g.uniform()) * random_unit<T>(g);
    cases.push_back({tri, ray_t<T>(o, target - o)});
  }
  return cases;
}

// Agreement with a double-precision watertight reference on the same (float) data: the same
// hit/miss, and on a hit t and the barycentrics within 1e-3 (relative for t).
struct agreement {
  long same = 0, total = 0;
};
agreement agree(const std::vector<ray_case<float>>& cases, triangle_method m) {
  agreement a;
  for (const auto& c : cases) {
    hit_t<float> h;
    hit ref;
    const bool got = intersect(c.tri, c.r, 0.0f, infinity<float>, h, m);
    const triangle tri{vec3(c.tri.a), vec3(c.tri.b), vec3(c.tri.c)};
    const bool want = intersect_watertight(tri, ray(vec3(c.r.origin), vec3(c.r.direction)), 0.0,
                                           infinity<double>, ref);
    bool same = got == want;
    if (same && got)
      same = std::abs(h.t - ref.t) <= 1e-3 * ref.t && std::abs(h.uv.x - ref.uv.x) <= 1e-3 &&
             std::abs(h.uv.y - ref.uv.y) <= 1e-3;
    a.same += same ? 1 : 0;
    ++a.total;
  }
  return a;
}

// A closed fan of n triangles around a raised centre and a grid of quads split in two, all
// vertices exactly representable; rays aimed at every shared vertex and at every 1/8 of every
// shared edge, straight down and from random directions at least 45 degrees steep. A ray that
// misses every triangle has fallen through a crack.
std::vector<trianglef> crack_meshes() {
  std::vector<trianglef> tris;
  const int n = 48;
  std::vector<vec3f> rim;
  for (int k = 0; k < n; ++k) {
    const double th = 2 * pi<double> * k / n;
    rim.push_back(vec3f(1000 + std::round(512 * std::cos(th)) / 256,
                        3000 + std::round(512 * std::sin(th)) / 256, 500));
  }
  for (int k = 0; k < n; ++k) tris.push_back({vec3f(1000, 3000, 500.5f), rim[k], rim[(k + 1) % n]});
  auto vtx = [](int i, int j) {  // a 12 x 12 grid starting at (-7, 5, 2)
    return vec3f(-7 + 0.375f * i, 5 + 0.375f * j, 2 + 0.046875f * ((i * 7 + j * 3) % 5));
  };
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) {
      tris.push_back({vtx(i, j), vtx(i + 1, j), vtx(i + 1, j + 1)});
      tris.push_back({vtx(i, j), vtx(i + 1, j + 1), vtx(i, j + 1)});
    }
  return tris;
}

std::vector<vec3f> shared_points(const std::vector<trianglef>& tris) {
  auto key = [](const vec3f& v) { return std::array<float, 3>{v.x, v.y, v.z}; };
  std::map<std::pair<std::array<float, 3>, std::array<float, 3>>, int> directed;
  for (const auto& t : tris) {
    const std::array<vec3f, 3> v = {t.a, t.b, t.c};
    for (int i = 0; i < 3; ++i) ++directed[{key(v[i]), key(v[(i + 1) % 3])}];
  }
  std::map<std::array<float, 3>, bool> interior;  // vertex -> all its edges shared
  std::vector<vec3f> pts;
  for (const auto& [e, count] : directed) {
    const bool shared = directed.count({e.second, e.first}) > 0;
    interior.try_emplace(e.first, true).first->second &= shared;
    interior.try_emplace(e.second, true).first->second &= shared;
    if (!shared || e.first < e.second) continue;  // each shared edge once
    const vec3f p(e.first[0], e.first[1], e.first[2]), q(e.second[0], e.second[1], e.second[2]);
    for (int s = 1; s < 8; ++s) pts.push_back(p + (float(s) / 8) * (q - p));
  }
  for (const auto& [v, inner] : interior)
    if (inner) pts.push_back(vec3f(v[0], v[1], v[2]));
  return pts;
}

long count_cracks(const std::vector<trianglef>& tris, const std::vector<vec3f>& targets,
                  triangle_method m, std::uint64_t seed, long& rays) {
  rng g(seed);
  long cracks = 0;
  rays = 0;
  for (const vec3f& target : targets)
    for (int k = -1; k < 4; ++k) {
      vec3f d(0, 0, 1);
      if (k >= 0) {
        d = random_unit<float>(g);
        d.z = std::abs(d.z) + 1;
      }
      const vec3f o = target + 4.0f * d;
      const rayf r(o, target - o);
      bool any = false;
      hit_t<float> h;
      for (const auto& tri : tris) any = any || intersect(tri, r, 0.0f, infinity<float>, h, m);
      cracks += any ? 0 : 1;
      ++rays;
    }
  return cracks;
}

// Nanoseconds per intersection test: every case once per round, the best of 3 rounds.
template <class T> double ns_per_test(const std::vector<ray_case<T>>& cases, triangle_method m) {
  double best = infinity<double>;
  long hits = 0;
  for (int round = 0; round < 3; ++round) {
    stopwatch clock;
    for (const auto& c : cases) {
      hit_t<T> h;
      hits += intersect(c.tri, c.r, T(0), infinity<T>, h, m) ? 1 : 0;
    }
    best = std::min(best, clock.seconds());
  }
  if (hits < 0) std::puts("");  // keeps the loop from being optimised away
  return 1e9 * best / double(cases.size());
}

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
    const std::map<std::string, triangle_method> by_name = {
        {"edge", triangle_method::edge_tests},
        {"mt", triangle_method::moller_trumbore},
        {"watertight", triangle_method::watertight}};
    if (!by_name.count(method_name))
      throw error("--method must be edge, mt or watertight, got '" + method_name + "'");
    const triangle_method method = by_name.at(method_name);
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

    // The comparison, in float (where the methods differ most) and double.
    const auto cases_f = random_cases<float>(seed, rays);
    const auto cases_d = random_cases<double>(seed, rays);
    const auto mesh = crack_meshes();
    const auto targets = shared_points(mesh);
    std::printf("%d random rays on random triangles; %zu triangles (a fan of 48 at (1000, 3000, "
                "500) and a 12x12 grid), %zu shared points\n",
                rays, mesh.size(), targets.size());
    std::printf("%-11s %15s %15s %12s %12s\n", "method", "agree (float)", "cracks (float)",
                "ns (float)", "ns (double)");
    std::array<double, 3> rate{}, ns_f{}, ns_d{};
    std::array<long, 3> cracks{};
    long crack_rays = 0;
    for (int i = 0; i < 3; ++i) {
      const agreement a = agree(cases_f, methods[i]);
      rate[i] = 100.0 * double(a.same) / double(a.total);
      cracks[i] = count_cracks(mesh, targets, methods[i], seed, crack_rays);
      ns_f[i] = ns_per_test(cases_f, methods[i]);
      ns_d[i] = ns_per_test(cases_d, methods[i]);
      const std::string label(name(methods[i]));
      std::printf("%-11s %14.4f%% %8ld/%-6ld %12.1f %12.1f\n", label.c_str(), rate[i], cracks[i],
                  crack_rays, ns_f[i], ns_d[i]);
    }
    std::printf("\nsummary: %.2f s; agreement edge/mt/watertight %.4f/%.4f/%.4f %%, cracks "
                "%ld/%ld/%ld of %ld rays, ns per test (float) %.1f/%.1f/%.1f\n",
                total.seconds(), rate[0], rate[1], rate[2], cracks[0], cracks[1], cracks[2],
                crack_rays, ns_f[0], ns_f[1], ns_f[2]);
    return 0;
  });
}

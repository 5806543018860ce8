// Chapter 1.5, the comparison (compare.hpp): the three triangle methods on random rays (agreement
// with double precision, time per test) and on rays through the shared edges and vertices of two
// meshes (cracks).
#include "compare.hpp"

#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

using namespace zraka;

namespace {

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

method_comparison compare_triangle_methods(std::uint64_t seed, int rays) {
  const auto cases_f = random_cases<float>(seed, rays);
  const auto cases_d = random_cases<double>(seed, rays);
  const auto mesh = crack_meshes();
  const auto targets = shared_points(mesh);
  std::printf("%d random rays on random triangles; %zu triangles (a fan of 48 at (1000, 3000, "
              "500) and a 12x12 grid), %zu shared points\n",
              rays, mesh.size(), targets.size());
  std::printf("%-11s %15s %15s %12s %12s\n", "method", "agree (float)", "cracks (float)",
              "ns (float)", "ns (double)");
  method_comparison c;
  for (int i = 0; i < 3; ++i) {
    const agreement a = agree(cases_f, triangle_methods[i]);
    c.agree[i] = 100.0 * double(a.same) / double(a.total);
    c.cracks[i] = count_cracks(mesh, targets, triangle_methods[i], seed, c.crack_rays);
    c.ns_float[i] = ns_per_test(cases_f, triangle_methods[i]);
    c.ns_double[i] = ns_per_test(cases_d, triangle_methods[i]);
    const std::string label(name(triangle_methods[i]));
    std::printf("%-11s %14.4f%% %8ld/%-6ld %12.1f %12.1f\n", label.c_str(), c.agree[i], c.cracks[i],
                c.crack_rays, c.ns_float[i], c.ns_double[i]);
  }
  return c;
}

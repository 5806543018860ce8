// Ray-triangle intersection (triangle.hpp): the three methods, their agreement, cracks on shared
// edges and vertices, slivers, degenerate and non-finite input, bounds, and reintersection of
// spawned rays.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>
#include <zraka/accel/simd.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/geometry/triangle.hpp>

using namespace zraka;

namespace {

constexpr std::array<triangle_method, 3> methods = {
    triangle_method::edge_tests, triangle_method::moller_trumbore, triangle_method::watertight};

template <class T>
vec3_t<T> random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}

// A message line for MESSAGE (doctest streams only one value).
template <class... A>
std::string cat(const A&... a) {
  std::ostringstream s;
  s.precision(3);
  (s << ... << a);
  return s.str();
}
template <class T>
const char* type_name() {
  return sizeof(T) == 4 ? "float" : "double";
}

// 10^x with x uniform in [lo, hi]
double log_uniform(rng& g, double lo, double hi) {
  return std::pow(10.0, lo + (hi - lo) * g.uniform());
}

template <class T>
bool hits(const triangle_t<T>& tri, const ray_t<T>& r, triangle_method m) {
  hit_t<T> h;
  return intersect(tri, r, T(0), infinity<T>, h, m);
}

}  // namespace

TEST_CASE_TEMPLATE("every method hits a triangle where it should and fills the record", T, float,
                   double) {
  const triangle_t<T> tri{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}};
  const ray_t<T> r({T(0.5), T(0.25), T(3)}, {0, 0, -1});
  for (auto m : methods) {
    CAPTURE(name(m));
    hit_t<T> h;
    REQUIRE(intersect(tri, r, T(0), infinity<T>, h, m));
    // Every quantity here is a short dyadic fraction, so all methods give it exactly.
    CHECK(h.t == T(3));
    CHECK(h.uv.x == T(0.25));
    CHECK(h.uv.y == T(0.125));
    CHECK(h.p == vec3_t<T>(T(0.5), T(0.25), T(0)));
    CHECK(h.normal == vec3_t<T>(0, 0, 1));
    CHECK(h.front_face);
    // From below: a hit on the back face, normal unchanged, front_face false.
    REQUIRE(intersect(tri, ray_t<T>({T(0.5), T(0.25), T(-1)}, {0, 0, 1}), T(0), infinity<T>, h, m));
    CHECK(h.t == T(1));
    CHECK_FALSE(h.front_face);
    // Outside each edge, and behind the origin (the t < 0 test Listing 1.12 lacks: errata B2).
    CHECK_FALSE(hits(tri, ray_t<T>({T(-0.5), T(0.5), T(3)}, {0, 0, -1}), m));
    CHECK_FALSE(hits(tri, ray_t<T>({T(0.5), T(-0.5), T(3)}, {0, 0, -1}), m));
    CHECK_FALSE(hits(tri, ray_t<T>({T(1.5), T(1.5), T(3)}, {0, 0, -1}), m));
    CHECK_FALSE(hits(tri, ray_t<T>({T(0.5), T(0.25), T(3)}, {0, 0, 1}), m));
  }
  // The default intersect() is the watertight method.
  hit_t<T> h;
  CHECK(intersect(tri, r, T(0), infinity<T>, h));
}

TEST_CASE_TEMPLATE("t_min and t_max bound the hit (open interval)", T, float, double) {
  const triangle_t<T> tri{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
  const ray_t<T> r({0, 0, 2}, {0, 0, -1});  // hits at t = 2 exactly
  for (auto m : methods) {
    CAPTURE(name(m));
    hit_t<T> h;
    CHECK(intersect(tri, r, T(1.5), T(2.5), h, m));
    CHECK_FALSE(intersect(tri, r, T(2), T(3), h, m));  // t == t_min is excluded
    CHECK_FALSE(intersect(tri, r, T(0), T(2), h, m));  // t == t_max is excluded
    CHECK(intersect(tri, r, std::nextafter(T(2), T(0)), T(3), h, m));
    CHECK(intersect(tri, r, T(0), std::nextafter(T(2), T(3)), h, m));
    CHECK_FALSE(intersect(tri, r, T(2.5), infinity<T>, h, m));
  }
}

TEST_CASE_TEMPLATE("degenerate triangles and NaN/inf input are never hit", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>;
  const std::vector<triangle_t<T>> bad = {{{0, 0, 0}, {0, 0, 0}, {1, 1, 0}},  // two equal vertices
                                          {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}},  // a point
                                          {{-1, -2, -3}, {1, 2, 3}, {2, 4, 6}},  // collinear
                                          {{0, 0, 0}, {1, 0, 0}, {nan, 1, 0}},   // NaN vertex
                                          {{0, 0, 0}, {inf, 0, 0}, {0, 1, 0}},   // infinite vertex
                                          {{-inf, -inf, 0}, {inf, -inf, 0}, {0, inf, 0}}};
  for (auto m : methods) {
    CAPTURE(name(m));
    for (const auto& tri : bad) {
      // Rays from many directions through the line or point the triangle collapses to.
      rng g(7);
      for (int i = 0; i < 200; ++i) {
        const vec3_t<T> target = vec3_t<T>(T(g.uniform()), T(2 * g.uniform()), T(0));
        const vec3_t<T> o = target + T(3) * random_unit<T>(g);
        CHECK_FALSE(hits(tri, ray_t<T>(o, target - o), m));
      }
    }
    const triangle_t<T> good{{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    ray_t<T> r({0, 0, 1}, {0, 0, -1});
    r.origin.x = nan;
    CHECK_FALSE(hits(good, r, m));
    r.origin.x = inf;
    CHECK_FALSE(hits(good, r, m));
    CHECK_FALSE(hits(good, ray_t<T>({0, 0, 1}, {0, 0, 0}), m));     // zero direction
    CHECK_FALSE(hits(good, ray_t<T>({0, 0, 1}, {nan, 0, -1}), m));  // NaN direction
    ray_t<T> raw({0, 0, 1}, {0, 0, -1});
    raw.direction = {nan, nan, nan};  // set by hand, past the constructor's check
    CHECK_FALSE(hits(good, raw, m));
  }
}

TEST_CASE_TEMPLATE("rays parallel to the triangle's plane, above it or in it, do not hit", T, float,
                   double) {
  const triangle_t<T> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  for (auto m : methods) {
    CAPTURE(name(m));
    CHECK_FALSE(hits(tri, ray_t<T>({-1, T(0.25), T(0.5)}, {1, 0, 0}), m));     // above
    CHECK_FALSE(hits(tri, ray_t<T>({-1, T(0.25), T(0)}, {1, 0, 0}), m));       // in the plane
    CHECK_FALSE(hits(tri, ray_t<T>({-1, -1, T(0)}, {1, 1, 0}), m));            // in it, diagonal
    CHECK_FALSE(hits(tri, ray_t<T>({T(0.25), T(0.25), T(0)}, {1, 2, 0}), m));  // from inside
  }
}

TEST_CASE_TEMPLATE("the three methods agree on random rays and triangles", T, float, double) {
  // Tolerances: the methods round differently; for well-shaped triangles (smallest height at
  // least 1/10 of the longest edge) hit at |cos| >= 0.05, t and the barycentrics are
  // conditioned to about 1e3 ulp, so we allow 4e-4 (float) and 1e-12 (double), relative to t
  // and absolute for the barycentrics (which are at most 1). Rays aimed within that tolerance of
  // an edge may fairly be called hits by one method and misses by another: they are skipped.
  const T tol = sizeof(T) == 4 ? T(4e-4) : T(1e-12);
  rng g(2024);
  int compared = 0, both_hit = 0, disagree = 0;
  T worst_t = 0, worst_uv = 0;
  while (compared < 20000) {
    triangle_t<T> tri{random_unit<T>(g), random_unit<T>(g), random_unit<T>(g)};
    const vec3_t<T> n = glm::cross(tri.b - tri.a, tri.c - tri.a);
    const T longest = std::max(
        {glm::length(tri.b - tri.a), glm::length(tri.c - tri.b), glm::length(tri.a - tri.c)});
    if (glm::length(n) / longest < T(0.1) * longest) continue;  // height = |n| / edge
    const T u = T(-0.25 + 1.5 * g.uniform()), v = T(-0.25 + 1.5 * g.uniform());
    const T w = 1 - u - v;
    const vec3_t<T> target = w * tri.a + u * tri.b + v * tri.c;
    const vec3_t<T> o = target + T(1 + 9 * g.uniform()) * random_unit<T>(g);
    const ray_t<T> r(o, target - o);
    if (std::abs(glm::dot(glm::normalize(n), r.direction)) < T(0.05)) continue;
    if (std::min({std::abs(u), std::abs(v), std::abs(w)}) < T(10) * tol) continue;  // near an edge
    ++compared;
    std::array<hit_t<T>, 3> h;
    std::array<bool, 3> hit{};
    for (int i = 0; i < 3; ++i) hit[i] = intersect(tri, r, T(0), infinity<T>, h[i], methods[i]);
    const bool inside = u > 0 && v > 0 && w > 0;
    if (hit[0] != inside || hit[1] != inside || hit[2] != inside) ++disagree;
    if (hit[0] && hit[1] && hit[2]) {
      ++both_hit;
      for (int i = 0; i < 2; ++i) {
        worst_t = std::max(worst_t, std::abs(h[i].t - h[2].t) / h[2].t);
        worst_uv =
            std::max({worst_uv, std::abs(h[i].uv.x - h[2].uv.x), std::abs(h[i].uv.y - h[2].uv.y)});
      }
      worst_uv = std::max({worst_uv, std::abs(h[2].uv.x - u), std::abs(h[2].uv.y - v)});
    }
  }
  MESSAGE(cat(type_name<T>(), ": ", compared, " rays, ", both_hit, " hit by all three; ", disagree,
              " hit/miss disagreements; worst relative t difference ", worst_t,
              ", worst barycentric difference ", worst_uv));
  CHECK(disagree == 0);
  CHECK(both_hit > 4000);
  CHECK(worst_t <= tol);
  CHECK(worst_uv <= tol);
}

TEST_CASE_TEMPLATE("watertight edge functions have exact signs", T, float, double) {
  // a = b = 1 + 2^-k: a b = 1 + 2^(1-k) + 2^-2k rounds to 1 + 2^(1-k) = c d, so a b - c d rounds
  // to 0 (or, fused into an FMA, to a value of either sign) while the exact value is 2^-2k > 0.
  const int k = std::numeric_limits<T>::digits / 2;
  const T a = T(1) + std::ldexp(T(1), -k), c = T(1) + std::ldexp(T(1), 1 - k), d = T(1);
  CHECK(detail::edge_function(a, a, c, d) == std::ldexp(T(1), -2 * k));  // exact here
  CHECK(detail::edge_function(c, d, a, a) == -std::ldexp(T(1), -2 * k));  // and antisymmetric
  CHECK(detail::edge_function(c, d, c, d) == T(0));
  CHECK(detail::edge_function(T(3), T(5), T(5), T(3)) == T(0));
  // Far from 0 the plain value is kept.
  CHECK(detail::edge_function(T(3), T(4), T(1), T(2)) == T(10));
}

namespace {

// A closed fan of n triangles around a centre vertex, as a cone (the centre raised by h), rim
// vertices on a circle rounded to the grid `q` (so every coordinate is exactly representable).
template <class T>
std::vector<triangle_t<T>> fan(int n, T radius, T h, T q, vec3_t<T> shift) {
  std::vector<vec3_t<T>> rim;
  for (int k = 0; k < n; ++k) {
    const double th = 2 * pi<double> * k / n;
    rim.push_back(shift + vec3_t<T>(T(std::round(radius * std::cos(th) / q) * q),
                                    T(std::round(radius * std::sin(th) / q) * q), T(0)));
  }
  std::vector<triangle_t<T>> tris;
  for (int k = 0; k < n; ++k)
    tris.push_back({shift + vec3_t<T>(0, 0, h), rim[k], rim[(k + 1) % n]});
  return tris;
}

// A grid of n x n quads, each split into two triangles along a diagonal; heights z = small
// dyadic bumps. The grid starts at `corner`, cells `cell` wide.
template <class T>
std::vector<triangle_t<T>> grid(int n, T cell, vec3_t<T> corner) {
  auto vtx = [&](int i, int j) {
    return corner + vec3_t<T>(T(i) * cell, T(j) * cell, T(((i * 7 + j * 3) % 5)) * cell / T(8));
  };
  std::vector<triangle_t<T>> tris;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tris.push_back({vtx(i, j), vtx(i + 1, j), vtx(i + 1, j + 1)});
      tris.push_back({vtx(i, j), vtx(i + 1, j + 1), vtx(i, j + 1)});
    }
  return tris;
}

// Points on the shared (interior) edges and vertices of a mesh: every 1/8 of every edge that two
// triangles share, and every vertex all of whose edges are shared (so not on the boundary).
template <class T>
std::vector<vec3_t<T>> shared_points(const std::vector<triangle_t<T>>& tris) {
  std::vector<std::pair<vec3_t<T>, vec3_t<T>>> edges;
  for (const auto& t : tris) {
    const std::array<vec3_t<T>, 3> v = {t.a, t.b, t.c};
    for (int i = 0; i < 3; ++i) edges.emplace_back(v[i], v[(i + 1) % 3]);
  }
  auto shared = [&](const std::pair<vec3_t<T>, vec3_t<T>>& e) {
    for (const auto& f : edges)
      if (f.first == e.second && f.second == e.first) return true;
    return false;
  };
  std::vector<vec3_t<T>> pts, boundary;
  for (const auto& e : edges) {
    if (!shared(e)) {
      boundary.push_back(e.first);
      boundary.push_back(e.second);
      continue;
    }
    const auto& a = e.first;
    const auto& b = e.second;
    if (std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z))
      continue;  // each shared edge once (it appears in both directions)
    for (int s = 1; s < 8; ++s) pts.push_back(e.first + (T(s) / T(8)) * (e.second - e.first));
  }
  for (const auto& e : edges) {
    bool inner = std::find(boundary.begin(), boundary.end(), e.first) == boundary.end();
    for (const auto& p : pts) inner = inner && p != e.first;  // once per vertex
    if (inner) pts.push_back(e.first);
  }
  return pts;
}

struct crack_count {
  long rays = 0, cracks = 0;
};

// Rays at each target: straight down (exact: axis direction, target exactly on the edge) and
// from `origins` random points above (the normalised direction passes within rounding of it).
// The meshes are height fields with slopes below 1/2 and the rays descend at 45 degrees or
// steeper, so each ray crosses the surface at its target: missing every triangle is a crack.
template <class T>
crack_count count_cracks(const std::vector<triangle_t<T>>& tris, triangle_method m,
                         const std::vector<vec3_t<T>>& targets, T height, int origins,
                         std::uint64_t seed) {
  crack_count c;
  rng g(seed);
  for (const auto& target : targets) {
    for (int k = -1; k < origins; ++k) {
      vec3_t<T> o = target + vec3_t<T>(0, 0, height);
      if (k >= 0) {
        vec3_t<T> d = random_unit<T>(g);
        d.z = std::abs(d.z) + T(1);  // steeper than any facet: no ray only grazes a vertex
        o = target + height * d;
      }
      const ray_t<T> r(o, target - o);
      bool any = false;
      for (const auto& tri : tris) any = any || hits(tri, r, m);
      ++c.rays;
      c.cracks += any ? 0 : 1;
    }
  }
  return c;
}

}  // namespace

TEST_CASE_TEMPLATE("watertight: no cracks on shared edges and vertices of fans and grids", T, float,
                   double) {
  struct mesh {
    const char* what;
    std::vector<triangle_t<T>> tris;
    T height;
  };
  // Away from the origin the coordinates carry fewer fraction bits, which is where the
  // non-watertight methods lose rays.
  const std::vector<mesh> meshes = {
      {"fan of 16 at 0", fan<T>(16, T(1), T(0.25), T(1) / 1024, {0, 0, 0}), T(3)},
      {"fan of 64 at 0, flat", fan<T>(64, T(1), T(0), T(1) / 1024, {0, 0, 0}), T(3)},
      {"fan of 48 at (1000, 3000, 500)", fan<T>(48, T(2), T(0.5), T(1) / 256, {1000, 3000, 500}),
       T(5)},
      {"grid 8x8 at 0", grid<T>(8, T(0.25), {0, 0, 0}), T(4)},
      {"grid 8x8 at (4096, -2048, 100)", grid<T>(8, T(0.375), {4096, -2048, 100}), T(6)}};
  for (const auto& mesh : meshes) {
    const auto targets = shared_points(mesh.tris);
    REQUIRE(targets.size() > 50);
    std::array<crack_count, 3> c;
    for (int i = 0; i < 3; ++i)
      c[i] = count_cracks(mesh.tris, methods[i], targets, mesh.height, 6, 99);
    MESSAGE(cat(type_name<T>(), " ", mesh.what, ": ", c[0].rays, " rays; cracks: edge ",
                c[0].cracks, ", mt ", c[1].cracks, ", watertight ", c[2].cracks));
    CHECK(c[2].cracks == 0);
  }
}

TEST_CASE_TEMPLATE("slivers: thin triangles are hit, agree, and stay watertight", T, float,
                   double) {
  // Heights down to 1e-6 (float: 1e-4) of the length: n is tiny but non-zero, so they are real
  // triangles. Barycentrics along the long edge are well conditioned: tolerance as above.
  const T tol = sizeof(T) == 4 ? T(4e-4) : T(1e-12);
  for (T thin : {T(1e-2), T(1e-4), sizeof(T) == 4 ? T(1e-4) : T(1e-6)}) {
    CAPTURE(thin);
    const triangle_t<T> lower{{0, 0, 0}, {1, 0, 0}, {T(0.5), thin, 0}};
    const triangle_t<T> upper{{1, 0, 0}, {0, 0, 0}, {T(0.5), -thin, 0}};  // shares edge AB
    for (auto m : methods) {
      CAPTURE(name(m));
      hit_t<T> h;
      REQUIRE(
          intersect(lower, ray_t<T>({T(0.5), thin / 4, 1}, {0, 0, -1}), T(0), infinity<T>, h, m));
      CHECK(std::abs(h.uv.y - T(0.25)) <= tol);  // weight of C: a quarter of the height
      CHECK(std::abs(h.uv.x - T(0.375)) <= tol);
    }
    // Rays exactly along the shared edge's points, from oblique directions.
    rng g(5);
    long cracks = 0;
    for (int i = 0; i < 500; ++i) {
      const vec3_t<T> target(T(1 + (i % 63)) / T(64), 0, 0);
      vec3_t<T> d = random_unit<T>(g);
      d.z = std::abs(d.z) + T(0.1);
      const ray_t<T> r(target + d, -d);
      cracks += (hits(lower, r, triangle_method::watertight) ||
                 hits(upper, r, triangle_method::watertight))
                    ? 0
                    : 1;
    }
    CHECK(cracks == 0);
  }
}

namespace {

struct reintersection {
  long spawned = 0, self_hits = 0, sliver_self_hits = 0, primary_misses = 0;
  double worst_offset = 0;  // largest offset / triangle size seen
};

// Random triangles with positions |c| log-uniform in [1e-8, 1e8] and sizes from 1e-3 (float)
// or 1e-5 (double) to 1e2 times |c|, half of them slivers; a primary ray hits each, and
// `per_hit` rays leave the hit by spawn_ray, half on each side, half of them grazing. None of
// them may hit the triangle again.
template <class T>
reintersection reintersect(triangle_method m, int triangles, int per_hit) {
  reintersection out;
  rng g(12345);
  const double min_rel = sizeof(T) == 4 ? -3 : -5;
  for (int i = 0; i < triangles; ++i) {
    const double pos = log_uniform(g, -8, 8);
    const double size = pos * log_uniform(g, min_rel, 2);
    const vec3 c = pos * vec3(random_unit<double>(g));
    triangle_t<T> tri{vec3_t<T>(c + size * vec3(random_unit<double>(g))),
                      vec3_t<T>(c + size * vec3(random_unit<double>(g))),
                      vec3_t<T>(c + size * vec3(random_unit<double>(g)))};
    if (i % 2)  // every other one a sliver: C within 1e-1 ... 1e-3 (float) or 1e-5 of line AB
      tri.c = vec3_t<T>(vec3(tri.a) + g.uniform() * (vec3(tri.b) - vec3(tri.a)) +
                        size * log_uniform(g, min_rel, -1) * vec3(random_unit<double>(g)));
    const double u = 0.05 + 0.9 * g.uniform(), v = (1 - u) * (0.05 + 0.9 * g.uniform());
    const vec3 target = (1 - u - v) * vec3(tri.a) + u * vec3(tri.b) + v * vec3(tri.c);
    const vec3 o = target + 4 * size * vec3(random_unit<double>(g));
    hit_t<T> h;
    if (!intersect(tri, ray_t<T>(vec3_t<T>(o), vec3_t<T>(target - o)), T(0), infinity<T>, h, m)) {
      ++out.primary_misses;
      continue;
    }
    out.worst_offset =
        std::max(out.worst_offset, double(glm::dot(glm::abs(h.normal), h.p_error)) / size);
    for (int k = 0; k < per_hit; ++k) {
      vec3_t<T> w = random_unit<T>(g);
      if (k >= 2)  // grazing: 1e-4 ... 1e-1 radians off the surface
        w = glm::normalize(w - glm::dot(w, h.normal) * h.normal) +
            T(log_uniform(g, -4, -1)) * h.normal;
      if ((glm::dot(w, h.normal) > T(0)) != (k % 2 == 0)) w = -w;  // alternate the sides
      hit_t<T> again;
      ++out.spawned;
      const bool self = intersect(tri, spawn_ray(h, w), T(0), infinity<T>, again, m);
      out.self_hits += self ? 1 : 0;
      out.sliver_self_hits += self && i % 2 ? 1 : 0;
    }
  }
  return out;
}

}  // namespace

TEST_CASE_TEMPLATE("rays spawned from a triangle never hit it again (1e-8 ... 1e8)", T, float,
                   double) {
  for (auto m : methods) {
    const reintersection r = reintersect<T>(m, 1500, 4);
    MESSAGE(cat(type_name<T>(), " ", name(m), ": ", r.spawned, " spawned rays, ", r.self_hits,
                " hit their own triangle again (", r.sliver_self_hits,
                " of them slivers); primary misses ", r.primary_misses, "; largest offset/size ",
                r.worst_offset));
    CHECK(r.spawned >= 4000);
    // The primary ray is aimed well inside: every method must hit it (float: within 1e-3
    // relative size a few may be lost to the shear's rounding; see the book).
    CHECK(r.primary_misses <= 15);
    if (m == triangle_method::watertight) CHECK(r.self_hits == 0);
  }
}

TEST_CASE_TEMPLATE("the hit point lies within p_error of the triangle's plane", T, float, double) {
  // The exact plane distance is computed in long double from the stored vertices; the computed
  // point must be within dot(|n|, p_error), the offset spawn_ray moves it by.
  rng g(77);
  double worst_ratio = 0;
  for (int i = 0; i < 2000; ++i) {
    const double pos = log_uniform(g, -8, 8), size = pos * log_uniform(g, -3, 2);
    const vec3 c = pos * vec3(random_unit<double>(g));
    const triangle_t<T> tri{vec3_t<T>(c + size * vec3(random_unit<double>(g))),
                            vec3_t<T>(c + size * vec3(random_unit<double>(g))),
                            vec3_t<T>(c + size * vec3(random_unit<double>(g)))};
    const vec3 target = (vec3(tri.a) + vec3(tri.b) + vec3(tri.c)) / 3.0;
    const vec3 o = target + 3 * size * vec3(random_unit<double>(g));
    hit_t<T> h;
    if (!intersect(tri, ray_t<T>(vec3_t<T>(o), vec3_t<T>(target - o)), T(0), infinity<T>, h))
      continue;
    using L = long double;
    const L ax = tri.a.x, ay = tri.a.y, az = tri.a.z;
    const L e1[3] = {L(tri.b.x) - ax, L(tri.b.y) - ay, L(tri.b.z) - az};
    const L e2[3] = {L(tri.c.x) - ax, L(tri.c.y) - ay, L(tri.c.z) - az};
    const L n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                    e1[0] * e2[1] - e1[1] * e2[0]};
    const L len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const L dist =
        std::abs(((L(h.p.x) - ax) * n[0] + (L(h.p.y) - ay) * n[1] + (L(h.p.z) - az) * n[2]) / len);
    const double bound = glm::dot(glm::abs(h.normal), h.p_error);
    REQUIRE(bound > 0);
    worst_ratio = std::max(worst_ratio, double(dist) / bound);
  }
  MESSAGE(cat(type_name<T>(),
              ": worst (distance of p from the plane) / (spawn offset) = ", worst_ratio));
  CHECK(worst_ratio < 1);
}

namespace {

// The conservative-t bound this library used before (pbrt's, on the errors of the shear, the
// edge functions and t), kept here only to count the real hits it turned away.
template <class T>
bool old_bound_accepts(const triangle_t<T>& tri, const ray_t<T>& r, T t) {
  const detail::watertight_ray<T> w(r);
  auto to_ray_space = [&](const vec3_t<T>& p) {
    const vec3_t<T> q = p - w.origin;
    return vec3_t<T>(q[w.kx] - w.sx * q[w.kz], q[w.ky] - w.sy * q[w.kz], w.sz * q[w.kz]);
  };
  const vec3_t<T> a = to_ray_space(tri.a), b = to_ray_space(tri.b), c = to_ray_space(tri.c);
  const T e_a = detail::edge_function(c.x, b.y, c.y, b.x);
  const T e_b = detail::edge_function(a.x, c.y, a.y, c.x);
  const T e_c = detail::edge_function(b.x, a.y, b.y, a.x);
  const T inv_det = T(1) / (e_a + e_b + e_c);
  const T X = max_component(glm::abs(vec3_t<T>(a.x, b.x, c.x)));
  const T Y = max_component(glm::abs(vec3_t<T>(a.y, b.y, c.y)));
  const T Z = max_component(glm::abs(vec3_t<T>(a.z, b.z, c.z)));
  const T E = max_component(glm::abs(vec3_t<T>(e_a, e_b, e_c)));
  const T dx = gamma<T>(7) * (X + Z), dy = gamma<T>(7) * (Y + Z), dz = gamma<T>(3) * Z;
  const T de = T(2) * (gamma<T>(2) * X * Y + dx * Y + X * dy);
  const T dt = T(3) * (gamma<T>(3) * E * Z + de * Z + E * dz) * std::abs(inv_det);
  return t > dt;
}

// One cell of a sweep: rays that pass the edge tests at t > 0 (candidates), those the
// certainty test accepts (all of them must be), those the old bound accepted; and rays spawned
// from the hits (both sides, some grazing) that hit the triangle again (none may).
struct sweep_cell {
  long rays = 0, candidates = 0, accepted = 0, old_accepted = 0, spawned = 0, self_hits = 0;
};

template <class T>
void probe(const triangle_t<T>& tri, const ray_t<T>& r, rng& g, sweep_cell& c) {
  ++c.rays;
  T t, u, v;
  if (!detail::watertight_test(detail::watertight_ray<T>(r), tri.a, tri.b, tri.c, t, u, v) ||
      !(t > T(0)))
    return;
  ++c.candidates;
  c.old_accepted += old_bound_accepts(tri, r, t) ? 1 : 0;
  hit_t<T> h;
  if (!intersect_watertight(tri, r, T(0), infinity<T>, h)) return;
  ++c.accepted;
  for (int k = 0; k < 4; ++k) {
    vec3_t<T> w = random_unit<T>(g);
    if (k >= 2)  // grazing: 1e-6 ... 1e-2 radians off the surface
      w = glm::normalize(w - glm::dot(w, h.normal) * h.normal) + T(log_uniform(g, -6, -2)) * h.normal;
    if ((glm::dot(w, h.normal) > T(0)) != (k % 2 == 0)) w = -w;
    hit_t<T> again;
    ++c.spawned;
    c.self_hits += intersect_watertight(tri, spawn_ray(h, w), T(0), infinity<T>, again) ? 1 : 0;
  }
}

// A random rotation (columns of an orthonormal frame), applied in double.
struct frame {
  vec3 x, y, z;
  explicit frame(rng& g) {
    z = vec3(random_unit<double>(g));
    x = glm::normalize(glm::cross(z, std::abs(z.x) < 0.9 ? vec3(1, 0, 0) : vec3(0, 1, 0)));
    y = glm::cross(z, x);
  }
  vec3 operator()(const vec3& p) const { return p.x * x + p.y * y + p.z * z; }
};

template <class T>
void report(const char* what, double param, const sweep_cell& c) {
  MESSAGE(cat(type_name<T>(), " ", what, " ", param, ": ", c.rays, " rays, ", c.candidates,
              " pass the edges, accepted ", c.accepted, " (old bound: ", c.old_accepted, "); ",
              c.self_hits, "/", c.spawned, " spawned rays hit again"));
  CHECK(c.accepted == c.candidates);
  CHECK(c.self_hits == 0);
}

}  // namespace

TEST_CASE_TEMPLATE("certainty of t > 0: slivers of aspect 1e-1 ... 1e-7 are hit", T, float, double) {
  // Length 1, height `aspect`, at random places (|c| up to 100) and orientations; rays from
  // distance 1 ... 100 at least 0.1 rad off the plane, aimed at points well inside.
  rng g(101);
  for (int e = 1; e <= 7; ++e) {
    const double aspect = std::pow(10.0, -e);
    sweep_cell c;
    for (int i = 0; i < 400; ++i) {
      const frame f(g);
      const vec3 center = log_uniform(g, -2, 2) * vec3(random_unit<double>(g));
      const triangle_t<T> tri{vec3_t<T>(center + f(vec3(-0.5, 0, 0))),
                              vec3_t<T>(center + f(vec3(0.5, 0, 0))),
                              vec3_t<T>(center + f(vec3(0.1 * g.uniform(), aspect, 0)))};
      const double u = 0.25 + 0.5 * g.uniform(), v = 0.25 + 0.25 * g.uniform();
      const vec3 target = (1 - u - v) * vec3(tri.a) + u * vec3(tri.b) + v * vec3(tri.c);
      vec3 d = vec3(random_unit<double>(g));
      if (std::abs(glm::dot(d, f.z)) < 0.1) d = glm::normalize(d + 0.2 * f.z);
      const vec3 o = target + log_uniform(g, 0, 2) * d;
      probe(tri, ray_t<T>(vec3_t<T>(o), vec3_t<T>(target - o)), g, c);
      // and straight down the plane's normal, from an origin on the normal through the target
      const vec3 o2 = target + log_uniform(g, 0, 2) * f.z;
      probe(tri, ray_t<T>(vec3_t<T>(o2), vec3_t<T>(target - o2)), g, c);
    }
    report<T>("sliver, aspect", aspect, c);
    // float: below aspect 1e-5 the rounding of the vertices and of the shear (~1e-7 of the
    // distance) is as large as the sliver's height, so fewer rays pass the edges at all.
    CHECK(c.candidates >= (sizeof(T) == 8 || aspect >= 1e-5 ? c.rays / 2 : c.rays / 8));
  }
}

TEST_CASE_TEMPLATE("certainty of t > 0: tiny triangles far away are hit", T, float, double) {
  // Size 1e-6 ... 1 near the coordinate origin (where float can represent them), seen from
  // distance 1 ... 1e6. In float, beyond distance/size ~ 1e6 the rounded direction itself
  // misses the triangle: those rays are not candidates, the rest must all be accepted.
  rng g(202);
  for (int se = 0; se <= 6; ++se)
    for (int de = 0; de <= 6; de += 2) {
      const double size = std::pow(10.0, -se), dist = std::pow(10.0, de);
      sweep_cell c;
      for (int i = 0; i < 100; ++i) {
        const frame f(g);
        const vec3 center = size * vec3(random_unit<double>(g));
        const triangle_t<T> tri{vec3_t<T>(center + size * f(vec3(-0.5, -0.3, 0))),
                                vec3_t<T>(center + size * f(vec3(0.5, -0.3, 0))),
                                vec3_t<T>(center + size * f(vec3(0, 0.6, 0)))};
        const vec3 target = (vec3(tri.a) + vec3(tri.b) + vec3(tri.c)) / 3.0;
        vec3 d = vec3(random_unit<double>(g));
        if (std::abs(glm::dot(d, f.z)) < 0.2) d = glm::normalize(d + 0.4 * f.z);
        const vec3_t<T> o(target + dist * d);
        probe(tri, ray_t<T>(o, vec3_t<T>(target) - o), g, c);
      }
      report<T>("tiny far triangle, size/distance", size / dist, c);
      if (sizeof(T) == 8 || size / dist >= 1e-5) CHECK(c.candidates >= 90);
    }
}

TEST_CASE_TEMPLATE("certainty of t > 0: rays nearly parallel to the plane are hit", T, float,
                   double) {
  // A triangle of size 1 at a random place and orientation; rays at 1e-1 ... 1e-6 rad to its
  // plane from distance 0.5 ... 2, aimed at points well inside.
  rng g(303);
  for (int e = 1; e <= 6; ++e) {
    const double angle = std::pow(10.0, -e);
    sweep_cell c;
    for (int i = 0; i < 400; ++i) {
      const frame f(g);
      const vec3 center = log_uniform(g, -1, 1) * vec3(random_unit<double>(g));
      const triangle_t<T> tri{vec3_t<T>(center + f(vec3(-1, -1, 0))),
                              vec3_t<T>(center + f(vec3(1, -1, 0))),
                              vec3_t<T>(center + f(vec3(0, 1, 0)))};
      const double u = 0.3 + 0.2 * g.uniform(), v = 0.3 + 0.2 * g.uniform();
      const vec3 target = (1 - u - v) * vec3(tri.a) + u * vec3(tri.b) + v * vec3(tri.c);
      const double phi = 2 * pi<double> * g.uniform();
      const double side = i % 2 ? 1 : -1;  // from the front and from the back
      const vec3 d = f(vec3(std::cos(angle) * std::cos(phi), std::cos(angle) * std::sin(phi),
                            side * std::sin(angle)));
      const vec3 o = target + (0.5 + 1.5 * g.uniform()) * d;
      probe(tri, ray_t<T>(vec3_t<T>(o), vec3_t<T>(target - o)), g, c);
    }
    report<T>("grazing ray, angle", angle, c);
    CHECK(c.candidates >= 300);
  }
}

TEST_CASE_TEMPLATE("certainty of t > 0: the extreme cases", T, float, double) {
  const triangle_t<T> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const T tiny = std::numeric_limits<T>::min();
  hit_t<T> h;
  // Origin exactly in the plane, the ray leaving it: s = 0, never a hit.
  CHECK_FALSE(intersect_watertight(tri, ray_t<T>({T(0.25), T(0.25), 0}, {0, 0, 1}), T(0), infinity<T>, h));
  CHECK_FALSE(intersect_watertight(tri, ray_t<T>({T(0.25), T(0.25), 0}, {0, 0, -1}), T(0), infinity<T>, h));
  // 1e-30 (double: 1e-300) above the plane, going down: a real hit at that t, accepted.
  const T above = sizeof(T) == 4 ? T(1e-30) : T(1e-300);
  REQUIRE(intersect_watertight(tri, ray_t<T>({T(0.25), T(0.25), above}, {0, 0, -1}), T(0), infinity<T>, h));
  CHECK(std::abs(h.t - above) <= T(1e-6) * above);
  CHECK_FALSE(intersect_watertight(tri, ray_t<T>({T(0.25), T(0.25), above}, {0, 0, 1}), T(0), infinity<T>, h));
  // A sliver of height min (the smallest normal float/double) from far above: still a hit.
  const triangle_t<T> flat{{0, 0, 0}, {1, 0, 0}, {T(0.5), tiny, 0}};
  CHECK(intersect_watertight(flat, ray_t<T>({T(0.5), tiny / 2, T(1e3)}, {0, 0, -1}), T(0), infinity<T>, h));
  CHECK_FALSE(intersect_watertight(flat, ray_t<T>({T(0.5), tiny / 2, T(1e3)}, {0, 0, 1}), T(0), infinity<T>, h));
  // A ray in the plane, along it: s and n.D are 0: no hit, as before.
  CHECK_FALSE(intersect_watertight(tri, ray_t<T>({-1, T(0.25), 0}, {1, 0, 0}), T(0), infinity<T>, h));
  // Huge and tiny coordinates together: a triangle of size 1e-30 (float: 1e-15) at the
  // coordinate origin, seen from 1e3 away.
  const T s = sizeof(T) == 4 ? T(1e-15) : T(1e-30);
  const triangle_t<T> small{{0, 0, 0}, {s, 0, 0}, {0, s, 0}};
  CHECK(intersect_watertight(small, ray_t<T>({s / 4, s / 4, T(1e3)}, {0, 0, -1}), T(0), infinity<T>, h));
}

// t_positive_in_float answers for the double test only where it is sure: wherever it answers,
// the answer must be t_certainly_positive_in_double's, on ordinary hits (where it must answer
// nearly always, or it saves nothing) and on the cases that make float unsure: origins on or
// within an ulp of the plane, slivers, grazing directions, scales from 1e-30 to 1e30, far
// offsets, subnormal and huge coordinates, inf and NaN; and again with subnormals flushed to
// zero, as a program that sets the processor's FTZ/DAZ flags runs it.
namespace {
struct certainty_counts {
  long answered = 0, ordinary = 0, ordinary_answered = 0;
};
void certainty_cases(rng& g, certainty_counts& c) {
  const auto check = [&](const vec3f& A, const vec3f& B, const vec3f& C, const vec3f& O, const vec3f& D,
                         bool ordinary) {
    const int f = detail::t_positive_in_float(A, B, C, O, D);
    const bool d = detail::t_certainly_positive_in_double(A, B, C, O, D);
    if (f >= 0) {
      ++c.answered;
      if ((f == 1) != d) {
        CAPTURE(A.x); CAPTURE(A.y); CAPTURE(A.z); CAPTURE(O.x); CAPTURE(O.y); CAPTURE(O.z);
        CAPTURE(D.x); CAPTURE(D.y); CAPTURE(D.z); CAPTURE(f);
        FAIL("float answered, and not as double");
      }
    }
    if (ordinary) ++c.ordinary, c.ordinary_answered += f >= 0;
    // The dispatcher gives double's answer in every case.
    CHECK(detail::t_certainly_positive(A, B, C, O, D) == d);
  };
  for (int i = 0; i < 20000; ++i) {
    const float size = float(log_uniform(g, -30, 30)), far = float(log_uniform(g, -30, 30));
    const bool near_origin = g.uniform() < 0.5;
    const vec3f offset = (near_origin ? 0.0f : far) * random_unit<float>(g);
    const vec3f A = offset + size * random_unit<float>(g), B = offset + size * random_unit<float>(g);
    vec3f C = offset + size * random_unit<float>(g);
    const float distance = size * float(log_uniform(g, -1, 3));
    const vec3f P = A + float(g.uniform()) * (B - A) * 0.5f + float(g.uniform()) * (C - A) * 0.5f;
    const vec3f D = random_unit<float>(g);
    // Ordinary: from some distance along -D to a point of the triangle.
    // (Ordinary: sizes 1e-6 ... 1e6, the triangle not farther than 1e3 sizes from the coordinate origin.)
    check(A, B, C, P - distance * D, D, size > 1e-6f && size < 1e6f && (near_origin || far < 1e3f * size));
    check(A, B, C, P + distance * D, D, false);  // behind
    // On or next to the plane: the point itself, and an ulp or a few away in each coordinate.
    check(A, B, C, P, D, false);
    const vec3f ulp(std::nextafter(P.x, infinity<float>), std::nextafter(P.y, -infinity<float>),
                    std::nextafter(P.z, infinity<float>));
    check(A, B, C, ulp, D, false);
    check(A, B, C, P + size * 1e-6f * random_unit<float>(g), D, false);
    // A sliver: C on AB but for 10^-1 ... 10^-8 of the size.
    const vec3f sliver = A + float(g.uniform()) * (B - A) + size * float(log_uniform(g, -8, -1)) * random_unit<float>(g);
    check(A, B, sliver, P - distance * D, D, false);
    // Grazing: a direction in the plane but for 10^-9 ... 10^-1.
    const vec3f n = glm::normalize(glm::cross(vec3(B - A), vec3(C - A))) != glm::normalize(glm::cross(vec3(B - A), vec3(C - A)))
                        ? vec3f(0, 0, 1)
                        : vec3f(glm::normalize(glm::cross(vec3(B - A), vec3(C - A))));
    const vec3f along = vec3f(glm::normalize(vec3(B - A)));
    const vec3f graze = along + float(log_uniform(g, -9, -1)) * n;
    check(A, B, C, P - distance * graze, graze, false);
  }
  // Special values in every coordinate of the origin and the direction.
  const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min(),
              small = std::numeric_limits<float>::min();
  const float values[] = {0.0f, -0.0f, 1.0f, -1.0f, tiny, -tiny, small, big, -big, 1e30f, -1e-30f,
                          infinity<float>, -infinity<float>, std::numeric_limits<float>::quiet_NaN()};
  const vec3f tris[][3] = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},
                           {{tiny, 0, 0}, {0, tiny, 0}, {0, 0, tiny}},
                           {{small, 0, 0}, {0, small, 0}, {small, small, small}},
                           {{-big, -big, 0}, {big, -big, 0}, {0, big, big}},
                           {{1e30f, 1e30f, 1e30f}, {1e30f, 1e30f, 1.0000001e30f}, {1e30f, 1.0000001e30f, 1e30f}}};
  for (const auto& t : tris)
    for (const float a : values)
      for (const float b : values) {
        check(t[0], t[1], t[2], vec3f(a, b, 0.5f), vec3f(0, 0, -1), false);
        check(t[0], t[1], t[2], vec3f(0.25f, 0.25f, 1), vec3f(a, b, -1), false);
        check(t[0], t[1], t[2], vec3f(a, 0.25f, b), vec3f(b, -1, a), false);
      }
}
}  // namespace

TEST_CASE("the certainty of t > 0 asked in float first: double's answer wherever float answers") {
  rng g(77);
  certainty_counts c;
  certainty_cases(g, c);
  MESSAGE(cat("float answered ", c.answered, " cases, ", c.ordinary_answered, " of ", c.ordinary, " ordinary hits"));
  CHECK(c.ordinary > 1000);
  CHECK(c.ordinary_answered >= c.ordinary * 95 / 100);
#if ZRAKA_HAS_SSE
  // The same with subnormals flushed to zero (FTZ) and read as zero (DAZ).
  const unsigned csr = _mm_getcsr();
  _mm_setcsr(csr | 0x8040u);
  certainty_counts flushed;
  rng g2(77);
  certainty_cases(g2, flushed);
  _mm_setcsr(csr);
  CHECK(flushed.ordinary_answered >= flushed.ordinary * 95 / 100);
#endif
}

// The watertight test's per-ray half chooses its axes by arithmetic, not branches (triangle.hpp):
// on every combination of special components, z is an axis of largest |D| (the first such in
// the order the rule x > y, x > z, y > z picks), (kx, ky, kz) is a permutation, an even one
// exactly when D[kz] is not negative (the winding kept), and the shear is D's components times
// 1 / D[kz] (one division a ray).
TEST_CASE_TEMPLATE("the watertight ray's axes and shear, on special direction components", T, float, double) {
  const T big = std::numeric_limits<T>::max(), tiny = std::numeric_limits<T>::denorm_min();
  const T values[] = {T(0), -T(0), T(1), T(-1), T(0.5), T(-3), tiny, -tiny, big, -big,
                      infinity<T>, -infinity<T>, std::numeric_limits<T>::quiet_NaN()};
  int checked = 0;
  for (const T x : values)
    for (const T y : values)
      for (const T z : values) {
        ray_t<T> r(vec3_t<T>(1, 2, 3), vec3_t<T>(1, 0, 0));
        r.direction = vec3_t<T>(x, y, z);  // set after the constructor, which refuses some
        const detail::watertight_ray<T> w(r);
        const T d[3] = {x, y, z};
        const T ax = std::abs(x), ay = std::abs(y), az = std::abs(z);
        const int kz = ax > ay ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
        REQUIRE(w.kz == kz);
        REQUIRE(w.kx + w.ky + w.kz == 3);
        REQUIRE(w.kx != w.ky);
        const bool even = w.kx == (w.kz + 1) % 3;
        REQUIRE(even == !(d[kz] < T(0)));
        const auto same = [](T a, T b) { return (std::isnan(a) && std::isnan(b)) || a == b; };
        REQUIRE(same(w.sz, T(1) / d[kz]));
        REQUIRE(same(w.sx, d[w.kx] * w.sz));
        REQUIRE(same(w.sy, d[w.ky] * w.sz));
        REQUIRE(w.ox == T(1 + w.kx));
        REQUIRE(w.oy == T(1 + w.ky));
        REQUIRE(w.oz == T(1 + w.kz));
        ++checked;
      }
  CHECK(checked == 13 * 13 * 13);
}

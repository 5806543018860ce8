// The triangle BVH (triangle_bvh.hpp): its memory (4-wide nodes of 128 bytes, 32 per child;
// blocks of four 40-byte triangles; at most 60 bytes per triangle on the teapot), and hits identical to brute force (same t, same triangle,
// same barycentrics, bit for bit) for nearest and any hit, against two references: its own brute
// force loop and triangle.hpp's intersect_watertight() over the input in index order. On
// random soups, the teapot at several divs, axis-aligned rays, rays from inside, no triangles,
// one triangle, identical centroids, degenerate triangles and NaN rays.
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/io/bpt.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

using namespace zraka;

namespace {

using tri_f = triangle_t<float>;

vec3f random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3f(vec3(s * std::cos(phi), s * std::sin(phi), z));
}
vec3f random_in(rng& g, const aabb_t<float>& b) {
  return b.lo + vec3f(vec3(g.uniform(), g.uniform(), g.uniform())) * (b.hi - b.lo);
}

// The independent reference: triangle.hpp's watertight test over every input triangle in index
// order; strict t < t_max, so among exact ties the lowest index stays.
triangle_bvh_hit reference(const std::vector<tri_f>& tris, const rayf& r, float t_max) {
  triangle_bvh_hit best;
  for (std::size_t i = 0; i < tris.size(); ++i) {
    hit_t<float> h;
    if (intersect_watertight(tris[i], r, 0.0f, t_max, h)) {
      t_max = h.t;
      best = {h.t, h.uv.x, h.uv.y, std::uint32_t(i)};
    }
  }
  return best;
}

bool same(const triangle_bvh_hit& a, const triangle_bvh_hit& b) {
  return a.triangle == b.triangle && a.t == b.t && a.u == b.u && a.v == b.v;
}

// The SIMD levels this processor runs (simd.hpp), the scalar one first: each walk must give the
// reference's hits. On x86-64 with AVX2 (this project's machines), all three.
std::vector<simd_level> simd_levels() {
  std::vector<simd_level> out;
  for (const simd_level s : {simd_level::scalar, simd_level::sse, simd_level::avx2})
    if (usable_simd(s) == s) out.push_back(s);
  return out;
}

// The eight-wide BVH with its nodes quantized (wide_qnode8), whatever its size.
bvh_build_options quantized_options() {
  bvh_build_options o = triangle_bvh::default_options();
  o.quantize = 1;
  return o;
}

// The nearest hit and any hit of the eight-wide BVH (with full and with quantized nodes) and the
// four-wide one, at every SIMD level, against the reference, and the BVH's brute force. Returns
// the number of rays that hit.
int compare(const std::vector<tri_f>& tris, const std::vector<rayf>& rays) {
  const triangle_bvh bvh8(tris);
  const triangle_bvh4 bvh4(tris);
  const triangle_bvh bvh8q(tris, quantized_options());
  CHECK((bvh8q.quantized() || bvh8q.node_count() == 0));
  int hits = 0, bad_nearest = 0, bad_brute = 0, bad_any = 0;
  for (const rayf& r : rays) {
    const triangle_bvh_hit want = reference(tris, r, infinity<float>);
    const bool want_found = want.triangle != UINT32_MAX;
    hits += want_found;
    triangle_bvh_hit brute;
    const bool brute_found = bvh8.intersect_brute_force(r, 0.0f, infinity<float>, brute);
    if (brute_found != want_found || !same(brute, want)) ++bad_brute;
    float t_max[3];
    bool blocked[3];
    for (int k = 0; k < 3; ++k) {
      const float s = k == 0 ? 0.5f : k == 1 ? 2.0f : infinity<float>;
      t_max[k] = want_found ? want.t * s : s;
      blocked[k] = reference(tris, r, t_max[k]).triangle != UINT32_MAX;
    }
    for (const simd_level level : simd_levels()) {
      auto check = [&](const auto& bvh) {
        triangle_bvh_hit got;
        const bool found = bvh.intersect(r, 0.0f, infinity<float>, got, nullptr, level);
        if (found != want_found || !same(got, want)) ++bad_nearest;
        for (int k = 0; k < 3; ++k)
          if (bvh.occluded(r, 0.0f, t_max[k], nullptr, level) != blocked[k]) ++bad_any;
      };
      check(bvh8);
      check(bvh4);
      check(bvh8q);
    }
  }
  CHECK(bad_nearest == 0);
  CHECK(bad_brute == 0);
  CHECK(bad_any == 0);
  return hits;
}

std::vector<rayf> mixed_rays(rng& g, const aabb_t<float>& box, int n) {
  std::vector<rayf> rays;
  const vec3f c = box.center();
  const float radius = glm::length(box.extent());
  for (int i = 0; i < n; ++i) {
    if (i % 2 == 0) {
      const vec3f o = c + radius * random_unit(g);
      rays.emplace_back(o, random_in(g, box) - o);  // from outside, towards the box
    } else {
      rays.emplace_back(random_in(g, box), random_unit(g));  // from inside
    }
  }
  return rays;
}

std::vector<tri_f> float_triangles(const mesh& m) {
  std::vector<tri_f> tris;
  for (std::size_t i = 0; i < m.triangle_count(); ++i) {
    const triangle t = m.triangle(i);
    tris.push_back({vec3f(t.a), vec3f(t.b), vec3f(t.c)});
  }
  return tris;
}

}  // namespace

TEST_CASE("layout: 256-byte 8-wide and 128-byte 4-wide nodes, 160-byte blocks of 4 triangles, at most 60 bytes per teapot triangle") {
  static_assert(sizeof(triangle_bvh_node8) == 256 && alignof(triangle_bvh_node8) == 64);
  static_assert(sizeof(triangle_bvh_node4) == 128 && alignof(triangle_bvh_node4) == 64);
  static_assert(sizeof(packed_triangle) == 40 && sizeof(triangle4) == 160);
  MESSAGE("SIMD levels run here: " << simd_levels().size() << ", the best " << std::string(to_string(cpu_simd())));
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  for (const int divs : {4, 16}) {
    const mesh m = tessellate(patches, divs);
    const triangle_bvh bvh(m);
    const triangle_bvh4 bvh4(m);
    MESSAGE("teapot divs " << divs << ": " << m.triangle_count() << " triangles, " << bvh.node_count()
                           << " 8-wide nodes (" << bvh4.nodes().size() << " 4-wide), " << bvh.bytes_per_triangle()
                           << " bytes per triangle (" << bvh4.bytes_per_triangle() << "), depth " << bvh.depth());
    CHECK(bvh.input_count() == m.triangle_count());
    CHECK(bvh.bytes_per_triangle() <= 60.0);
    CHECK(bvh4.bytes_per_triangle() <= 60.0);
    // The 8-wide tree has fewer nodes (not half: a node over a small subtree has fewer than eight
    // children, as its 4-wide twin has fewer than four).
    CHECK(bvh.node_count() * 4 < bvh4.node_count() * 3);
    CHECK(bvh.depth() < bvh_max_depth);
    // The teapot's collapsed rows give zero-area triangles: left out, since never hit.
    CHECK(bvh.triangle_count() < m.triangle_count());
    CHECK(bvh.triangle_count() > m.triangle_count() * 9 / 10);
  }
}

TEST_CASE("SIMD levels: a level asked for is lowered to what this processor runs, never raised") {
  const simd_level best = cpu_simd();
  CHECK(usable_simd(simd_level::scalar) == simd_level::scalar);
  CHECK(usable_simd(simd_level::avx2) == best);
  CHECK(usable_simd(simd_level::sse) == (best == simd_level::scalar ? simd_level::scalar : simd_level::sse));
  CHECK(simd_levels().front() == simd_level::scalar);
  CHECK(simd_levels().back() == best);
}

TEST_CASE("the teapot at several divs: identical to brute force") {
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  rng g(21);
  for (const int divs : {1, 2, 5, 12}) {
    CAPTURE(divs);
    const mesh m = tessellate(patches, divs);
    const auto tris = float_triangles(m);
    const aabb_t<float> box{vec3f(m.bounds().lo), vec3f(m.bounds().hi)};
    const int hits = compare(tris, mixed_rays(g, box, 300));
    CHECK(hits > 100);
  }
}

TEST_CASE("quantized nodes: every child's box read back contains the box, at every scale") {
  // Random full nodes: boxes at scales 1e-30..1e30, far from the origin or across it, points,
  // zeros of both signs, subnormal sizes, boxes spanning nearly all of float, unused slots.
  rng g(11);
  long children = 0, wrong = 0;
  float max_growth = 0;  // of a box's extent, relative to its node's
  for (int it = 0; it < 20000; ++it) {
    bvh_node8 f{};
    const float scale = std::ldexp(1.0f, int(g.uniform() * 200) - 100);
    const float offset = g.uniform() < 0.3 ? 0.0f : float((g.uniform() - 0.5) * 1e30 * (g.uniform() < 0.5 ? 1 : 1e-25));
    for (int k = 0; k < 8; ++k) {
      for (int a = 0; a < 3; ++a) {
        float lo = offset + float(g.uniform() - 0.5) * scale, hi = lo + float(g.uniform()) * scale * float(g.uniform() < 0.2 ? 0 : 1);
        if (it % 97 == 0) lo = -0.0f, hi = 0.0f;
        if (it % 89 == 0) lo = -3e38f, hi = 3e38f;
        if (it % 83 == 0) lo = 1e-44f, hi = 3e-44f;  // subnormal
        f.box[a][k] = lo, f.box[3 + a][k] = std::max(lo, hi);
      }
      f.child[k] = std::uint32_t(k), f.count[k] = std::uint32_t(k % 3);
      if (g.uniform() < 0.15 && k > 0)  // an unused slot: an empty box
        for (int a = 0; a < 3; ++a) f.box[a][k] = infinity<float>, f.box[3 + a][k] = -infinity<float>;
    }
    wide_qnode8 q;
    REQUIRE_NOTHROW(quantize(f, q));
    for (int k = 0; k < 8; ++k) {
      const bool used = f.box[0][k] <= f.box[3][k];
      wrong += used != bool((q.used >> k) & 1u);
      if (!used) continue;
      ++children;
      wrong += q.child[k] != f.child[k] || q.count[k] != f.count[k];
      for (int a = 0; a < 3; ++a) {
        const float lo = detail::dequantize(q.q[a][k], q.scale[a], q.origin[a]);
        const float hi = detail::dequantize(q.q[3 + a][k], q.scale[a], q.origin[a]);
        wrong += !(lo <= f.box[a][k]) || !(hi >= f.box[3 + a][k]);
        float node_lo = infinity<float>, node_hi = -infinity<float>;
        for (int j = 0; j < 8; ++j)
          if (f.box[0][j] <= f.box[3][j]) node_lo = std::min(node_lo, f.box[a][j]), node_hi = std::max(node_hi, f.box[3 + a][j]);
        if (node_hi > node_lo && std::isfinite(node_hi - node_lo))
          max_growth = std::max(max_growth, ((hi - lo) - (f.box[3 + a][k] - f.box[a][k])) / (node_hi - node_lo));
      }
    }
  }
  // A leaf count that does not fit a byte is refused, not cut (bvh.hpp never builds one).
  bvh_node8 too_big{};
  too_big.box[0][0] = too_big.box[1][0] = too_big.box[2][0] = 0;
  too_big.count[0] = 256;
  wide_qnode8 q;
  CHECK_THROWS_WITH(quantize(too_big, q), doctest::Contains("at most 255"));
  MESSAGE(children << " children, largest growth of a box " << max_growth << " of its node's extent");
  CHECK(wrong == 0);
  CHECK(max_growth <= 2.0f / 255 * 2);  // a step of scale at each end, scale at most twice extent / 255
}

TEST_CASE("nodes are quantized only for a tree larger than eight L2 caches, or when asked") {
  CHECK(detail::l2_cache_bytes() >= 64 * 1024);
  CHECK(detail::quantize_above_bytes() == 8 * detail::l2_cache_bytes());
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  const mesh m = tessellate(patches, 8);  // 4,096 triangles, about 200 kB
  const triangle_bvh small(m);
  CHECK_FALSE(small.quantized());
  CHECK(small.node_count() == small.nodes().size());
  const triangle_bvh asked(m, quantized_options());
  CHECK(asked.quantized());
  CHECK(asked.nodes().empty());
  CHECK(asked.node_count() == small.node_count());  // the same tree
  CHECK(asked.bytes() < small.bytes());
  bvh_build_options full = triangle_bvh::default_options();
  full.quantize = 0;
  // Soups of small triangles whose full trees are just under and just over the threshold.
  rng g(5);
  std::vector<tri_f> soup;
  const auto grow_to = [&](std::size_t count) {
    while (soup.size() < count) {
      const vec3f p(float(g.uniform()), float(g.uniform()), float(g.uniform()));
      soup.push_back({p, p + vec3f(0.01f, 0, 0), p + vec3f(0, 0.01f, 0)});
    }
  };
  grow_to(detail::quantize_above_bytes() / 64);
  const triangle_bvh below(soup);
  CHECK(triangle_bvh(soup, full).bytes() <= detail::quantize_above_bytes());
  CHECK_FALSE(below.quantized());
  grow_to(detail::quantize_above_bytes() / 40);
  CHECK(triangle_bvh(soup, full).bytes() > detail::quantize_above_bytes());
  CHECK(triangle_bvh(soup).quantized());
  CHECK_FALSE(triangle_bvh(soup, full).quantized());
}

TEST_CASE("random soups, small and large triangles: identical to brute force") {
  rng g(8);
  const aabb_t<float> world{vec3f(-10), vec3f(10)};
  for (const int n : {1, 2, 9, 300, 3000}) {
    for (const float size : {0.5f, 5.0f}) {
      CAPTURE(n);
      CAPTURE(size);
      std::vector<tri_f> tris;
      for (int i = 0; i < n; ++i) {
        const vec3f c = random_in(g, world);
        tris.push_back({c + size * random_unit(g), c + size * random_unit(g), c + size * random_unit(g)});
      }
      const int hits = compare(tris, mixed_rays(g, world, 400));
      if (n >= 300) CHECK(hits > 10);
    }
  }
}

TEST_CASE("rays along the axes from origins in the planes of box faces") {
  // Integer coordinates: origins lie exactly in box faces, directions have zero components,
  // so the slab test meets 0 * inf = NaN and must keep the box closed.
  rng g(4);
  auto grid = [&] { return float(std::floor(g.uniform() * 9)); };
  std::vector<tri_f> tris;
  for (int i = 0; i < 500; ++i) {
    const vec3f a(grid(), grid(), grid());
    tris.push_back({a, a + vec3f(grid() - 4, grid() - 4, grid() - 4),
                    a + vec3f(grid() - 4, grid() - 4, grid() - 4)});
  }
  std::vector<rayf> rays;
  for (int i = 0; i < 900; ++i) {
    vec3f d(0);
    d[i % 3] = (i / 3) % 2 ? 1.0f : -1.0f;
    rays.emplace_back(vec3f(grid(), grid(), grid()) + 0.5f * vec3f(float(i % 2), 0, i % 5 == 0), d);
  }
  // Negative zeros: 1 / -0 = -inf, so the near side of that slab is hi (bvh_ray's sign bit);
  // taking the sign by d < 0 instead would make those slabs empty.
  for (int i = 0; i < 300; ++i) {
    vec3f d(-0.0f, -0.0f, -0.0f);
    d[i % 3] = i % 2 ? 1.0f : -1.0f;
    rays.emplace_back(vec3f(grid(), grid(), grid()), d);
    REQUIRE(std::signbit(rays.back().direction[(i + 1) % 3]));
  }
  CHECK(compare(tris, rays) > 50);
}

TEST_CASE("no triangles, one triangle, identical centroids, degenerate triangles") {
  const triangle_bvh none(std::vector<tri_f>{});
  triangle_bvh_hit h;
  CHECK(none.bytes() == 0);
  CHECK_FALSE(none.intersect(rayf({0, 0, 0}, {1, 0, 0}), 0.0f, infinity<float>, h));
  CHECK_FALSE(none.occluded(rayf({0, 0, 0}, {1, 0, 0}), 0.0f, infinity<float>));

  const triangle_bvh one(std::vector<tri_f>{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}});
  REQUIRE(one.intersect(rayf({0.25f, 0.5f, 2}, {0, 0, -1}), 0.0f, infinity<float>, h));
  CHECK(h.t == 2.0f);  // exact: short dyadic fractions
  CHECK(h.u == 0.25f);
  CHECK(h.v == 0.5f);
  CHECK(h.triangle == 0);
  CHECK_FALSE(one.intersect(rayf({0.25f, 0.5f, 2}, {0, 0, -1}), 0.0f, 2.0f, h));  // open interval
  CHECK_FALSE(one.occluded(rayf({0.25f, 0.5f, 2}, {0, 0, -1}), 0.0f, 2.0f));
  CHECK(one.occluded(rayf({0.25f, 0.5f, 2}, {0, 0, -1}), 0.0f, 2.5f));

  // 2000 copies of one triangle: the builder halves by count; every copy ties, index 0 wins.
  const std::vector<tri_f> copies(2000, tri_f{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const triangle_bvh same(copies);
  CHECK(same.depth() <= 1 + 9);
  REQUIRE(same.intersect(rayf({0.2f, 0.2f, 1}, {0, 0, -1}), 0.0f, infinity<float>, h));
  CHECK(h.triangle == 0);

  // Degenerate triangles (a point, a segment) and a NaN vertex are never hit, as in triangle.hpp.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<tri_f> bad{{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}},
                               {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}},
                               {{0, 0, 0}, {nan, 0, 0}, {0, 1, 0}},
                               {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}};
  const triangle_bvh with_bad(bad);
  CHECK(with_bad.triangle_count() == 1);
  REQUIRE(with_bad.intersect(rayf({0.1f, 0.1f, 1}, {0, 0, -1}), 0.0f, infinity<float>, h));
  CHECK(h.triangle == 3);
}

TEST_CASE("NaN rays hit nothing and visit nothing") {
  rng g(2);
  std::vector<tri_f> tris;
  for (int i = 0; i < 100; ++i)
    tris.push_back({random_in(g, {vec3f(-1), vec3f(1)}), random_in(g, {vec3f(-1), vec3f(1)}),
                    random_in(g, {vec3f(-1), vec3f(1)})});
  const triangle_bvh bvh(tris);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (const rayf& r : {rayf({nan, 0, 0}, {1, 0, 0}), rayf({0, 0, 0}, {nan, 0, 1}),
                        rayf({0, 0, 0}, {0, 0, 0})}) {
    bvh_stats st;
    triangle_bvh_hit h;
    CHECK_FALSE(bvh.intersect(r, 0.0f, infinity<float>, h, &st));
    CHECK_FALSE(bvh.occluded(r, 0.0f, infinity<float>, &st));
    CHECK_FALSE(bvh.intersect_brute_force(r, 0.0f, infinity<float>, h));
    CHECK(st.nodes == 0);
  }
}

TEST_CASE("statistics count box and triangle tests; any hit stops early") {
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  const mesh m = tessellate(patches, 8);
  const triangle_bvh bvh(m);
  const rayf r({0, 1.5f, 20}, {0, 0, -1});  // straight at the teapot's body
  bvh_stats nearest, any;
  triangle_bvh_hit h;
  REQUIRE(bvh.intersect(r, 0.0f, infinity<float>, h, &nearest));
  REQUIRE(bvh.occluded(r, 0.0f, infinity<float>, &any));
  CHECK(nearest.nodes >= std::uint64_t(bvh.depth()) / 2);
  CHECK(nearest.primitives < 200);  // of 4096: the point of a BVH
  CHECK(any.nodes <= nearest.nodes);
}

TEST_CASE("errata C10: log-like on the teapot, linear on slivers through one point") {
  // Counts of box and triangle tests, not times: deterministic.
  auto tests_per_ray = [](const triangle_bvh& bvh, const std::vector<rayf>& rays) {
    bvh_stats st;
    triangle_bvh_hit h;
    for (const rayf& r : rays) bvh.intersect(r, 0.0f, infinity<float>, h, &st);
    return double(st.nodes + st.primitives) / double(rays.size());
  };
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  rng g(6);
  const mesh small = tessellate(patches, 4), large = tessellate(patches, 16);  // 1k and 16k
  const aabb_t<float> box{vec3f(small.bounds().lo), vec3f(small.bounds().hi)};
  const auto rays = mixed_rays(g, box, 2000);
  const double a = tests_per_ray(triangle_bvh(small), rays), b = tests_per_ray(triangle_bvh(large), rays);
  MESSAGE("teapot: " << a << " tests per ray at 1k triangles, " << b << " at 16k");
  CHECK(b < 2 * a);  // 16 times the triangles, far less than twice the work

  // n slivers through the origin in random directions: every box overlaps every other.
  auto slivers = [&](int n) {
    std::vector<tri_f> tris;
    for (int i = 0; i < n; ++i) {
      const vec3f u = random_unit(g);
      tris.push_back({u, -u, 0.01f * random_unit(g)});
    }
    return triangle_bvh(tris);
  };
  std::vector<rayf> through_middle;
  for (int i = 0; i < 500; ++i) {
    const vec3f o(4 * float(g.uniform()) - 2, 4 * float(g.uniform()) - 2, 3);
    through_middle.emplace_back(o, 0.1f * vec3f(float(g.uniform()), float(g.uniform()), 0) - o);
  }
  const double s1 = tests_per_ray(slivers(256), through_middle);
  const double s4 = tests_per_ray(slivers(1024), through_middle);
  MESSAGE("slivers: " << s1 << " tests per ray at n = 256, " << s4 << " at 1024");
  CHECK(s4 > 3 * s1);  // four times n, about four times the work: O(n)
  CHECK(s4 > 1024);    // more tests than brute force's n
}

namespace {

// Rays aimed exactly at the points of a mesh's shared edges (every 1/8, in float) and at its
// interior vertices, from a direction that faces every triangle there (so no silhouette folds
// the surface over the point, where a ray may rightly pass by). Triangles share by position,
// not by index, so patch seams count too; degenerate triangles are left out, as by the BVH.
struct aimed_ray {
  vec3 target, direction;
};

std::vector<aimed_ray> aim_at_shared(const std::vector<tri_f>& tris, rng& g) {
  using key = std::array<float, 3>;
  auto k = [](const vec3f& p) { return key{p.x, p.y, p.z}; };
  std::map<key, std::vector<int>> at_vertex;
  std::map<std::pair<key, key>, std::vector<int>> at_edge;
  std::vector<vec3> normals(tris.size());
  for (int i = 0; i < int(tris.size()); ++i) {
    const tri_f& t = tris[i];
    const vec3 n = glm::cross(vec3(t.b) - vec3(t.a), vec3(t.c) - vec3(t.a));
    if (glm::cross(t.b - t.a, t.c - t.a) == vec3f(0) || glm::length(n) == 0) continue;
    normals[i] = glm::normalize(n);
    const std::array<vec3f, 3> v = {t.a, t.b, t.c};
    for (int j = 0; j < 3; ++j) {
      at_vertex[k(v[j])].push_back(i);
      const key a = k(v[j]), b = k(v[(j + 1) % 3]);
      at_edge[std::minmax(a, b)].push_back(i);
    }
  }
  auto facing = [&](const std::vector<int>& around, vec3& d) {  // false: no direction faces all
    vec3 sum(0);
    for (int i : around) sum += normals[i];
    if (glm::length(sum) == 0) return false;
    d = glm::normalize(glm::normalize(sum) + 0.2 * vec3(random_unit(g)));
    for (int i : around)
      if (glm::dot(d, normals[i]) < 0.05) return false;
    return true;
  };
  std::vector<aimed_ray> out;
  std::set<key> open;  // vertices on an edge not shared by exactly two triangles
  for (const auto& [e, around] : at_edge) {
    if (around.size() != 2) {
      open.insert(e.first);
      open.insert(e.second);
      continue;
    }
    vec3 d;
    if (!facing(around, d)) continue;
    const vec3 a(e.first[0], e.first[1], e.first[2]), b(e.second[0], e.second[1], e.second[2]);
    for (int s = 1; s < 8; ++s) out.push_back({a + (s / 8.0) * (b - a), d});
  }
  for (const auto& [v, around] : at_vertex) {
    vec3 d;
    if (!open.count(v) && facing(around, d)) out.push_back({vec3(v[0], v[1], v[2]), d});
  }
  return out;
}

struct crack_count {
  long rays = 0, bvh = 0, brute = 0, any = 0, different = 0;
  double worst_dt = 0;
};

// The mesh scaled by `scale` and moved by `shift` (then rounded to float), rays from `dist`
// times the scale away: cracks of the nearest-hit walk, of brute force and of occluded().
crack_count cracks(const std::vector<tri_f>& unit, double scale, const vec3& shift, double dist,
                   int stride, rng& g) {
  std::vector<tri_f> tris;
  for (const tri_f& t : unit)
    tris.push_back({vec3f(scale * vec3(t.a) + shift), vec3f(scale * vec3(t.b) + shift),
                    vec3f(scale * vec3(t.c) + shift)});
  const triangle_bvh bvh(tris);
  crack_count c;
  const std::vector<aimed_ray> aimed = aim_at_shared(tris, g);
  for (std::size_t i = 0; i < aimed.size(); i += std::size_t(stride)) {
    const aimed_ray& a = aimed[i];
    const vec3f target(a.target), o(a.target + dist * scale * a.direction);
    const rayf r(o, target - o);
    triangle_bvh_hit h, b;
    ++c.rays;
    const bool found = bvh.intersect(r, 0.0f, infinity<float>, h);
    const bool brute_found = bvh.intersect_brute_force(r, 0.0f, infinity<float>, b);
    c.bvh += found ? 0 : 1;
    c.brute += brute_found ? 0 : 1;
    c.any += bvh.occluded(r, 0.0f, infinity<float>) ? 0 : 1;
    c.different += found == brute_found && same(h, b) ? 0 : 1;
    if (found && brute_found && !same(h, b))
      c.worst_dt = std::max(c.worst_dt, double(std::abs(h.t - b.t)) / double(b.t));
  }
  return c;
}

std::vector<tri_f> fan_mesh(int n, float h) {
  std::vector<tri_f> tris;
  for (int k = 0; k < n; ++k) {
    auto rim = [&](int j) {
      const double th = 2 * pi<double> * j / n;
      return vec3f(vec3(std::cos(th), std::sin(th), 0));  // rounded once: shared exactly
    };
    tris.push_back({vec3f(0, 0, h), rim(k), rim((k + 1) % n)});
  }
  return tris;
}

std::vector<tri_f> grid_mesh(int n) {
  auto v = [&](int i, int j) {
    return vec3f(vec3(i, j, 0.37 * std::sin(i * 1.3 + j * 0.7)) / double(n));
  };
  std::vector<tri_f> tris;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      tris.push_back({v(i, j), v(i + 1, j), v(i + 1, j + 1)});
      tris.push_back({v(i, j), v(i + 1, j + 1), v(i, j + 1)});
    }
  return tris;
}

}  // namespace

TEST_CASE("watertight in float: no ray through a shared edge or vertex (fans, grids, teapot)") {
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  struct test_mesh {
    const char* what;
    std::vector<tri_f> tris;
    int stride;  // every stride-th aimed ray (brute force on the teapot is the slow part)
  };
  const std::vector<test_mesh> meshes = {
      {"fan of 48, cone", fan_mesh(48, 0.25f), 1},
      {"fan of 64, flat", fan_mesh(64, 0.0f), 1},
      {"grid 16x16", grid_mesh(16), 2},
      {"teapot divs 6", float_triangles(tessellate(patches, 6)), 7}};
  rng g(4242);
  for (const auto& [what, unit, stride] : meshes) {
    crack_count total;
    // Scales 1e-4 ... 1e4; at the coordinate origin and shifted 1e3 scales away (fewer fraction
    // bits); rays from 1, 100 and 1e4 sizes away.
    for (const double scale : {1e-4, 1e-2, 1.0, 1e2, 1e4})
      for (const double shift : {0.0, 1e3})
        for (const double dist : {1.0, 1e2, 1e4}) {
          const crack_count c = cracks(unit, scale, shift * scale * vec3(1, -2, 3), dist, stride, g);
          total.rays += c.rays;
          total.bvh += c.bvh;
          total.brute += c.brute;
          total.any += c.any;
          total.different += c.different;
          total.worst_dt = std::max(total.worst_dt, c.worst_dt);
        }
    MESSAGE(std::string(what) << ": " << total.rays << " rays at shared edges and vertices; cracks: BVH "
                 << total.bvh << ", brute force " << total.brute << ", occluded() "
                 << total.any << "; BVH != brute force: " << total.different << " (worst relative t difference " << total.worst_dt << ")");
    CHECK(total.rays > 1000);
    CHECK(total.bvh == 0);
    CHECK(total.brute == 0);
    CHECK(total.any == 0);
    CHECK(total.different == 0);
  }
}

TEST_CASE("blocks of four: the four-lane walk equals the scalar brute force in extreme cases") {
  // compare() checks the walks (their leaves four lanes at a time where SSE is there, at the SSE
  // and AVX2 levels) against the BVH's own brute force (the scalar test, one triangle at a time)
  // and triangle.hpp's intersect_watertight.
  rng g(31);
  auto soup = [&](int n, double scale, const vec3& shift, double size) {
    std::vector<tri_f> tris;
    for (int i = 0; i < n; ++i) {
      const vec3 c = shift + scale * vec3(random_unit(g));
      tris.push_back({vec3f(c + size * scale * vec3(random_unit(g))), vec3f(c + size * scale * vec3(random_unit(g))),
                      vec3f(c + size * scale * vec3(random_unit(g)))});
    }
    return tris;
  };
  auto rays_at = [&](const std::vector<tri_f>& tris, double reach, int n) {
    std::vector<rayf> rays;
    for (int i = 0; i < n; ++i) {
      const tri_f& t = tris[std::size_t(g.uniform() * double(tris.size()))];
      const double wa = 1.2 * g.uniform() - 0.1, wb = 1.2 * g.uniform() - 0.1;
      const vec3 target = vec3(t.a) + wa * (vec3(t.b) - vec3(t.a)) + wb * (vec3(t.c) - vec3(t.a));
      const vec3 o = target + reach * vec3(random_unit(g));
      rays.emplace_back(vec3f(o), vec3f(target - o));
    }
    return rays;
  };
  // Tiny, huge and far triangles. t's numerator is a product of three coordinates: beyond
  // scales of about 1e-12 and 1e12 it falls out of float's range (at 1e-30 the edge functions
  // themselves round to 0: the scalar test's double), and the float test finds no hit, in four
  // lanes as in one.
  for (const double scale : {1e-30, 1e-10, 1e-3, 1e10, 1e30}) {
    CAPTURE(scale);
    for (const vec3& shift : {vec3(0), vec3(1e4, -2e4, 3e4) * scale}) {
      const auto tris = soup(400, scale, shift, 0.3);
      const int hits = compare(tris, rays_at(tris, 3 * scale, 500));
      if (scale > 1e-20 && scale < 1e20) CHECK(hits > 100);
    }
  }
  // Exact ties: every triangle three times (one block, or two), the lowest index must win.
  {
    auto tris = soup(200, 1.0, vec3(0), 0.3);
    const std::size_t n = tris.size();
    for (std::size_t i = 0; i < n; ++i) tris.push_back(tris[i]), tris.push_back(tris[i]);
    const triangle_bvh bvh(tris);
    const auto rays = rays_at(tris, 3, 500);
    CHECK(compare(tris, rays) > 100);
    for (const rayf& r : rays) {
      triangle_bvh_hit h;
      if (bvh.intersect(r, 0.0f, infinity<float>, h)) CHECK(h.triangle < n);
    }
  }
  // Slivers (nearly segments) and grazing rays along a flat grid, in its plane and just off it.
  {
    std::vector<tri_f> tris = grid_mesh(12);
    for (tri_f& t : tris) t.a.z = t.b.z = t.c.z = 0.0f;
    for (int i = 0; i < 100; ++i) {
      const vec3f a = random_in(g, {vec3f(0), vec3f(1)}), b = random_in(g, {vec3f(0), vec3f(1)});
      tris.push_back({a, b, a + 1e-6f * (b - a) + vec3f(0, 0, 1e-7f)});
    }
    std::vector<rayf> rays;
    for (int i = 0; i < 600; ++i) {
      const float z = i % 3 == 0 ? 0.0f : (i % 3 == 1 ? 1e-7f : -1e-30f);
      const vec3f o(-0.5f, float(g.uniform()), z);
      rays.emplace_back(o, vec3f(1, float(g.uniform()) - 0.5f, i % 2 ? 0.0f : -z * 1e-3f));
      rays.emplace_back(random_in(g, {vec3f(0, 0, 1), vec3f(1, 1, 1)}), vec3f(float(g.uniform()), 0.5f, -1e-6f));
    }
    compare(tris, rays);
  }
  // Rays at float's edges: subnormal and infinite direction components, an origin near FLT_MAX.
  {
    const std::vector<tri_f> tris = {{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 0, -1}, {1, 0, -1}, {0, 1, -1}}};
    const float inf = infinity<float>;
    const std::vector<rayf> rays = {rayf({0.25f, 0.25f, 5}, {0, 0, -1e-39f}), rayf({0.25f, 0.25f, 5}, {1e-45f, 0, -1e-39f}),
                                    rayf({0.25f, 0.25f, 5}, {0, 0, -inf}), rayf({0.25f, 0.25f, 3e38f}, {0, 0, -1}),
                                    rayf({0.25f, 0.25f, 5}, {0, 1e-30f, -1}), rayf({0.25f, 0.25f, 5}, {0, 0, -1})};
    CHECK(compare(tris, rays) >= 2);
  }
}

// The generic BVH (bvh.hpp): the tree's invariants, and hits identical to brute force (same t,
// same primitive, same barycentrics) for nearest-hit and any-hit, on random triangle soups,
// random sphere sets, the tessellated teapot and the objects of a scene; plus the edge cases:
// rays from inside, rays along the axes, no primitives, one primitive, identical centroids,
// a depth-provoking input, NaN rays and primitives, bad options; and the float builder's
// vector binning against its plain pass.
#include <zraka/accel/bvh.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/geometry/triangle.hpp>
#include <zraka/io/bpt.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <vector>

using namespace zraka;

namespace {

template <class T> vec3_t<T> random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}
template <class T> vec3_t<T> random_in(rng& g, const aabb_t<T>& b) {
  const vec3 u(g.uniform(), g.uniform(), g.uniform());
  return b.lo + vec3_t<T>(u) * (b.hi - b.lo);
}

// One primitive's intersection: (index, ray, t_min, t_max, hit) -> bool, t in (t_min, t_max).
template <class T>
using intersector = std::function<bool(std::uint32_t, const ray_t<T>&, T, T, hit_t<T>&)>;

template <class T> struct nearest {
  bool found = false;
  std::uint32_t prim = UINT32_MAX;
  hit_t<T> h;
};

// The nearest hit as the smallest (t, index): a hit at exactly the current t counts for a lower
// index only. The primitive is asked for t up to and including t_max (nextafter), so that ties
// are seen; brute force in index order and the BVH in any order then agree exactly.
template <class T> auto nearest_test(const intersector<T>& isect, const ray_t<T>& r, T t_min,
                                     nearest<T>& out) {
  return [&isect, &r, t_min, &out](std::uint32_t i, T& t_max) {
    hit_t<T> h;
    if (!isect(i, r, t_min, std::nextafter(t_max, infinity<T>), h)) return false;
    if (h.t == t_max && out.found && i > out.prim) return false;
    out = {true, i, h};
    t_max = h.t;
    return true;
  };
}

template <class T>
nearest<T> brute_nearest(std::size_t n, const intersector<T>& isect, const ray_t<T>& r, T t_max) {
  nearest<T> out;
  auto test = nearest_test(isect, r, T(0), out);
  for (std::uint32_t i = 0; i < n; ++i) test(i, t_max);
  return out;
}
template <class T>
nearest<T> bvh_nearest(const bvh_t<T>& b, const intersector<T>& isect, const ray_t<T>& r, T t_max,
                       bvh_stats* st = nullptr) {
  nearest<T> out;
  const bool found = bvh_intersect(b, r, T(0), t_max, nearest_test(isect, r, T(0), out), st);
  CHECK(found == out.found);
  return out;
}
template <class T>
bool brute_any(std::size_t n, const intersector<T>& isect, const ray_t<T>& r, T t_max) {
  for (std::uint32_t i = 0; i < n; ++i) {
    hit_t<T> h;
    if (isect(i, r, T(0), t_max, h)) return true;
  }
  return false;
}
template <class T>
bool bvh_any(const bvh_t<T>& b, const intersector<T>& isect, const ray_t<T>& r, T t_max) {
  return bvh_occluded(b, r, T(0), t_max, [&](std::uint32_t i) {
    hit_t<T> h;
    return isect(i, r, T(0), t_max, h);
  });
}

// Compares BVH and brute force on every ray, nearest hit and any hit (to the nearest hit's
// distance scaled by 0.5 and 2, and unbounded). Returns the number of nearest hits.
template <class T>
int compare(const bvh_t<T>& b, std::size_t n, const intersector<T>& isect,
            const std::vector<ray_t<T>>& rays) {
  int hits = 0, mismatches = 0, any_mismatches = 0;
  for (const auto& r : rays) {
    const nearest<T> want = brute_nearest(n, isect, r, infinity<T>);
    const nearest<T> got = bvh_nearest(b, isect, r, infinity<T>);
    hits += want.found;
    // Exact equality: the same primitive's test on the same ray gives the same bits.
    if (got.found != want.found || got.prim != want.prim || got.h.t != want.h.t ||
        got.h.uv != want.h.uv)
      ++mismatches;
    for (const T s : {T(0.5), T(2), infinity<T>}) {
      const T t_max = want.found ? want.h.t * s : s;
      if (bvh_any(b, isect, r, t_max) != brute_any(n, isect, r, t_max)) ++any_mismatches;
    }
  }
  CHECK(mismatches == 0);
  CHECK(any_mismatches == 0);
  return hits;
}

// Every primitive in exactly one leaf, leaves within max_leaf_size, first child next to its
// parent, children's boxes inside the parent's, depth within the stack.
template <class T> void check_structure(const bvh_t<T>& b, std::size_t included, int max_leaf) {
  CHECK(b.order.size() == included);
  std::vector<int> seen(b.primitive_count, 0);
  std::size_t in_leaves = 0;
  for (std::size_t k = 0; k < b.nodes.size(); ++k) {
    const auto& n = b.nodes[k];
    if (n.leaf()) {
      CHECK(n.count <= max_leaf);
      for (std::uint32_t j = n.index; j < n.index + n.count; ++j) ++seen[b.order[j]];
      in_leaves += n.count;
    } else {
      REQUIRE(k + 1 < b.nodes.size());
      REQUIRE(n.index > k + 1);
      REQUIRE(n.index < b.nodes.size());
      for (const auto* c : {&b.nodes[k + 1], &b.nodes[n.index]}) {
        CHECK(n.box.contains(c->box.lo));
        CHECK(n.box.contains(c->box.hi));
      }
    }
  }
  CHECK(in_leaves == included);
  for (const std::uint32_t i : b.order) CHECK(seen[i] == 1);
  CHECK(b.depth < bvh_max_depth);
}

template <class T> aabb_t<T> box_of(const triangle_t<T>& t) {
  aabb_t<T> b;
  b.grow(t.a);
  b.grow(t.b);
  b.grow(t.c);
  return b;
}

template <class T> std::vector<triangle_t<T>> random_soup(rng& g, int n, T size) {
  std::vector<triangle_t<T>> tris;
  const aabb_t<T> world{vec3_t<T>(-10), vec3_t<T>(10)};
  for (int i = 0; i < n; ++i) {
    const vec3_t<T> c = random_in(g, world);
    tris.push_back({c + size * random_unit<T>(g), c + size * random_unit<T>(g),
                    c + size * random_unit<T>(g)});
  }
  return tris;
}

template <class T> intersector<T> triangles_isect(const std::vector<triangle_t<T>>& tris) {
  return [&tris](std::uint32_t i, const ray_t<T>& r, T t0, T t1, hit_t<T>& h) {
    return intersect(tris[i], r, t0, t1, h);
  };
}

template <class T> bvh_t<T> bvh_of(const std::vector<triangle_t<T>>& tris, bvh_build_options o = {}) {
  std::vector<aabb_t<T>> boxes;
  for (const auto& t : tris) boxes.push_back(box_of(t));
  return build_bvh(boxes, o);
}

// Rays from outside towards the box, and rays from inside in random directions.
template <class T> std::vector<ray_t<T>> mixed_rays(rng& g, const aabb_t<T>& box, int n) {
  std::vector<ray_t<T>> rays;
  const vec3_t<T> c = box.center();
  const T radius = glm::length(box.extent());
  for (int i = 0; i < n; ++i) {
    if (i % 2 == 0) {
      const vec3_t<T> o = c + radius * random_unit<T>(g);
      rays.emplace_back(o, random_in(g, box) - o);
    } else {
      rays.emplace_back(random_in(g, box), random_unit<T>(g));
    }
  }
  return rays;
}

}  // namespace

TEST_CASE_TEMPLATE("random triangle soups: nearest and any hit equal brute force", T, float,
                   double) {
  rng g(11);
  for (const int n : {1, 2, 7, 100, 2000}) {
    for (const T size : {T(0.3), T(4)}) {  // small, and large overlapping triangles
      CAPTURE(n);
      CAPTURE(size);
      const auto tris = random_soup<T>(g, n, size);
      const bvh_t<T> b = bvh_of(tris);
      check_structure(b, tris.size(), 4);
      const int hits = compare(b, tris.size(), triangles_isect(tris),
                               mixed_rays(g, aabb_t<T>{vec3_t<T>(-10), vec3_t<T>(10)}, 600));
      if (n >= 100 && size > 1) CHECK(hits > 30);  // the comparison saw real hits
      if (n == 2000) CHECK(hits > 30);
    }
  }
}

TEST_CASE_TEMPLATE("rays along the axes, on a grid where origins lie in box faces", T, float,
                   double) {
  // Integer vertices and integer origins: many rays start exactly in the plane of a box face
  // and run parallel to it (zero direction components: inverse direction +-inf, and 0 * inf).
  rng g(5);
  std::vector<triangle_t<T>> tris;
  auto grid = [&] { return T(std::floor(g.uniform() * 9)); };
  for (int i = 0; i < 400; ++i) {
    const vec3_t<T> a(grid(), grid(), grid());
    tris.push_back({a, a + vec3_t<T>(grid() - 4, grid() - 4, grid() - 4),
                    a + vec3_t<T>(grid() - 4, grid() - 4, grid() - 4)});
  }
  const bvh_t<T> b = bvh_of(tris);
  std::vector<ray_t<T>> rays;
  for (int i = 0; i < 600; ++i) {
    vec3_t<T> d(0);
    d[i % 3] = (i / 3) % 2 ? T(1) : T(-1);
    rays.emplace_back(vec3_t<T>(grid(), grid(), grid()) + T(0.5) * vec3_t<T>(i % 2, 0, i % 5 == 0), d);
  }
  const int hits = compare(b, tris.size(), triangles_isect(tris), rays);
  CHECK(hits > 50);
}

TEST_CASE_TEMPLATE("random sphere sets equal brute force", T, float, double) {
  rng g(7);
  for (const int n : {1, 3, 50, 1000}) {
    CAPTURE(n);
    std::vector<sphere_t<T>> spheres;
    std::vector<aabb_t<T>> boxes;
    for (int i = 0; i < n; ++i) {
      const sphere_t<T> s{random_in(g, aabb_t<T>{vec3_t<T>(-20), vec3_t<T>(20)}),
                          T(0.05 + 2 * g.uniform() * g.uniform())};
      spheres.push_back(s);
      // Padded by the rounding of c +- r, so the box surely holds the sphere the test sees.
      const vec3_t<T> pad = gamma<T>(2) * (glm::abs(s.center) + s.radius);
      boxes.push_back({s.center - s.radius - pad, s.center + s.radius + pad});
    }
    const bvh_t<T> b = build_bvh(boxes);
    check_structure(b, spheres.size(), 4);
    const intersector<T> isect = [&](std::uint32_t i, const ray_t<T>& r, T t0, T t1, hit_t<T>& h) {
      return intersect(spheres[i], r, t0, t1, h);
    };
    const int hits = compare(b, spheres.size(), isect,
                             mixed_rays(g, aabb_t<T>{vec3_t<T>(-20), vec3_t<T>(20)}, 400));
    if (n >= 50) CHECK(hits > 20);
  }
}

TEST_CASE("the teapot at several divs equals brute force, and visits few nodes") {
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  rng g(3);
  for (const int divs : {1, 3, 8}) {
    CAPTURE(divs);
    const mesh m = tessellate(patches, divs);
    std::vector<triangle> tris;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) tris.push_back(m.triangle(i));
    const bvh_t<double> b = bvh_of(tris);
    check_structure(b, tris.size(), 4);
    const auto rays = mixed_rays(g, m.bounds(), 200);
    const int hits = compare(b, tris.size(), triangles_isect(tris), rays);
    CHECK(hits > 50);
    if (divs == 8) {  // 4096 triangles: a ray tests a small fraction of them
      bvh_stats st;
      for (const auto& r : rays) bvh_nearest(b, triangles_isect(tris), r, infinity<double>, &st);
      CHECK(double(st.primitives) / rays.size() < 0.05 * tris.size());
    }
  }
}

TEST_CASE("the objects of a scene, through object_ref and intersect_object") {
  scene sc;
  const int mat = sc.add_material(material::lambertian(rgb(0.5f)));
  rng g(9);
  for (int i = 0; i < 40; ++i)
    sc.add(sphere{random_in(g, aabb{vec3(-5), vec3(5)}), 0.2 + g.uniform()}, mat);
  for (int i = 0; i < 20; ++i)
    sc.add(quad{random_in(g, aabb{vec3(-5), vec3(5)}), 2.0 * random_unit<double>(g),
                2.0 * random_unit<double>(g)},
           mat);
  std::vector<object_ref> objects;
  std::vector<aabb> boxes;
  for (int i = 0; i < int(sc.spheres.size()); ++i) {
    objects.push_back({shape_kind::sphere, i});
    const auto& s = sc.spheres[i].shape;
    const vec3 pad = gamma<double>(2) * (glm::abs(s.center) + s.radius);
    boxes.push_back({s.center - s.radius - pad, s.center + s.radius + pad});
  }
  for (int i = 0; i < int(sc.quads.size()); ++i) {
    objects.push_back({shape_kind::quad, i});
    const auto& q = sc.quads[i].shape;
    aabb b;
    for (const vec3& p : {q.corner, q.corner + q.u, q.corner + q.v, q.corner + q.u + q.v}) b.grow(p);
    const vec3 pad = gamma<double>(4) * (glm::abs(b.lo) + glm::abs(b.hi));
    boxes.push_back({b.lo - pad, b.hi + pad});
  }
  const bvh b = build_bvh(boxes);
  for (const auto& r : mixed_rays(g, aabb{vec3(-6), vec3(6)}, 300)) {
    scene_hit want;
    const bool found = nearest_hit(sc, r, want);
    double t_max = infinity<double>;
    hit h;
    std::uint32_t prim = UINT32_MAX;
    const bool got = bvh_intersect(b, r, 0.0, t_max, [&](std::uint32_t i, double& tm) {
      if (!intersect_object(sc, objects[i], r, 0.0, tm, h)) return false;
      tm = h.t;
      prim = i;
      return true;
    });
    REQUIRE(got == found);
    if (found) {
      CHECK(h.t == want.h.t);
      CHECK(objects[prim].kind == want.object.kind);
      CHECK(objects[prim].index == want.object.index);
    }
  }
}

TEST_CASE("no primitives, one primitive, primitives that can never be hit") {
  const intersector<double> none = [](std::uint32_t, const ray&, double, double, hit&) {
    FAIL("no primitive may be tested");
    return false;
  };
  const bvh empty = build_bvh(std::vector<aabb>{});
  CHECK(empty.empty());
  CHECK_FALSE(bvh_nearest(empty, none, ray({0, 0, 0}, {1, 0, 0}), infinity<double>).found);
  CHECK_FALSE(bvh_any(empty, none, ray({0, 0, 0}, {1, 0, 0}), infinity<double>));

  const std::vector<triangle> one{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}};
  const bvh b1 = bvh_of(one);
  REQUIRE(b1.nodes.size() == 1);
  CHECK(b1.nodes[0].count == 1);
  const auto got = bvh_nearest(b1, triangles_isect(one), ray({0.25, 0.25, 1}, {0, 0, -1}),
                               infinity<double>);
  CHECK(got.found);
  CHECK(got.h.t == 1.0);

  // NaN and empty boxes are left out of the tree (they could only spoil the binning).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<aabb> boxes{aabb{}, aabb{vec3(nan), vec3(1)}, aabb{vec3(0), vec3(1)}};
  const bvh b = build_bvh(boxes);
  CHECK(b.primitive_count == 3);
  REQUIRE(b.order.size() == 1);
  CHECK(b.order[0] == 2);
}

TEST_CASE("identical centroids: the builder halves by count and ends") {
  // 1000 copies of one triangle, and 1000 nested boxes with one centre: SAH finds no plane.
  std::vector<triangle> same(1000, triangle{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  const bvh b = bvh_of(same);
  check_structure(b, same.size(), 4);
  CHECK(b.depth <= 1 + 10);  // halving: ceil(log2(1000/4)) + 1 levels, and the root
  const auto got = bvh_nearest(b, triangles_isect(same), ray({0.2, 0.2, 1}, {0, 0, -1}),
                               infinity<double>);
  CHECK(got.found);
  CHECK(got.prim == 0);  // all tie at t = 1: the lowest index wins

  std::vector<aabb> nested;
  for (int i = 1; i <= 1000; ++i) nested.push_back({vec3(-i), vec3(i)});
  check_structure(build_bvh(nested), nested.size(), 4);
}

TEST_CASE("a depth-provoking input stays within the traversal stack") {
  // Centroids at 2^-k: each SAH split would peel off one primitive, a chain of depth n.
  std::vector<aabb> boxes;
  for (int k = 0; k < 300; ++k) {
    const double x = std::ldexp(1.0, -k);
    boxes.push_back({vec3(x, 0, 0), vec3(x, 1, 1)});
  }
  bvh_build_options o;
  o.max_leaf_size = 1;
  const bvh b = build_bvh(boxes, o);
  check_structure(b, boxes.size(), 1);
  CHECK(b.depth <= bvh_max_depth - 1);
  // Every box is hit by a ray along x: all 300 leaves are reached through the fixed stack.
  std::vector<int> tested(boxes.size(), 0);
  bvh_stats st;
  bvh_intersect(b, ray({-1, 0.5, 0.5}, {1, 0, 0}), 0.0, infinity<double>,
                [&](std::uint32_t i, double&) { return ++tested[i], false; }, &st);
  for (int k = 0; k < 300; ++k) CHECK(tested[k] == 1);
}

TEST_CASE("NaN and invalid rays hit nothing and test nothing") {
  rng g(1);
  const auto tris = random_soup<double>(g, 200, 3.0);
  const bvh b = bvh_of(tris);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  int calls = 0;
  auto count = [&](std::uint32_t, double&) { return ++calls, false; };
  for (const ray& r : {ray({nan, 0, 0}, {1, 0, 0}), ray({0, 0, 0}, {nan, 1, 0}),
                       ray({0, 0, 0}, {0, 0, 0}), ray({infinity<double>, 0, 0}, {1, 0, 0})}) {
    CHECK_FALSE(bvh_intersect(b, r, 0.0, infinity<double>, count));
    CHECK_FALSE(bvh_occluded(b, r, 0.0, infinity<double>, [&](std::uint32_t) { return ++calls, true; }));
  }
  CHECK(calls == 0);
  // A NaN t_max: every box comparison fails, nothing is tested.
  CHECK_FALSE(bvh_intersect(b, ray({0, 0, 0}, {1, 0, 0}), 0.0, nan, count));
  CHECK(calls == 0);
}

TEST_CASE("bad build options are refused with a message") {
  const std::vector<aabb> boxes{aabb{vec3(0), vec3(1)}};
  bvh_build_options o;
  o.bins = 1;
  CHECK_THROWS_WITH_AS(build_bvh(boxes, o), doctest::Contains("bins"), error);
  o = {};
  o.max_leaf_size = 0;
  CHECK_THROWS_WITH_AS(build_bvh(boxes, o), doctest::Contains("max_leaf_size"), error);
  o = {};
  for (const int block : {0, 256}) {
    o.leaf_block = block;
    CHECK_THROWS_WITH_AS(build_bvh(boxes, o), doctest::Contains("leaf_block"), error);
  }
  o = {};
  for (const int leaf : {0, 256}) {  // the triangle BVH's wide tree (collapse_by_cost)
    o.wide_leaf_size = leaf;
    CHECK_THROWS_WITH_AS(build_bvh(boxes, o), doctest::Contains("wide_leaf_size"), error);
  }
  o = {};
  for (const double cost : {-1.0, std::nan(""), infinity<double>}) {
    o.wide_node_cost = cost;
    CHECK_THROWS_WITH_AS(build_bvh(boxes, o), doctest::Contains("wide_node_cost"), error);
  }
  CHECK_THROWS_AS(build_bvh(boxes, std::vector<vec3>{}), error);
}

TEST_CASE("leaf_block: leaves priced by blocks fill their blocks, and still equal brute force") {
  // Triangle BVH leaves are tested four at a time (triangle_bvh.hpp): a leaf of 5 costs two
  // blocks, like one of 8. Priced so, the SAH leaves few lanes of the last block empty.
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  const mesh m = tessellate(patches, 8);
  std::vector<triangle> tris;
  for (std::size_t i = 0; i < m.triangle_count(); ++i) tris.push_back(m.triangle(i));
  auto empty_lanes = [](const bvh_t<double>& b) {
    std::size_t lanes = 0, used = 0;
    for (const auto& n : b.nodes)
      if (n.leaf()) lanes += 4 * ((n.count + 3u) / 4u), used += n.count;
    return double(lanes - used) / double(lanes);
  };
  bvh_build_options by_triangle;
  by_triangle.max_leaf_size = 16;
  by_triangle.traversal_cost = 3;
  bvh_build_options by_block = by_triangle;
  by_block.leaf_block = 4;
  const bvh_t<double> a = bvh_of(tris, by_triangle), b = bvh_of(tris, by_block);
  check_structure(b, tris.size(), 16);
  MESSAGE("empty lanes: priced by triangles " << empty_lanes(a) << ", by blocks of 4 " << empty_lanes(b));
  CHECK(empty_lanes(b) < 0.06);
  CHECK(empty_lanes(b) < 0.5 * empty_lanes(a));
  rng g(12);
  CHECK(compare(b, tris.size(), triangles_isect(tris), mixed_rays(g, m.bounds(), 200)) > 50);
  // A block as large as a leaf: every leaf costs one test, so only the traversal cost and
  // max_leaf_size bound the leaves.
  bvh_build_options one_block = by_triangle;
  one_block.leaf_block = 16;
  check_structure(bvh_of(tris, one_block), tris.size(), 16);
}

TEST_CASE_TEMPLATE("leaf_block: a leaf of n costs ceil(n / b) tests, b a power of two or not", T, float, double) {
  // Eight unit cubes in a row (x from 0 to 8). Worked out by hand with the SAH of bvh.hpp:
  // the whole row has area 34, a row of k cubes 2 (2k + 1).
  std::vector<aabb_t<T>> boxes;
  for (int i = 0; i < 8; ++i) boxes.push_back({vec3_t<T>(T(i), 0, 0), vec3_t<T>(T(i + 1), 1, 1)});
  auto leaves = [&](int block, double trav) {
    bvh_build_options o;
    o.max_leaf_size = 8;
    o.leaf_block = block;
    o.traversal_cost = trav;
    std::vector<int> counts;
    for (const auto& n : build_bvh(boxes, o).nodes)
      if (n.leaf()) counts.push_back(n.count);
    return counts;
  };
  // b = 4 (a shift): one leaf costs 34 * 2 = 68; the best split, 4 | 4, 34 C_trav + 18 + 18.
  CHECK(leaves(4, 1.0) == std::vector<int>{8});       // 68 <= 70
  CHECK(leaves(4, 0.9) == std::vector<int>{4, 4});    // 66.6 < 68
  // b = 3 (a division): one leaf costs 34 * 3 = 102; 3 | 5 costs 34 + 14 + 22 * 2 = 92, and
  // the five left over stay a leaf (22 * 2 = 44 against 22 + 10 + 14 = 46).
  CHECK(leaves(3, 1.0) == std::vector<int>{3, 5});
}
TEST_CASE("vector binning builds the same float tree as the plain pass") {
  // bin_primitives<true> grows each bin's bounds four lanes at a time; the tree must not move.
  // Boxes of every kind: the teapot's triangles, flat and point boxes, one repeated centroid,
  // and sizes from 1e-30 to 1e30 far from the origin.
  const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
  const mesh m = tessellate(patches, 8);
  std::vector<aabb_t<float>> boxes;
  for (std::size_t i = 0; i < m.triangle_count(); ++i) {
    const aabb b = box_of(m.triangle(i));
    boxes.push_back({vec3_t<float>(b.lo), vec3_t<float>(b.hi)});
  }
  rng g(77);
  for (int i = 0; i < 3000; ++i) {
    const float size = std::ldexp(1.0f, int(g.uniform() * 200) - 100);
    const vec3_t<float> c = vec3_t<float>(float(1e6 * (g.uniform() - 0.5)), float(g.uniform()), 0.0f);
    vec3_t<float> e(size * float(g.uniform()), size * float(g.uniform()), size * float(g.uniform()));
    if (i % 7 == 0) e.y = 0;                // flat
    if (i % 11 == 0) e = vec3_t<float>(0);  // a point
    boxes.push_back({c - e, c + e});
  }
  for (int i = 0; i < 100; ++i) boxes.push_back({vec3_t<float>(-1.0f * float(i)), vec3_t<float>(float(i))});
  for (const int bins : {2, 16, 64}) {
    bvh_build_options vec, plain;
    vec.bins = plain.bins = bins;
    plain.vector_binning = false;
    const bvh_t<float> a = build_bvh(boxes, vec), b = build_bvh(boxes, plain);
    CAPTURE(bins);
    CHECK(a.order == b.order);
    CHECK(a.depth == b.depth);
    REQUIRE(a.nodes.size() == b.nodes.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.nodes.size(); ++i) {
      const auto &x = a.nodes[i], &y = b.nodes[i];
      differ += !(x.box.lo == y.box.lo && x.box.hi == y.box.hi && x.index == y.index &&
                  x.count == y.count && x.axis == y.axis);
    }
    CHECK(differ == 0);
  }
}

// The wide BVH (wide_bvh.hpp): float boxes that contain the exact ones (rounded outward, for far,
// huge and tiny geometry), and hits identical to the readable binary traversal (bvh.hpp's
// bvh_intersect, the book's listing) and to brute force: same t, same primitive, nearest and any
// hit, in float and double, on random rays, grazing rays along box faces, rays from inside boxes,
// flat boxes, rays with zero, tiny, infinite and NaN direction components; the scene's object
// BVH over every kind of object; the depth limit; no allocation per ray.
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/wide_bvh.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/geometry/triangle.hpp>
#include <zraka/geometry/user_shape.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <memory>
#include <new>
#include <vector>

// Every allocation of this program is counted, so a test can show that a traversal makes none.
// (GCC sees free() on memory from operator new once both are inlined and warns; here they are
// the replaced pair, malloc and free, so that is what is meant.)
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
namespace {
std::atomic<long> allocations{0};
}
void* operator new(std::size_t n) {
  ++allocations;
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }

using namespace zraka;

namespace {

template <class T> vec3_t<T> random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}

// A world of triangles, some of them flat along an axis (a box of zero thickness), placed about
// `centre` at scale `size`.
template <class T> struct world {
  std::vector<triangle_t<T>> tris;
  std::vector<aabb_t<T>> boxes;
  aabb_t<T> bounds;
};
template <class T> world<T> random_world(rng& g, int n, vec3_t<T> centre, T size) {
  world<T> w;
  for (int i = 0; i < n; ++i) {
    const vec3_t<T> c = centre + size * T(10) * vec3_t<T>(vec3(2 * g.uniform() - 1, 2 * g.uniform() - 1, 2 * g.uniform() - 1));
    triangle_t<T> t{c + size * random_unit<T>(g), c + size * random_unit<T>(g), c + size * random_unit<T>(g)};
    if (i % 5 == 0) t.a.z = t.b.z = t.c.z = c.z;  // flat in z
    if (i % 7 == 0) t.a.x = t.b.x = t.c.x = c.x;  // flat in x
    if (t.normal() == vec3_t<T>(0)) continue;
    aabb_t<T> b;
    for (const auto& p : {t.a, t.b, t.c}) b.grow(p);
    w.tris.push_back(t);
    w.boxes.push_back(b);
    w.bounds.grow(b);
  }
  return w;
}

template <class T> struct first_hit {
  bool hit = false;
  std::uint32_t prim = UINT32_MAX;
  T t = infinity<T>;
};

// The nearest hit as the smallest (t, index), the order of the walk being free: the primitive is
// asked for t up to and including t_max, and a tie goes to the lower index.
template <class T> auto nearest_test(const world<T>& w, const ray_t<T>& r, first_hit<T>& out) {
  return [&w, &r, &out](std::uint32_t i, T& t_max) {
    hit_t<T> h;
    if (!intersect(w.tris[i], r, T(0), std::nextafter(t_max, infinity<T>), h)) return false;
    if (h.t == t_max && out.hit && i > out.prim) return false;
    out = {true, i, h.t};
    t_max = h.t;
    return true;
  };
}

// Compares the wide walk with the binary walk and with brute force on every ray: nearest hit, and
// any hit up to half, twice and infinitely the nearest distance. Returns the number of hits.
template <class T> int compare(const world<T>& w, const std::vector<ray_t<T>>& rays) {
  const bvh_t<T> b = build_bvh(w.boxes);
  const wide_bvh wb = make_wide_bvh(b);
  int hits = 0, mismatches = 0, any_mismatches = 0;
  for (const auto& r : rays) {
    first_hit<T> scalar, wide, brute;
    const bool s = bvh_intersect(b, r, T(0), infinity<T>, nearest_test(w, r, scalar));
    const bool v = wide_intersect(wb, r, T(0), infinity<T>, nearest_test(w, r, wide));
    T t_max = infinity<T>;
    auto brute_test = nearest_test(w, r, brute);
    for (std::uint32_t i = 0; i < w.tris.size(); ++i) brute_test(i, t_max);
    hits += brute.hit;
    if (s != scalar.hit || v != wide.hit || wide.hit != scalar.hit || wide.prim != scalar.prim ||
        wide.t != scalar.t || wide.prim != brute.prim || wide.t != brute.t)
      ++mismatches;
    for (const T f : {T(0.5), T(2), infinity<T>}) {
      const T limit = brute.hit ? brute.t * f : f;
      auto blocks = [&](std::uint32_t i) {
        hit_t<T> h;
        return intersect(w.tris[i], r, T(0), limit, h);
      };
      if (wide_occluded(wb, r, T(0), limit, blocks) != bvh_occluded(b, r, T(0), limit, blocks)) ++any_mismatches;
    }
  }
  CHECK(mismatches == 0);
  CHECK(any_mismatches == 0);
  return hits;
}

// Random rays from outside aimed into the world, rays from inside, grazing rays along the faces
// of primitives' boxes (origin in the face's plane, direction in it: the 0 * inf case), and rays
// along the axes.
template <class T> std::vector<ray_t<T>> mixed_rays(rng& g, const world<T>& w, int n) {
  std::vector<ray_t<T>> rays;
  const vec3_t<T> c = w.bounds.center(), e = w.bounds.extent();
  auto in_box = [&](const aabb_t<T>& b) {
    return b.lo + vec3_t<T>(vec3(g.uniform(), g.uniform(), g.uniform())) * (b.hi - b.lo);
  };
  for (int i = 0; i < n; ++i) {
    const vec3_t<T> outside = c + e * random_unit<T>(g);
    rays.emplace_back(outside, in_box(w.bounds) - outside);
    rays.emplace_back(in_box(w.bounds), random_unit<T>(g));
    const aabb_t<T>& b = w.boxes[std::size_t(g.uniform() * double(w.boxes.size())) % w.boxes.size()];
    const int a = int(g.uniform() * 3) % 3;
    vec3_t<T> o = in_box(b) - e;  // in the plane x[a] = lo[a] of a primitive's box, from far off
    o[a] = g.uniform() < 0.5 ? b.lo[a] : b.hi[a];
    vec3_t<T> d = random_unit<T>(g);
    d[a] = T(0);
    if (i % 2) d[a] = -T(0);
    rays.emplace_back(o, d);
    vec3_t<T> axis(0);
    axis[(a + 1) % 3] = i % 4 < 2 ? T(1) : T(-1);
    vec3_t<T> p = in_box(b);
    p[(a + 1) % 3] = c[(a + 1) % 3] - axis[(a + 1) % 3] * e[(a + 1) % 3];
    rays.emplace_back(p, axis);
    rays.emplace_back(in_box(b), random_unit<T>(g));  // from inside a primitive's box
  }
  return rays;
}

}  // namespace

TEST_CASE("float_down and float_up bracket a value, also beyond float's range") {
  CHECK(float_down(0.1) < 0.1);
  CHECK(double(float_up(0.1)) > 0.1);
  CHECK(std::nextafter(float_down(0.1), 1.0f) == float_up(0.1));
  CHECK(float_down(0.5) == 0.5f);
  CHECK(float_up(0.5) == 0.5f);
  CHECK(float_down(1e300) == std::numeric_limits<float>::max());
  CHECK(float_up(1e300) == infinity<float>);
  CHECK(float_down(-1e300) == -infinity<float>);
  CHECK(float_up(-1e300) == -std::numeric_limits<float>::max());
  CHECK(float_down(1e-50) == 0.0f);
  CHECK(float_up(1e-50) == std::numeric_limits<float>::denorm_min());
  CHECK(float_up(-1e-50) == 0.0f);
  CHECK(float_up(infinity<double>) == infinity<float>);
  CHECK(float_down(0.3f) == 0.3f);  // a float stays as it is
}

TEST_CASE_TEMPLATE("wide boxes contain the exact boxes: near, far, huge and tiny geometry", T, float, double) {
  rng g(3);
  const bool dbl = sizeof(T) == 8;  // far: 1e12 in double, 1e5 in float
  for (const auto& [centre, size] : std::vector<std::pair<vec3_t<T>, T>>{
           {vec3_t<T>(0), T(1)},
           {vec3_t<T>(T(dbl ? 1e12 : 1e5), T(-3e3), T(7)), T(1)},
           {vec3_t<T>(0), T(dbl ? 1e100 : 1e9)},  // in double beyond float's range
           {vec3_t<T>(0), T(dbl ? 1e-30 : 1e-5)}}) {
    const world<T> w = random_world<T>(g, 300, centre, size);
    const bvh_t<T> b = build_bvh(w.boxes);
    const wide_bvh wb = make_wide_bvh(b);
    REQUIRE_FALSE(wb.empty());
    // Walk the wide tree: each primitive is in exactly one leaf slot whose box contains it.
    std::vector<int> seen(w.boxes.size(), 0);
    std::vector<std::uint32_t> todo{0};
    int bad = 0;
    while (!todo.empty()) {
      const bvh_node4& n = wb.nodes[todo.back()];
      todo.pop_back();
      for (int k = 0; k < 4; ++k) {
        if (!(n.box[0][k] <= n.box[3][k])) continue;  // unused
        if (n.count[k] == 0) {
          todo.push_back(n.child[k]);
          continue;
        }
        for (std::uint32_t j = n.child[k]; j < n.child[k] + n.count[k]; ++j) {
          const std::uint32_t i = wb.order[j];
          ++seen[i];
          for (int a = 0; a < 3; ++a)
            bad += !(T(n.box[a][k]) <= w.boxes[i].lo[a] && w.boxes[i].hi[a] <= T(n.box[3 + a][k]));
        }
      }
    }
    CHECK(bad == 0);
    for (const int s : seen) CHECK(s == 1);
    const int hits = compare(w, mixed_rays(g, w, 200));
    MESSAGE(w.tris.size() << " triangles at scale " << size << ": " << hits << " hits");
    CHECK(hits > 50);  // hits, not only misses, compared
  }
}

TEST_CASE_TEMPLATE("wide and binary traversal find the same hits", T, float, double) {
  rng g(7);
  const world<T> w = random_world<T>(g, 2000, vec3_t<T>(0), T(0.5));
  const int hits = compare(w, mixed_rays(g, w, 800));
  CHECK(hits > 1000);  // most rays hit something: the comparison is not of misses
}

TEST_CASE_TEMPLATE("rays with zero, tiny, infinite or NaN direction components", T, float, double) {
  rng g(11);
  const world<T> w = random_world<T>(g, 500, vec3_t<T>(0), T(1));
  // 1/tiny overflows float (in double a component that small is still exact for the binary walk).
  const T tiny = sizeof(T) == 8 ? T(1e-40) : std::numeric_limits<T>::denorm_min() * T(64);
  const T nan = std::numeric_limits<T>::quiet_NaN();
  std::vector<ray_t<T>> rays;
  for (int i = 0; i < 200; ++i) {
    const vec3_t<T> o = w.bounds.center() + T(5) * random_unit<T>(g);
    const vec3_t<T> d = w.bounds.center() - o;
    rays.emplace_back(o, vec3_t<T>(d.x, d.y, T(0)));
    rays.emplace_back(o, vec3_t<T>(d.x, -T(0), tiny));
    rays.emplace_back(o, vec3_t<T>(d.x, d.y, i % 2 ? tiny : -tiny));
    ray_t<T> r(o, d);  // an infinite component, set after the constructor (which would refuse it)
    r.direction.x = i % 2 ? infinity<T> : -infinity<T>;
    rays.push_back(r);
  }
  const int hits = compare(w, rays);
  CHECK(hits > 50);
  // A ray whose reciprocal direction leaves float's range is not exact: it visits every leaf.
  CHECK_FALSE(box4_ray(ray_t<T>(vec3_t<T>(0), vec3_t<T>(1, 0, tiny))).exact);
  CHECK(box4_ray(ray_t<T>(vec3_t<T>(0), vec3_t<T>(1, 0, -T(0)))).exact);
  // NaN and infinite directions, a NaN origin, a NaN t_max: no hit, no primitive tested.
  const bvh_t<T> b = build_bvh(w.boxes);
  const wide_bvh wb = make_wide_bvh(b);
  int calls = 0;
  auto count = [&](std::uint32_t, T&) { return ++calls, false; };
  ray_t<T> nan_direction;
  nan_direction.direction = vec3_t<T>(nan, 1, 0);
  for (const ray_t<T>& r : {ray_t<T>(vec3_t<T>(nan, 0, 0), vec3_t<T>(1, 0, 0)), nan_direction,
                            ray_t<T>(vec3_t<T>(0), vec3_t<T>(0))}) {
    CHECK_FALSE(wide_intersect(wb, r, T(0), infinity<T>, count));
    CHECK_FALSE(wide_occluded(wb, r, T(0), infinity<T>, [&](std::uint32_t) { return ++calls, true; }));
  }
  CHECK_FALSE(wide_intersect(wb, ray_t<T>(vec3_t<T>(0), vec3_t<T>(1, 0, 0)), T(0), nan, count));
  CHECK(calls == 0);
}

TEST_CASE("a depth-provoking input: every leaf reached; a tree deeper than the stack is refused") {
  std::vector<aabb> boxes;  // centroids at 2^-k: SAH would build a chain (bvh.hpp halves instead)
  for (int k = 0; k < 300; ++k) {
    const double x = std::ldexp(1.0, -k);
    boxes.push_back({vec3(x, 0, 0), vec3(x, 1, 1)});
  }
  bvh_build_options o;
  o.max_leaf_size = 1;
  const bvh b = build_bvh(boxes, o);
  const wide_bvh wb = make_wide_bvh(b);
  std::vector<int> tested(boxes.size(), 0);
  wide_intersect(wb, ray({-1, 0.5, 0.5}, {1, 0, 0}), 0.0, infinity<double>,
                 [&](std::uint32_t i, double&) { return ++tested[i], false; });
  for (int k = 0; k < 300; ++k) CHECK(tested[std::size_t(k)] == 1);

  bvh deep = b;  // claims more levels than the traversal stack holds
  deep.depth = bvh_max_depth + 1;
  CHECK_THROWS_WITH_AS(make_wide_bvh(deep), doctest::Contains("levels deep"), error);
}

TEST_CASE("no BVH, a single primitive (a root leaf)") {
  const wide_bvh none = make_wide_bvh(build_bvh(std::vector<aabb>{}));
  CHECK(none.empty());
  CHECK_FALSE(wide_intersect(none, ray({0, 0, 0}, {1, 0, 0}), 0.0, infinity<double>,
                             [](std::uint32_t, double&) { return true; }));
  const wide_bvh one = make_wide_bvh(build_bvh(std::vector<aabb>{aabb{vec3(1), vec3(2)}}));
  REQUIRE(one.nodes.size() == 1);
  int calls = 0;
  auto count = [&](std::uint32_t i, double&) { return ++calls, i == 0; };
  CHECK(wide_intersect(one, ray({0, 1.5, 1.5}, {1, 0, 0}), 0.0, infinity<double>, count));
  CHECK_FALSE(wide_intersect(one, ray({0, 1.5, 1.5}, {-1, 0, 0}), 0.0, infinity<double>, count));
  CHECK(calls == 1);
}

namespace {
// A user shape: a ball, through the sphere's own test.
template <class T> struct ball final : user_shape_t<T> {
  sphere_t<T> s;
  explicit ball(sphere_t<T> s_) : s(s_) {}
  std::string name() const override { return "ball"; }
  aabb_t<T> bounds() const override { return {s.center - vec3_t<T>(s.radius), s.center + vec3_t<T>(s.radius)}; }
  bool intersect(const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h) const override {
    return zraka::intersect(s, r, t_min, t_max, h);
  }
};
}  // namespace

TEST_CASE_TEMPLATE("the scene's object BVH: every kind of object, hits as the binary walk finds them", T, float, double) {
  rng g(5);
  scene_t<T> sc;
  const int m = sc.add_material(material::lambertian(rgb(0.5f)));
  auto at = [&] { return vec3_t<T>(vec3(8 * g.uniform() - 4, 8 * g.uniform() - 4, 8 * g.uniform() - 4)); };
  for (int i = 0; i < 40; ++i) {
    sc.add(sphere_t<T>{at(), T(0.1 + 0.4 * g.uniform())}, m);
    const vec3_t<T> c = at();
    // Axis-aligned quads (flat boxes), as a Cornell box is made of, and tilted ones.
    sc.add(parallelogram_t<T>{c, vec3_t<T>(T(0.7), 0, 0), i % 2 ? vec3_t<T>(0, T(0.5), 0) : random_unit<T>(g)}, m);
    sc.add(triangle_t<T>{at(), at(), at()}, m);
    sc.add(std::make_shared<const ball<T>>(sphere_t<T>{at(), T(0.3)}), m);
  }
  mesh_t<T> grid;  // a mesh: a bent grid, one object with its own triangle BVH
  for (int y = 0; y <= 8; ++y)
    for (int x = 0; x <= 8; ++x) grid.positions.push_back(vec3_t<T>(T(x) - 4, T(y) - 4, T(0.1) * T((x * y) % 5)));
  for (std::uint32_t y = 0; y < 8; ++y)
    for (std::uint32_t x = 0; x < 8; ++x) {
      const std::uint32_t i = y * 9 + x;
      grid.triangles.push_back({i, i + 1, i + 10});
      grid.triangles.push_back({i, i + 10, i + 9});
    }
  sc.add(grid, m);
  sc.add(plane_t<T>{vec3_t<T>(0, 0, -5), vec3_t<T>(0, 0, 1)}, m);
  REQUIRE(sc.build_acceleration());
  REQUIRE(sc.has_object_bvh());
  int hits = 0, mismatches = 0, shadow_mismatches = 0;
  for (int i = 0; i < 3000; ++i) {
    const vec3_t<T> o = i % 3 ? T(8) * random_unit<T>(g) : at();  // from outside, or from among the objects
    vec3_t<T> d = i % 3 ? at() - o : random_unit<T>(g);
    if (i % 10 == 0) d.z = T(0);  // grazing the axis-aligned quads' planes
    const ray_t<T> r(o, d);
    scene_hit_t<T> got;
    const bool found = nearest_hit(sc, r, got);
    // The binary walk over the same objects (planes first, as nearest_hit does).
    hit_t<T> h;
    std::uint32_t tri = 0;
    T t_max = infinity<T>;
    object_ref best{shape_kind::sphere, -1};
    if (intersect_object(sc, {shape_kind::plane, 0}, r, T(0), t_max, h, tri)) t_max = h.t, best = {shape_kind::plane, 0};
    bvh_intersect(sc.accel.tree, r, T(0), t_max, [&](std::uint32_t k, T& tm) {
      if (!intersect_object(sc, sc.accel.objects[k], r, T(0), tm, h, tri)) return false;
      tm = h.t;
      best = sc.accel.objects[k];
      return true;
    });
    hits += found;
    if (found != (best.index >= 0) ||
        (found && (got.h.t != h.t || !(got.object == best) || (best.kind == shape_kind::mesh && got.triangle != tri))))
      ++mismatches;
    const T limit = found ? got.h.t * T(i % 2 ? 0.999 : 1.001) : T(100);
    const bool blocked = bvh_occluded(sc.accel.tree, r, T(0), limit, [&](std::uint32_t k) {
      return object_blocks(sc, sc.accel.objects[k], r, limit);
    }) || object_blocks(sc, {shape_kind::plane, 0}, r, limit);
    if (occluded(sc, segment_t<T>{r, limit}) != blocked) ++shadow_mismatches;
  }
  CHECK(hits > 1500);
  CHECK(mismatches == 0);
  CHECK(shadow_mismatches == 0);
}

TEST_CASE("a traversal allocates nothing") {
  rng g(9);
  const world<double> w = random_world<double>(g, 1000, vec3(0), 0.5);
  const wide_bvh wb = make_wide_bvh(build_bvh(w.boxes));
  const auto rays = mixed_rays(g, w, 100);
  const long before = allocations.load();
  int hits = 0;
  for (const ray& r : rays) {
    first_hit<double> f;
    hits += wide_intersect(wb, r, 0.0, infinity<double>, nearest_test(w, r, f));
    hits += wide_occluded(wb, r, 0.0, 10.0, [&](std::uint32_t i) {
      hit h;
      return intersect(w.tris[i], r, 0.0, 10.0, h);
    });
  }
  CHECK(allocations.load() == before);
  CHECK(hits > 100);
}

// The ray's preparation for the four-box test works without branches (wide_bvh.hpp); on every
// combination of special components it keeps its contract: valid for a finite origin and a
// non-zero direction without NaN; exact when each non-zero component's reciprocal is in float's
// normal range; the near row by the sign bit; the origin rounded so that each slab only grows
// (a float origin as it is).
TEST_CASE_TEMPLATE("the box test's ray setup, on special components", T, float, double) {
  const T big = std::numeric_limits<T>::max(), tiny = std::numeric_limits<T>::denorm_min();
  const T nan = std::numeric_limits<T>::quiet_NaN();
  const T values[] = {T(0), -T(0), T(1), T(-1), T(0.1), T(-3), tiny, -tiny, big, -big, T(1e-39), infinity<T>,
                      -infinity<T>, nan};
  int checked = 0;
  for (const T x : values)
    for (const T y : values)
      for (const T z : values)
        for (const T o : {T(0.1), T(-0), big, nan}) {
          ray_t<T> r(vec3_t<T>(o, T(2), T(-0.3)), vec3_t<T>(1, 0, 0));
          r.direction = vec3_t<T>(x, y, z);  // set after the constructor, which refuses some
          const box4_ray b(r);
          const T d[3] = {x, y, z};
          const T origin[3] = {o, T(2), T(-0.3)};
          const bool any_nan = std::isnan(x) || std::isnan(y) || std::isnan(z);
          const bool nonzero = x != T(0) || y != T(0) || z != T(0);
          REQUIRE(b.valid == (std::isfinite(o) && nonzero && !any_nan));
          bool exact = true;
          for (int a = 0; a < 3; ++a) {
            const T inv = std::abs(T(1) / d[a]);
            if (d[a] != T(0) && !(inv >= T(std::numeric_limits<float>::min()) &&
                                  inv <= T(std::numeric_limits<float>::max())))
              exact = false;
            const bool negative = std::signbit(d[a]);
            REQUIRE(b.near_row[a] == (negative ? 3 + a : a));
            REQUIRE(b.far_row[a] == (negative ? a : 3 + a));
            REQUIRE(std::bit_cast<std::uint32_t>(b.inv_direction[a]) ==
                    std::bit_cast<std::uint32_t>(static_cast<float>(T(1) / d[a])));
            if (std::isnan(origin[a])) continue;
            // The near plane's t may only fall, the far plane's only rise: the origin moves
            // towards the far side for the first and towards the near side for the second.
            const T near_o = T(b.near_origin[a]), far_o = T(b.far_origin[a]);
            REQUIRE((negative ? near_o <= origin[a] : near_o >= origin[a]));
            REQUIRE((negative ? far_o >= origin[a] : far_o <= origin[a]));
            if (std::is_same_v<T, float>) REQUIRE((near_o == origin[a] && far_o == origin[a]));
          }
          REQUIRE(b.exact == exact);
          ++checked;
        }
  CHECK(checked == 14 * 14 * 14 * 4);
}

// box4_ray prepares a float ray with SSE where it can (wide_bvh.hpp): every member must equal the
// plain loop's, bit for bit, on every combination of special components of origin and direction.
TEST_CASE("box4_ray: the SSE preparation of a float ray equals the plain loop's") {
  const float big = std::numeric_limits<float>::max(), tiny = std::numeric_limits<float>::denorm_min(),
              small = std::numeric_limits<float>::min(), nan = std::numeric_limits<float>::quiet_NaN();
  const float values[] = {0.0f, -0.0f, 1.0f, -2.5f, tiny, -tiny, small, -small, 3e-39f, big, -big, 1e38f,
                          0x1p126f, -0x1p126f,  // 1 / D exactly float's smallest normal: still exact
                          0x1p-128f, infinity<float>, -infinity<float>, nan};
  const auto bits = [](float x) { return std::bit_cast<std::uint32_t>(x); };
  int checked = 0, exact = 0, valid = 0;
  for (const float x : values)
    for (const float y : values)
      for (const float z : values) {
        ray_t<float> r(vec3f(1, 2, 3), vec3f(1, 0, 0));
        r.direction = vec3f(x, y, z);  // set after the constructor, which refuses some
        r.origin = vec3f(y, z, x);
        const box4_ray fast(r), plain(r, simd_scalar{});
        for (int a = 0; a < 3; ++a) {
          REQUIRE(bits(fast.inv_direction[a]) == bits(plain.inv_direction[a]));
          REQUIRE(bits(fast.near_origin[a]) == bits(plain.near_origin[a]));
          REQUIRE(bits(fast.far_origin[a]) == bits(plain.far_origin[a]));
          REQUIRE(fast.near_row[a] == plain.near_row[a]);
          REQUIRE(fast.far_row[a] == plain.far_row[a]);
        }
        REQUIRE(fast.valid == plain.valid);
        REQUIRE(fast.exact == plain.exact);
        ++checked, exact += plain.exact, valid += plain.valid;
      }
  CHECK(checked == 18 * 18 * 18);
  CHECK(exact > 100);  // both outcomes occur
  CHECK(exact < checked);
  CHECK(valid > 100);
  CHECK(valid < checked);
}

namespace {
// The SAH cost of a wide tree as collapse_by_cost counts it: a wide node c.node, a leaf its
// blocks, each times the area of its box (the float boxes of the wide nodes, rounded outward).
template <int N> double wide_cost(const std::vector<wide_node<N>>& nodes, std::uint32_t w, const collapse_costs& c,
                                  double node_area, std::size_t& leaves_seen, std::vector<int>& seen) {
  double cost = node_area * c.node;
  for (int k = 0; k < N; ++k) {
    const wide_node<N>& n = nodes[w];
    if (!(n.box[0][k] <= n.box[3][k])) continue;  // unused slot
    const double dx = double(n.box[3][k]) - n.box[0][k], dy = double(n.box[4][k]) - n.box[1][k],
                 dz = double(n.box[5][k]) - n.box[2][k];
    const double area = 2 * (dx * dy + dy * dz + dz * dx);
    if (n.count[k] != 0) {
      ++leaves_seen;
      cost += area * double((n.count[k] + std::uint32_t(c.leaf_block) - 1) / std::uint32_t(c.leaf_block));
      for (std::uint32_t i = n.child[k]; i < n.child[k] + n.count[k]; ++i) ++seen[i];
      CHECK(int(n.count[k]) <= c.max_leaf);
    } else {
      cost += wide_cost<N>(nodes, n.child[k], c, area, leaves_seen, seen);
    }
  }
  return cost;
}
template <int N> double wide_cost(const std::vector<wide_node<N>>& nodes, const bvh_t<float>& b, const collapse_costs& c) {
  std::size_t leaves = 0;
  std::vector<int> seen(b.order.size(), 0);
  const double cost = wide_cost<N>(nodes, 0, c, double(b.nodes[0].box.surface_area()), leaves, seen);
  for (const int s : seen) REQUIRE(s == 1);  // every position in exactly one leaf
  return cost;
}
}  // namespace

TEST_CASE_TEMPLATE("collapse by cost: every primitive once, its cost as counted, never above the greedy collapse",
                   W, std::integral_constant<int, 4>, std::integral_constant<int, 8>) {
  constexpr int N = W::value;
  rng g(41);
  for (int round = 0; round < 12; ++round) {
    // Soups of boxes: clustered or spread, of one size or of many.
    std::vector<aabb_t<float>> boxes;
    const int n = 20 + int(g.uniform() * 3000);
    for (int i = 0; i < n; ++i) {
      const float spread = round % 3 == 0 ? 1.0f : 100.0f;
      const vec3_t<float> c(float(g.uniform()) * spread, float(g.uniform()) * spread, float(g.uniform()));
      const float s = round % 2 ? 0.01f : float(std::ldexp(1.0, -int(g.uniform() * 12)));
      boxes.push_back({c - vec3_t<float>(s), c + vec3_t<float>(s)});
    }
    bvh_build_options o;
    o.max_leaf_size = 1 + int(g.uniform() * 12);
    o.traversal_cost = 0.5 + 3 * g.uniform();
    o.leaf_block = round % 4 == 0 ? 1 : 4;
    const bvh_t<float> b = build_bvh(boxes, o);
    collapse_costs c;
    c.node = 1 + 8 * g.uniform();
    c.leaf_block = o.leaf_block;
    c.max_leaf = o.max_leaf_size + int(g.uniform() * 16);
    double reported = 0;
    const auto by_cost = collapse_by_cost<N>(b, c, &reported);
    const double cost = wide_cost<N>(by_cost, b, c), greedy = wide_cost<N>(collapse<N>(b), b, c);
    CAPTURE(round);
    CAPTURE(n);
    // The boxes of the wide nodes are the binary ones rounded outward to float: a relative
    // 1e-6 covers that.
    CHECK(cost == doctest::Approx(reported).epsilon(1e-6));
    CHECK(cost <= greedy * (1 + 1e-6));
  }
}

TEST_CASE("collapse by cost: a tree cheaper as one leaf is one wide node with one leaf; bad costs are refused") {
  std::vector<aabb_t<float>> boxes;
  for (int i = 0; i < 6; ++i) boxes.push_back({vec3_t<float>(float(i), 0, 0), vec3_t<float>(float(i) + 1, 1, 1)});
  bvh_build_options o;
  o.max_leaf_size = 1;  // a binary tree of single leaves
  const bvh_t<float> b = build_bvh(boxes, o);
  REQUIRE(!b.nodes[0].leaf());
  collapse_costs c;
  c.leaf_block = 8;  // six boxes cost one block as a leaf; any node costs more
  const auto w = collapse_by_cost<4>(b, c);
  REQUIRE(w.size() == 1);
  CHECK(w[0].count[0] == 6);
  CHECK(w[0].child[0] == 0);
  for (int k = 1; k < 4; ++k) CHECK(!(w[0].box[0][k] <= w[0].box[3][k]));  // the other slots unused
  c.max_leaf = 5;  // too many for one leaf now: a wide node
  CHECK(collapse_by_cost<4>(b, c).size() >= 1);
  CHECK(collapse_by_cost<4>(b, c)[0].count[0] < 6);
  const struct {
    collapse_costs costs;
    const char* field;
  } bad[] = {{{-1, 4, 16}, "node"}, {{std::nan(""), 4, 16}, "node"}, {{infinity<double>, 4, 16}, "node"},
             {{5, 0, 16}, "leaf_block"}, {{5, 4, 0}, "max_leaf"}, {{5, 4, 256}, "max_leaf"}};
  for (const auto& x : bad) {
    CAPTURE(x.field);
    CHECK_THROWS_WITH_AS(collapse_by_cost<4>(b, x.costs), doctest::Contains(x.field), error);
  }
}

// The four-lane watertight test (watertight4.hpp) against the scalar one (triangle.hpp's
// detail::watertight_test), lane by lane: the same lanes hit, with the same bits of t, u and v,
// and the lanes it leaves to the scalar test are those with an edge function rounded to 0. On
// random triangles, integer grids with rays along the axes (edge functions exactly 0), slivers,
// grazing rays, huge, tiny and far triangles, empty (NaN) lanes and non-finite rays.
#include <zraka/accel/watertight4.hpp>
#include <zraka/core/rng.hpp>

#include <doctest/doctest.h>

#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <vector>

using namespace zraka;

#if ZRAKA_HAS_SSE

namespace {

using tri_f = triangle_t<float>;

triangle4 block_of(const std::array<tri_f, 4>& t, int used = 4) {
  triangle4 q;
  for (int l = 0; l < 4; ++l) {
    const float* v[3] = {&t[l].a.x, &t[l].b.x, &t[l].c.x};
    for (int row = 0; row < 9; ++row)
      q.v[row][l] = l < used ? v[row / 3][row % 3] : std::numeric_limits<float>::quiet_NaN();
    q.id[l] = l < used ? std::uint32_t(l) : UINT32_MAX;
  }
  return q;
}

struct tally {
  long lanes = 0, hits = 0, scalar = 0, wrong = 0;
};

// One block and one ray: every lane that is not left to the scalar test must agree with it.
void check(const triangle4& q, const std::array<tri_f, 4>& tris, int used, const rayf& r, float t_min,
           float t_bound, tally& n) {
  const detail::watertight_ray<float> wr(r);
  const detail::watertight_ray4 r4(wr);
  float t4[4], u4[4], v4[4];
  unsigned scalar = 0;
  const unsigned lanes = detail::watertight_test4(r4, q, t_min, t_bound, t4, u4, v4, scalar);
  for (int l = 0; l < 4; ++l) {
    ++n.lanes;
    const bool simd = (lanes >> l) & 1u, left = (scalar >> l) & 1u;
    if (l >= used) {  // an empty lane: never hit, never left to the scalar test
      n.wrong += simd || left;
      continue;
    }
    if (left) {  // only a lane with an edge function of exactly 0 in float
      ++n.scalar;
      n.wrong += simd;
      continue;
    }
    float t = 0, u = 0, v = 0;
    const bool want = detail::watertight_test(wr, tris[l].a, tris[l].b, tris[l].c, t, u, v) && t > t_min && t <= t_bound;
    n.hits += want;
    if (simd != want) ++n.wrong;
    else if (want && (std::bit_cast<std::uint32_t>(t) != std::bit_cast<std::uint32_t>(t4[l]) ||
                      std::bit_cast<std::uint32_t>(u) != std::bit_cast<std::uint32_t>(u4[l]) ||
                      std::bit_cast<std::uint32_t>(v) != std::bit_cast<std::uint32_t>(v4[l])))
      ++n.wrong;
  }
}

vec3f random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3f(vec3(s * std::cos(phi), s * std::sin(phi), z));
}

}  // namespace

TEST_CASE("four lanes equal the scalar test, bit for bit, on random triangles at many scales") {
  if (!detail::watertight4_available) {  // an FMA target: the BVH tests lane by lane (watertight4.hpp)
    CHECK(detail::may_fuse);
    return;
  }
  rng g(17);
  tally n;
  for (const double scale : {1e-30, 1e-6, 1.0, 1e6, 1e30})
    for (const double shift : {0.0, 1e4})  // far from the origin: fewer fraction bits
      for (int i = 0; i < 3000; ++i) {
        std::array<tri_f, 4> t;
        const vec3 c = shift * scale * vec3(1, -2, 3);
        for (tri_f& x : t) {
          const vec3 m = c + scale * vec3(random_unit(g));
          x = {vec3f(m + 0.5 * scale * vec3(random_unit(g))), vec3f(m + 0.5 * scale * vec3(random_unit(g))),
               vec3f(m + 0.5 * scale * vec3(random_unit(g)))};
        }
        if (i % 5 == 0) t[2] = t[1];  // two lanes hit at exactly one t
        if (i % 7 == 0) t[3].c = t[3].a + 1e-7f * (t[3].b - t[3].a);  // a sliver, nearly a segment
        const int used = 1 + i % 4;
        const triangle4 q = block_of(t, used);
        const vec3 o = c + 3 * scale * vec3(random_unit(g));
        const tri_f& aim = t[std::size_t(i % used)];  // a point of a used lane's plane, maybe outside
        const double wa = 1.4 * g.uniform() - 0.2, wb = 1.4 * g.uniform() - 0.2;
        const vec3 target = vec3(aim.a) + wa * (vec3(aim.b) - vec3(aim.a)) + wb * (vec3(aim.c) - vec3(aim.a));
        check(q, t, used, rayf(vec3f(o), vec3f(target - o)), 0.0f, infinity<float>, n);
        // Grazing: along triangle 0's plane, through its middle, nudged off it a little.
        const vec3f mid = (t[0].a + t[0].b + t[0].c) / 3.0f, along = t[0].b - t[0].a;
        const vec3f normal = glm::cross(t[0].b - t[0].a, t[0].c - t[0].a);
        const vec3f nudge = 1e-6f * glm::length(along) * normalize_or_zero(normal);
        check(q, t, used, rayf(mid - along + nudge * float(g.uniform() - 0.5), along), 0.0f, infinity<float>, n);
        check(q, t, used, rayf(vec3f(o), vec3f(target - o)), 0.0f, float(0.5 * glm::length(target - o)), n);
      }
  MESSAGE(n.lanes << " lanes, " << n.hits << " hits, " << n.scalar << " left to the scalar test, " << n.wrong
                  << " wrong");
  CHECK(n.wrong == 0);
  CHECK(n.hits > 3000);
}

TEST_CASE("four lanes on an integer grid, rays along the axes: zeros go to the scalar test") {
  if (!detail::watertight4_available) {  // an FMA target: the BVH tests lane by lane (watertight4.hpp)
    CHECK(detail::may_fuse);
    return;
  }
  // Rays through vertices and along edges make edge functions exactly 0 in float: the lanes
  // where that decides the hit are left to the scalar test, which recomputes them in double.
  rng g(5);
  auto grid = [&] { return float(std::floor(g.uniform() * 5)); };
  tally n;
  for (int i = 0; i < 20000; ++i) {
    std::array<tri_f, 4> t;
    for (tri_f& x : t) x = {{grid(), grid(), grid()}, {grid(), grid(), grid()}, {grid(), grid(), grid()}};
    vec3f d(0);
    d[i % 3] = i % 2 ? 1.0f : -1.0f;
    if (i % 4 == 0) d[(i + 1) % 3] = 0.5f * (i % 8 == 0 ? 1.0f : -1.0f);
    const vec3f o = vec3f(grid(), grid(), grid()) - 10.0f * d;
    check(block_of(t), t, 4, rayf(o, d), 0.0f, infinity<float>, n);
  }
  MESSAGE(n.lanes << " lanes, " << n.hits << " hits, " << n.scalar << " left to the scalar test");
  CHECK(n.wrong == 0);
  CHECK(n.scalar > 1000);
  CHECK(n.hits > 1000);
}

TEST_CASE("four lanes: empty lanes, NaN and infinite rays, overflowing coordinates") {
  if (!detail::watertight4_available) {  // an FMA target: the BVH tests lane by lane (watertight4.hpp)
    CHECK(detail::may_fuse);
    return;
  }
  const float inf = infinity<float>, nan = std::numeric_limits<float>::quiet_NaN(), big = 3e38f;
  const std::array<tri_f, 4> t = {tri_f{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, tri_f{{-big, -big, 1}, {big, -big, 1}, {0, big, 1}},
                                  tri_f{{0, 0, big}, {1, 0, big}, {0, 1, big}}, tri_f{{0, 0, -2}, {1, 0, -2}, {0, 1, -2}}};
  tally n;
  for (const int used : {0, 1, 4})
    for (const rayf& r : {rayf({0.25f, 0.25f, 5}, {0, 0, -1}), rayf({0.25f, 0.25f, -big}, {0, 0, 1}),
                          rayf({0.25f, 0.25f, 5}, {0, 0, -1e-39f}), rayf({0.25f, 0.25f, 5}, {1e-30f, 0, -1}),
                          rayf({-big, 0.25f, 5}, {big, 0, -1}), rayf({0.25f, 0.25f, 5}, {0, 0, -inf}),
                          rayf({0.25f, 0.25f, inf}, {0, 0, -1}), rayf({0.25f, nan, 5}, {0, 0, -1}),
                          rayf({0.25f, 0.25f, 5}, {nan, 0, -1})})
      check(block_of(t, used), t, used, r, 0.0f, inf, n);
  MESSAGE(n.lanes << " lanes, " << n.hits << " hits");
  CHECK(n.wrong == 0);
  CHECK(n.hits > 0);
}

#else
TEST_CASE("four lanes: no SSE here, the triangle BVH tests lane by lane") {
  CHECK_FALSE(detail::watertight4_available);
}
#endif

// Tessellating the teapot: counts, normals from the patches, orientation, seams, bounding box.
#include <zraka/core/resources.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/io/bpt.hpp>

#include <doctest/doctest.h>

#include <map>

using namespace zraka;

namespace {
template <class T> std::vector<bezier_patch_t<T>> teapot() {
  return load_bpt<T>(resource_path("scenes/teapot.bpt")).all_patches();
}
}  // namespace

TEST_CASE_TEMPLATE("32 divs^2 2 triangles, degenerate ones kept", T, float, double) {
  const auto patches = teapot<T>();
  for (const int divs : {2, 5, 16}) {
    const auto m = tessellate(patches, divs);
    CHECK(m.triangle_count() == std::size_t(32 * divs * divs * 2));
    CHECK(m.positions.size() == std::size_t(32 * (divs + 1) * (divs + 1)));
    CHECK(m.normals.size() == m.positions.size());
    // The zero-area triangles: one per cell along each of the 8 collapsed rows. (At divs = 1
    // there are 4 more: the spout's end patches have 4 collinear corners.)
    std::size_t zero = 0;
    for (std::size_t i = 0; i < m.triangle_count(); ++i) zero += m.triangle(i).area() == T(0);
    CHECK(zero == std::size_t(8 * divs));
  }
  CHECK(tessellate(patches, 16).triangle_count() == 16384);  // the thesis's divs = 16
  CHECK_THROWS_AS(tessellate(patches, 0), error);
}

TEST_CASE_TEMPLATE("vertex normals are the patch normals: unit, finite, outward", T, float,
                   double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  const auto patches = teapot<T>();
  const int divs = 8;
  const auto m = tessellate(patches, divs);
  for (std::size_t k = 0; k < m.normals.size(); ++k) {
    REQUIRE(is_finite(m.normals[k]));
    CHECK(std::abs(glm::length(m.normals[k]) - T(1)) <= 4 * eps);
  }
  // Not averaged: vertex (i, j) of patch p is exactly the patch's normal at (i/divs, j/divs).
  const std::size_t per_patch = std::size_t(divs + 1) * (divs + 1);
  const vec3_t<T> n53 = patch_normal(patches[5], T(2) / 8, T(3) / 8);
  CHECK(max_component(glm::abs(m.normals[5 * per_patch + 3 * (divs + 1) + 2] - n53)) <= 4 * eps);
  // Each non-degenerate triangle's winding agrees with its vertex normals (the geometric
  // normal is on the same side), so hit_t's front_face and the shading normal agree.
  std::size_t disagree = 0;
  for (std::size_t i = 0; i < m.triangle_count(); ++i) {
    const auto tri = m.triangle(i);
    if (tri.area() == T(0)) continue;
    const auto& f = m.triangles[i];
    const vec3_t<T> avg = m.normals[f[0]] + m.normals[f[1]] + m.normals[f[2]];
    disagree += glm::dot(tri.normal(), avg) <= T(0);
  }
  CHECK(disagree == 0);
}

TEST_CASE_TEMPLATE("the tessellated teapot's bounding box (data README)", T, float, double) {
  const auto m = tessellate(teapot<T>(), 16);
  const auto b = m.bounds();
  // The README's box (x from -3 to 3.525, y +-2, z from 0 to 3.15) is the control net's; the
  // surface lies inside it (convex hull property). z, y and the handle's back (x = -3) reach it
  // at grid points that are corner control points, exactly; the spout's lip (x = 3.525) is an
  // interior control point, which the surface does not reach (it ends near x = 3.43).
  CHECK(b.lo.z == T(0));
  CHECK(b.hi.z == T(3.15));
  CHECK(b.hi.x < T(3.525));
  CHECK(b.hi.x > T(3.4));
  CHECK(b.lo.x == T(-3.0));
  CHECK(b.lo.y == T(-2));
  CHECK(b.hi.y == T(2));
}

TEST_CASE_TEMPLATE("seams between patches are watertight: shared vertices are bit-identical", T,
                   float, double) {
  const auto set = load_bpt<T>(resource_path("scenes/teapot.bpt"));
  const int divs = 7, n = divs + 1;
  const auto m = tessellate(set.all_patches(), divs);
  // The four edges of a patch as (control indices, grid indices), both in edge order.
  auto edges = [&](std::size_t p) {
    std::vector<std::pair<std::array<std::uint32_t, 4>, std::vector<std::size_t>>> out;
    const auto& c = set.patches[p];
    const std::size_t base = p * std::size_t(n * n);
    const int corner[4][2] = {{0, 0}, {0, 3}, {0, 0}, {3, 0}};  // v=0, v=1 rows; u=0, u=1 columns
    for (int e = 0; e < 4; ++e) {
      std::array<std::uint32_t, 4> ctrl{};
      std::vector<std::size_t> grid;
      for (int k = 0; k < 4; ++k)
        ctrl[k] = e < 2 ? c[4 * corner[e][1] + k] : c[4 * k + corner[e][0]];
      for (int k = 0; k < n; ++k)
        grid.push_back(base + (e < 2 ? std::size_t((corner[e][1] ? divs : 0) * n + k)
                                     : std::size_t(k * n + (corner[e][0] ? divs : 0))));
      out.push_back({ctrl, grid});
    }
    return out;
  };
  std::map<std::array<std::uint32_t, 4>, std::vector<std::size_t>> seen;
  int shared = 0;
  for (std::size_t p = 0; p < set.patches.size(); ++p)
    for (const auto& [ctrl, grid] : edges(p)) {
      if (ctrl[0] == ctrl[1] && ctrl[1] == ctrl[2] && ctrl[2] == ctrl[3]) continue;  // a pole
      auto it = seen.find(ctrl);
      if (it == seen.end()) {
        seen[ctrl] = grid;
        continue;
      }
      ++shared;
      for (int k = 0; k < n; ++k) CHECK(m.positions[grid[k]] == m.positions[it->second[k]]);
    }
  CHECK(shared >= 40);  // the teapot's patches share most of their edges in the same direction
}

TEST_CASE_TEMPLATE("an affine transform moves points and turns normals, mirrors keep winding", T,
                   float, double) {
  const auto patches = teapot<T>();
  const auto plain = tessellate(patches, 4);
  // The book's scenes are y-up: rotate the z-up teapot by -90 degrees about x and scale it.
  const auto to_world =
      affine_t<T>::scale(vec3_t<T>(2, 2, 2)) * affine_t<T>::rotate(vec3_t<T>(1, 0, 0), -pi<T> / 2);
  const auto moved = tessellate(patches, 4, to_world);
  // A few roundings of numbers up to ~7: 64 eps absolute is ample.
  constexpr T tol = 64 * std::numeric_limits<T>::epsilon();
  for (std::size_t k = 0; k < plain.positions.size(); k += 37) {
    const vec3_t<T> p = plain.positions[k], q = moved.positions[k];
    CHECK(max_component(glm::abs(q - T(2) * vec3_t<T>(p.x, p.z, -p.y))) <= 8 * tol);
    const vec3_t<T> n = plain.normals[k], nq = moved.normals[k];
    CHECK(max_component(glm::abs(nq - vec3_t<T>(n.x, n.z, -n.y))) <= tol);
  }
  // A mirror (x -> -x) flips the triangles' winding back, so they still face the normals.
  const auto mirrored = tessellate(patches, 4, affine_t<T>::scale(vec3_t<T>(-1, 1, 1)));
  for (std::size_t i = 0; i < mirrored.triangle_count(); ++i) {
    const auto tri = mirrored.triangle(i);
    if (tri.area() == T(0)) continue;
    const auto& f = mirrored.triangles[i];
    CHECK(glm::dot(tri.normal(), mirrored.normals[f[0]] + mirrored.normals[f[1]] +
                                     mirrored.normals[f[2]]) > T(0));
  }
  CHECK_THROWS_AS(tessellate(patches, 4, affine_t<T>::scale(vec3_t<T>(1, 0, 1))), error);
}

TEST_CASE("the triangle limit is checked before tessellating, not after the memory is gone") {
  const auto patches = load_bpt<double>(resource_path("scenes/teapot.bpt")).all_patches();
  CHECK_THROWS_WITH_AS(tessellate(patches, 1024),
                       "the triangle count of 32 patches at divs 1024 is 67108864, more than the limit of 4000000 "
                       "(raise with --limit triangles=N)",
                       error);
  const input_limits saved = limits();
  set_limit(limits(), "triangles=256");
  CHECK(tessellate(patches, 2).triangles.size() == 256);
  CHECK_THROWS_AS(tessellate(patches, 3), error);
  limits() = saved;
}

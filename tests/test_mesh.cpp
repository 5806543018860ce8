// The indexed triangle mesh: bounds, nearest hit, shading vs geometric normal.
#include <zraka/geometry/mesh.hpp>

#include <doctest/doctest.h>

using namespace zraka;

namespace {
// Two unit squares in the planes z = z0 and z = z1, each of two triangles, facing +z, with
// vertex normals tilted outwards (like a sampled dome), so shading and geometric normals differ.
template <class T> mesh_t<T> two_squares(T z0, T z1) {
  mesh_t<T> m;
  for (const T z : {z0, z1}) {
    const auto base = static_cast<std::uint32_t>(m.positions.size());
    for (const auto& [x, y] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
      m.positions.push_back(vec3_t<T>(T(x), T(y), z));
      m.normals.push_back(glm::normalize(vec3_t<T>(T(x) - T(0.5), T(y) - T(0.5), T(1))));
    }
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
  }
  return m;
}
}  // namespace

TEST_CASE_TEMPLATE("bounds of the whole mesh and of a triangle range", T, float, double) {
  const auto m = two_squares<T>(T(-1), T(2));
  CHECK(m.bounds().lo == vec3_t<T>(0, 0, -1));
  CHECK(m.bounds().hi == vec3_t<T>(1, 1, 2));
  CHECK(m.bounds(2, 4).lo == vec3_t<T>(0, 0, 2));
  CHECK(m.bounds(0, 0).empty());
}

TEST_CASE_TEMPLATE("the nearest hit, whatever the triangle order", T, float, double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  for (const auto& [z0, z1] : {std::pair{T(0), T(1)}, {T(1), T(0)}}) {
    const auto m = two_squares<T>(z0, z1);
    const ray_t<T> r(vec3_t<T>(0.25, 0.75, 5), vec3_t<T>(0, 0, -1));
    hit_t<T> h;
    mesh_shading_t<T> s;
    REQUIRE(intersect(m, r, T(0), infinity<T>, h, s));
    CHECK(h.t == doctest::Approx(4));  // the square at z = 1
    CHECK(m.triangle(s.triangle).a.z == T(1));
    CHECK(h.normal == vec3_t<T>(0, 0, 1));  // hit_t keeps the geometric normal
    CHECK(h.front_face);
    // The shading normal interpolates the vertex normals: at (0.25, 0.75) it leans to -x, +y.
    CHECK(std::abs(glm::length(s.normal) - T(1)) <= 4 * eps);
    CHECK(s.normal.x < T(0));
    CHECK(s.normal.y > T(0));
    // Up to t_max only: then the far square is the only candidate... and it is cut off too.
    CHECK_FALSE(intersect(m, r, T(0), T(3.5), h));
    // From between the squares, looking up: the upper one, seen from below.
    REQUIRE(intersect(m, ray_t<T>(vec3_t<T>(0.5, 0.5, 0.5), vec3_t<T>(0, 0, 1)), T(0), infinity<T>,
                      h, s));
    CHECK(h.t == doctest::Approx(0.5));
    CHECK_FALSE(h.front_face);
  }
}

TEST_CASE_TEMPLATE("a triangle range limits the search", T, float, double) {
  const auto m = two_squares<T>(T(0), T(1));
  const ray_t<T> r(vec3_t<T>(0.25, 0.75, 5), vec3_t<T>(0, 0, -1));
  hit_t<T> h;
  mesh_shading_t<T> s;
  REQUIRE(intersect(m, 0, 2, r, T(0), infinity<T>, h, s));  // only the square at z = 0
  CHECK(h.t == doctest::Approx(5));
  CHECK(s.triangle < 2);
  CHECK_FALSE(intersect(m, 2, 2, r, T(0), infinity<T>, h, s));
}

TEST_CASE_TEMPLATE("cancelling vertex normals fall back to the geometric normal", T, float,
                   double) {
  mesh_t<T> m;
  m.positions = {vec3_t<T>(0, 0, 0), vec3_t<T>(1, 0, 0), vec3_t<T>(0, 1, 0)};
  m.normals = {vec3_t<T>(0, 0, 1), vec3_t<T>(0, 0, -1), vec3_t<T>(0, 0, 1)};
  m.triangles = {{0, 1, 2}};
  // At barycentrics u = 1/2, v = 0 the first two normals cancel exactly.
  CHECK(m.shading_normal(0, T(0.5), T(0)) == vec3_t<T>(0, 0, 1));
}

TEST_CASE_TEMPLATE("zero-area triangles are kept but never hit", T, float, double) {
  mesh_t<T> m;
  m.positions = {vec3_t<T>(0, 0, 0), vec3_t<T>(0, 0, 0), vec3_t<T>(0, 1, 0)};
  m.normals = {vec3_t<T>(0, 0, 1), vec3_t<T>(0, 0, 1), vec3_t<T>(0, 0, 1)};
  m.triangles = {{0, 1, 2}};
  hit_t<T> h;
  CHECK_FALSE(
      intersect(m, ray_t<T>(vec3_t<T>(0, 0.5, 1), vec3_t<T>(0, 0, -1)), T(0), infinity<T>, h));
  CHECK(h.t == infinity<T>);  // untouched
}

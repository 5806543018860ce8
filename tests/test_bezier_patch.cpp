// Bicubic Bezier patches: layout, evaluation, the two derivative schemes, and the unit normal,
// including the teapot's collapsed patches (book 1.3, 1.4; errata A3, B6, C8).
#include <zraka/core/resources.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/bezier_patch.hpp>
#include <zraka/io/bpt.hpp>

#include <doctest/doctest.h>

#include <vector>

using namespace zraka;

namespace {
template <class T> std::vector<T> parameters() {
  std::vector<T> ts = {T(0), T(1e-7), T(0.5), T(1) - T(1e-7), T(1)};
  for (int k = 1; k < 8; ++k) ts.push_back(T(k) / T(8));
  return ts;
}
template <class T> bezier_patch_t<T> random_patch(rng& g) {
  bezier_patch_t<T> p;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)  // a wavy sheet over the unit square, so normals exist
      p.P[i + 4 * j] = vec3_t<T>(T(i / 3.0 + 0.1 * g.uniform()), T(j / 3.0 + 0.1 * g.uniform()),
                                 T(g.uniform() - 0.5));
  return p;
}
template <class T> T dist(const vec3_t<T>& a, const vec3_t<T>& b) {
  return max_component(glm::abs(a - b));
}
template <class T> T angle(const vec3_t<T>& a, const vec3_t<T>& b) {
  return T(2) * std::atan2(glm::length(a - b), glm::length(a + b));  // accurate for small angles
}
template <class T> patch_set_t<T> teapot() {
  return load_bpt<T>(resource_path("scenes/teapot.bpt"));
}
// Patches 21-24 (lid) and 29-32 (bottom), one-based in the data README: row 0 is one point.
const int collapsed[] = {21, 22, 23, 24, 29, 30, 31, 32};
}  // namespace

TEST_CASE_TEMPLATE("layout: P[4*row + col], the column runs in u and the row in v", T, float,
                   double) {
  bezier_patch_t<T> p;
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) p.P[4 * row + col] = vec3_t<T>(T(col), T(row), T(0));
  // Control points evenly spaced on a line reproduce the line (linear precision): P(u,v) =
  // (3u, 3v, 0). Rounding of a few operations on numbers up to 3: 16 eps is ample.
  constexpr T tol = 16 * std::numeric_limits<T>::epsilon();
  for (const T u : parameters<T>())
    for (const T v : parameters<T>()) {
      CHECK(dist(evaluate(p, u, v), vec3_t<T>(3 * u, 3 * v, 0)) <= 4 * tol);
      const auto d = differentiate(p, u, v);
      CHECK(dist(d.du, vec3_t<T>(3, 0, 0)) <= 4 * tol);
      CHECK(dist(d.dv, vec3_t<T>(0, 3, 0)) <= 4 * tol);
      CHECK(dist(patch_normal(p, u, v), vec3_t<T>(0, 0, 1)) <= tol);
    }
}

TEST_CASE_TEMPLATE("the corners of a patch are its corner control points, exactly", T, float,
                   double) {
  rng g(3);
  for (int k = 0; k < 50; ++k) {
    const auto p = random_patch<T>(g);
    CHECK(evaluate(p, T(0), T(0)) == p.P[0]);
    CHECK(evaluate(p, T(1), T(0)) == p.P[3]);
    CHECK(evaluate(p, T(0), T(1)) == p.P[12]);
    CHECK(evaluate(p, T(1), T(1)) == p.P[15]);
  }
}

TEST_CASE_TEMPLATE("derivatives: explicit (A3) = fast scheme (B6) = central differences", T, float,
                   double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  const T h = std::cbrt(eps);  // balances truncation (~h^2) and rounding (~eps/h)
  rng g(5);
  for (int k = 0; k < 50; ++k) {
    const auto p = random_patch<T>(g);
    const T scale = p.scale();
    for (const T u : parameters<T>())
      for (const T v : parameters<T>()) {
        const auto d = differentiate(p, u, v);
        // Point and tangents are combinations of the control points with weights up to 6 in
        // size, through 3 levels of lerps: 64 eps times the scale bounds both schemes' rounding.
        CHECK(dist(d.p, evaluate(p, u, v)) <= 64 * eps * scale);
        CHECK(dist(d.du, du_explicit(p, u, v)) <= 64 * eps * scale);
        CHECK(dist(d.dv, dv_explicit(p, u, v)) <= 64 * eps * scale);
        // Central differences of a bicubic: truncation <= 8 h^2 times the size of the control
        // points' third differences (at most 8 scale), rounding about eps scale / h.
        const T fd_tol = (64 * h * h + 4 * eps / h) * scale;
        const vec3_t<T> fu = (evaluate(p, u + h, v) - evaluate(p, u - h, v)) / (2 * h);
        const vec3_t<T> fv = (evaluate(p, u, v + h) - evaluate(p, u, v - h)) / (2 * h);
        CHECK(dist(d.du, fu) <= fd_tol);
        CHECK(dist(d.dv, fv) <= fd_tol);
        // The mixed derivative, by differencing the exact du: truncation 8 h^2 * 9 * 8 scale.
        const vec3_t<T> fuv = (du_explicit(p, u, v + h) - du_explicit(p, u, v - h)) / (2 * h);
        CHECK(dist(d.duv, fuv) <= (600 * h * h + 16 * eps / h) * scale);
      }
  }
}

TEST_CASE_TEMPLATE("the normal of a regular patch is (du x dv)/|du x dv|, unit length", T, float,
                   double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  rng g(9);
  for (int k = 0; k < 50; ++k) {
    const auto p = random_patch<T>(g);
    for (const T u : parameters<T>())
      for (const T v : parameters<T>()) {
        const vec3_t<T> n = patch_normal(p, u, v);
        const auto d = differentiate(p, u, v);
        CHECK(std::abs(glm::length(n) - T(1)) <= 4 * eps);  // normalised: a few roundings
        // Same direction as the textbook formula, up to its own rounding (~eps / sin).
        CHECK(angle(n, glm::normalize(glm::cross(d.du, d.dv))) <= 1e3 * eps);
      }
  }
}

TEST_CASE_TEMPLATE("the teapot's collapsed patches: the naive normal is 0/0 there", T, float,
                   double) {
  const auto set = teapot<T>();
  for (const int k : collapsed) {
    const auto p = set.patch(k - 1);
    for (int i = 1; i < 4; ++i) CHECK(p.P[i] == p.P[0]);  // row 0 is one point
    for (const T u : parameters<T>()) {
      const auto d = differentiate(p, u, T(0));
      CHECK(glm::length(glm::cross(d.du, d.dv)) == T(0));  // so normalize() would give NaN
    }
  }
}

TEST_CASE_TEMPLATE("the teapot's collapsed patches: normals unit, finite, continuous (C8)", T,
                   float, double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  const auto set = teapot<T>();
  for (const int k : collapsed) {
    const auto p = set.patch(k - 1);
    for (const T u : parameters<T>()) {
      for (const T v : {T(0), T(1e-7), T(1e-5)}) {
        const vec3_t<T> n = patch_normal(p, u, v);
        REQUIRE(is_finite(n));
        CHECK(std::abs(glm::length(n) - T(1)) <= 4 * eps);
        // Continuity: the plain formula at an inset point v = 1e-3, where both tangents are
        // long. The normal turns by about |dv| * 1e-3 * curvature there: 0.01 rad is generous.
        const auto d = differentiate(p, u, T(1e-3));
        const vec3_t<T> inset = glm::normalize(glm::cross(d.du, d.dv));
        CHECK(angle(n, inset) <= T(0.01));
      }
      // And at the pole itself, the limit normal agrees with the formula very close to it
      // (double only: in float du at v = 1e-6 is below the rounding noise).
      if constexpr (std::is_same_v<T, double>) {
        const auto d = differentiate(p, u, 1e-6);
        CHECK(angle(patch_normal(p, u, 0.0), glm::normalize(glm::cross(d.du, d.dv))) <= 1e-4);
      }
    }
  }
}

TEST_CASE("the teapot's poles: the lid knob points up, the bottom centre down") {
  const auto set = teapot<double>();
  for (const int k : {21, 22, 23, 24})
    for (const double u : parameters<double>())  // the knob top is flat: exactly +z there
      CHECK(angle(patch_normal(set.patch(k - 1), u, 0.0), vec3(0, 0, 1)) <= 1e-12);
  for (const int k : {29, 30, 31, 32})
    for (const double u : parameters<double>())
      CHECK(angle(patch_normal(set.patch(k - 1), u, 0.0), vec3(0, 0, -1)) <= 1e-12);
}

TEST_CASE_TEMPLATE("other degenerate patches still give a unit normal, never NaN", T, float,
                   double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  const auto set = teapot<T>();
  // A collapsed column: the lid patch with u and v swapped (transposed).
  bezier_patch_t<T> transposed;
  const auto lid = set.patch(20);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) transposed.P[i + 4 * j] = lid.P[j + 4 * i];
  for (const T w : parameters<T>()) {
    // Transposing swaps du and dv, so the normal flips.
    CHECK(angle(patch_normal(transposed, T(0), w), -patch_normal(lid, w, T(0))) <= T(1e-3));
  }
  // A collapsed corner: row 0 and column 0 both one point, so du = dv = 0 at (0, 0).
  bezier_patch_t<T> corner;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i)
      corner.P[i + 4 * j] = (i == 0 || j == 0) ? vec3_t<T>(0) : vec3_t<T>(T(i), T(j), T(i * j) / 9);
  // Every patch with no normal at all: a point, and a curve (all rows the same line).
  bezier_patch_t<T> point, curve;
  point.P.fill(vec3_t<T>(T(1), T(2), T(3)));
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) curve.P[i + 4 * j] = vec3_t<T>(T(i), T(0), T(0));
  for (const auto* p : {&corner, &point, &curve})
    for (const T u : parameters<T>())
      for (const T v : parameters<T>()) {
        const vec3_t<T> n = patch_normal(*p, u, v);
        REQUIRE(is_finite(n));
        CHECK(std::abs(glm::length(n) - T(1)) <= 4 * eps);
      }
  CHECK(patch_normal(point, T(0.5), T(0.5)) == vec3_t<T>(0, 0, 1));
}

TEST_CASE("the thesis's printed du (last weight 3u, errata A3) is wrong; 3u^2 is right") {
  rng g(21);
  const auto p = random_patch<double>(g);
  const double u = 0.5, v = 0.3, h = 1e-5;
  const vec3 fd = (evaluate(p, u + h, v) - evaluate(p, u - h, v)) / (2 * h);
  // The printed weights: the last one is 3u instead of 3u^2.
  const double s = 1 - u;
  const std::array<double, 4> printed = {-3 * s * s, 3 * s * s - 6 * u * s, 6 * u * s - 3 * u * u,
                                         3 * u};
  cubic_t<vec3> R;
  for (int j = 0; j < 4; ++j) R[j] = bernstein_sum(p.row(j), printed);
  const vec3 wrong = bernstein_sum(R, bernstein3(v));
  CHECK(max_component(glm::abs(wrong - fd)) > 0.1);                   // off by 0.75 sum_j b_j P_3j
  CHECK(max_component(glm::abs(du_explicit(p, u, v) - fd)) < 1e-8);  // ours: FD error only
}

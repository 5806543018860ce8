// Cubic Bezier curves: Bernstein sum vs de Casteljau, and the derivative (book 1.3, 1.4).
#include <zraka/core/rng.hpp>
#include <zraka/geometry/bezier.hpp>

#include <doctest/doctest.h>

#include <vector>

using namespace zraka;

namespace {
// The parameters every test visits: the ends, just inside them, the middle, and a grid.
template <class T> std::vector<T> parameters() {
  std::vector<T> ts = {T(0), T(1e-7), T(0.5), T(1) - T(1e-7), T(1)};
  for (int k = 1; k < 64; ++k) ts.push_back(T(k) / T(64));
  return ts;
}
template <class T> cubic_t<vec3_t<T>> random_cubic(rng& g, double size) {
  cubic_t<vec3_t<T>> P;
  for (auto& p : P)
    p = vec3_t<T>(vec3(g.uniform() - 0.5, g.uniform() - 0.5, g.uniform() - 0.5) * (2 * size));
  return P;
}
template <class T> T max_abs(const cubic_t<vec3_t<T>>& P) {
  T m = 0;
  for (const auto& p : P) m = std::max(m, max_component(glm::abs(p)));
  return m;
}
template <class T> T dist(const vec3_t<T>& a, const vec3_t<T>& b) {
  return max_component(glm::abs(a - b));
}
}  // namespace

TEST_CASE_TEMPLATE("Bernstein weights: a partition of unity, non-negative on [0,1]", T, float,
                   double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  for (const T t : parameters<T>()) {
    const auto b = bernstein3(t);
    const auto db = bernstein3_derivative(t);
    // Four rounded terms summed, each with a few roundings: 8 eps is ample.
    CHECK(std::abs(b[0] + b[1] + b[2] + b[3] - T(1)) <= 8 * eps);
    for (const T w : b) CHECK(w >= T(0));
    // The derivative of the constant 1 is 0; the weights are up to 3 in size.
    CHECK(std::abs(db[0] + db[1] + db[2] + db[3]) <= 32 * eps);
  }
}

TEST_CASE_TEMPLATE("a curve with known values", T, float, double) {
  using V = vec2_t<T>;
  const cubic_t<V> P = {V(0, 0), V(1, 2), V(3, 2), V(4, 0)};
  // P(1/2) = (P0 + 3 P1 + 3 P2 + P3) / 8 and P'(0) = 3 (P1 - P0), P'(1) = 3 (P3 - P2): all
  // exact in binary, so exact equality is right.
  CHECK(eval_bernstein(P, T(0.5)) == V(2, 1.5));
  CHECK(eval_de_casteljau(P, T(0.5)) == V(2, 1.5));
  CHECK(derivative_de_casteljau(P, T(0)) == V(3, 6));
  CHECK(derivative_de_casteljau(P, T(1)) == V(3, -6));
  CHECK(derivative_bernstein(P, T(0)) == V(3, 6));
}

TEST_CASE_TEMPLATE("both forms interpolate the end control points exactly", T, float, double) {
  rng g(7);
  for (int k = 0; k < 100; ++k) {
    const auto P = random_cubic<T>(g, 1000.0);
    // Exact, not approximate: patch seams rely on it (see lerp_point).
    CHECK(eval_bernstein(P, T(0)) == P[0]);
    CHECK(eval_bernstein(P, T(1)) == P[3]);
    CHECK(eval_de_casteljau(P, T(0)) == P[0]);
    CHECK(eval_de_casteljau(P, T(1)) == P[3]);
  }
}

TEST_CASE_TEMPLATE("Bernstein sum = de Casteljau", T, float, double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  rng g(11);
  for (const double size : {1e-3, 1.0, 1e4}) {
    for (int k = 0; k < 200; ++k) {
      const auto P = random_cubic<T>(g, size);
      const T scale = max_abs(P);
      for (const T t : parameters<T>()) {
        // Both are convex combinations of the P_i computed with at most ~8 roundings each;
        // the difference is bounded by 16 eps times the largest coordinate.
        CHECK(dist(eval_bernstein(P, t), eval_de_casteljau(P, t)) <= 16 * eps * scale);
      }
    }
  }
}

TEST_CASE_TEMPLATE("derivative: lemma = explicit weights = central differences", T, float, double) {
  constexpr T eps = std::numeric_limits<T>::epsilon();
  rng g(13);
  for (int k = 0; k < 200; ++k) {
    const auto P = random_cubic<T>(g, 10.0);
    const T scale = max_abs(P);
    for (const T t : parameters<T>()) {
      const auto c = de_casteljau(P, t);
      // One pass gives the point too.
      CHECK(dist(c.point, eval_de_casteljau(P, t)) == T(0));
      const vec3_t<T> lemma = c.derivative, expl = derivative_bernstein(P, t);
      // The derivative is a combination of differences of P_i with weights summing to <= 6:
      // 64 eps times the scale covers the roundings of both forms.
      CHECK(dist(lemma, expl) <= 64 * eps * scale);
      // Central difference (P(t+h) - P(t-h)) / 2h, computed in T. For a cubic its truncation
      // error is h^2/6 |P'''| <= 8 h^2 scale, and rounding adds about eps scale / h.
      // h = eps^(1/3) balances the two: about 1e-5 in double, 5e-3 in float.
      const T h = std::cbrt(eps);
      const vec3_t<T> fd = (eval_de_casteljau(P, t + h) - eval_de_casteljau(P, t - h)) / (2 * h);
      CHECK(dist(lemma, fd) <= (8 * h * h + 4 * eps / h) * scale);
    }
  }
}

TEST_CASE("float evaluation far from the origin stays within a few ulps of double") {
  // Control points near 1e4 (the size where a float has 3 decimals left): both forms stay
  // within a few float ulps of the same curve evaluated in double.
  rng g(17);
  for (int k = 0; k < 100; ++k) {
    cubic_t<vec3> Pd;
    for (auto& p : Pd) p = vec3(1e4) + vec3(g.uniform(), g.uniform(), g.uniform());
    cubic_t<vec3f> Pf;
    for (int i = 0; i < 4; ++i) Pf[i] = vec3f(Pd[i]);
    for (int i = 0; i < 4; ++i) Pd[i] = vec3(Pf[i]);  // the same points in both precisions
    for (const double t : parameters<double>()) {
      const vec3 exact = eval_de_casteljau(Pd, t);
      // 1e4 has ulp 2^-10 in float; 16 ulps covers either form's roundings.
      CHECK(max_component(glm::abs(vec3(eval_de_casteljau(Pf, float(t))) - exact)) <= 16 * 0x1p-10);
      CHECK(max_component(glm::abs(vec3(eval_bernstein(Pf, float(t))) - exact)) <= 16 * 0x1p-10);
    }
  }
}

TEST_CASE_TEMPLATE("a collapsed curve stays one point, with derivative exactly 0", T, float,
                   double) {
  // The teapot's lid and bottom patches have rows of four equal points; the lerp must keep them
  // exactly (see lerp_point), or the tessellated pole becomes a cluster of nearly equal points.
  const vec3_t<T> p(T(0.1), T(-2.7), T(3.15));
  const cubic_t<vec3_t<T>> P = {p, p, p, p};
  for (const T t : parameters<T>()) {
    const auto c = de_casteljau(P, t);
    CHECK(c.point == p);
    CHECK(c.derivative == vec3_t<T>(0));
  }
}

// Tests for affine.hpp (book 1.0, Def 1.0.1-1.0.3): linear vs affine maps, and normals.
#include <zraka/core/affine.hpp>
#include <zraka/core/rng.hpp>

#include <doctest/doctest.h>

#include <limits>
#include <string>

using namespace zraka;

namespace {
template <class T> vec3_t<T> random_vec(rng& g) {
  return vec3_t<T>(vec3(g.uniform(), g.uniform(), g.uniform()) * 4.0 - 2.0);
}
template <class T> affine_t<T> random_affine(rng& g) {
  affine_t<T> a;
  for (int c = 0; c < 3; ++c) a.linear[c] = random_vec<T>(g);
  a.translation = random_vec<T>(g);
  return a;
}
// Tolerance: entries and inputs are O(1), a map is 3 products and 2-3 sums per component;
// 64 eps relative to the sizes involved is generous and still catches any real mistake.
template <class T> constexpr T tol = 64 * std::numeric_limits<T>::epsilon();
}  // namespace

TEST_CASE_TEMPLATE("affine: the linear part is linear, B(alpha u + v) = alpha B(u) + B(v)", T,
                   float, double) {
  rng g(5);
  for (int i = 0; i < 1000; ++i) {
    const affine_t<T> A = random_affine<T>(g);
    const vec3_t<T> u = random_vec<T>(g), v = random_vec<T>(g);
    const T alpha = T(g.uniform() * 6 - 3);
    const vec3_t<T> lhs = A.vector(alpha * u + v), rhs = alpha * A.vector(u) + A.vector(v);
    CHECK(glm::length(lhs - rhs) <= tol<T> * (1 + glm::length(lhs)) * 10);
  }
}

TEST_CASE_TEMPLATE("affine: a translation is affine but not linear", T, float, double) {
  const affine_t<T> A = affine_t<T>::translate({T(1), T(-2), T(3)});
  const vec3_t<T> u(1, 1, 0), v(0, 2, 5);
  const T alpha = 2;
  CHECK_FALSE(A.is_linear());
  CHECK(A.point(vec3_t<T>(0)) != vec3_t<T>(0));  // a linear map fixes 0
  CHECK(A.point(alpha * u + v) != alpha * A.point(u) + A.point(v));
  // ... yet it keeps differences (vectors) and affine combinations (weights summing to 1).
  CHECK(A.point(u) - A.point(v) == u - v);
  CHECK(A.vector(u) == u);
  const T w = T(0.25);
  CHECK(glm::length(A.point((1 - w) * u + w * v) - ((1 - w) * A.point(u) + w * A.point(v))) <= tol<T> * 8);
  CHECK(affine_t<T>::scale({T(2), T(3), T(4)}).is_linear());
}

TEST_CASE_TEMPLATE("affine: normals stay perpendicular under non-uniform scale", T, float, double) {
  rng g(6);
  const affine_t<T> S = affine_t<T>::scale({T(1), T(10), T(0.01)});
  const affine_t<T> M = affine_t<T>::rotate({T(1), T(1), T(0)}, T(0.7)) * S *
                        affine_t<T>::translate({T(5), T(0), T(0)});
  double worst = 0, worst_naive = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3_t<T> n = normalize_or_zero(random_vec<T>(g));
    // A tangent of the plane with normal n.
    const vec3_t<T> t = normalize_or_zero(glm::cross(n, random_vec<T>(g)));
    const vec3_t<T> t2 = normalize_or_zero(M.vector(t)), n2 = M.normal(n);
    worst = std::max(worst, double(std::abs(glm::dot(t2, n2))));
    worst_naive = std::max(worst_naive, double(std::abs(glm::dot(t2, normalize_or_zero(M.vector(n))))));
    CHECK(std::abs(glm::length(n2) - T(1)) <= tol<T>);
  }
  MESSAGE(std::string(sizeof(T) == 4 ? "[float]" : "[double]") << " worst |t'.n'| with the inverse transpose " << worst << "; transforming n like a "
          << "vector gives " << worst_naive);
  // Tolerance: the inverse of a matrix with condition ~1000 loses 3 digits: 1000 * 64 eps.
  CHECK(worst <= 1000 * double(tol<T>));
  CHECK(worst_naive > 0.5);  // the wrong way is visibly wrong
}

TEST_CASE_TEMPLATE("affine: composition applies the right factor first", T, float, double) {
  const affine_t<T> S = affine_t<T>::scale({T(2), T(2), T(2)});
  const affine_t<T> Tr = affine_t<T>::translate({T(1), T(0), T(0)});
  const vec3_t<T> x(1, 1, 1);
  CHECK((S * Tr).point(x) == S.point(Tr.point(x)));  // (2*(x+1))
  CHECK((Tr * S).point(x) == Tr.point(S.point(x)));  // 2x + 1
  CHECK((S * Tr).point(x) == vec3_t<T>(4, 2, 2));
  CHECK((Tr * S).point(x) == vec3_t<T>(3, 2, 2));
  rng g(7);
  for (int i = 0; i < 200; ++i) {
    const affine_t<T> A = random_affine<T>(g), B = random_affine<T>(g);
    const vec3_t<T> p = random_vec<T>(g);
    CHECK(glm::length((A * B).point(p) - A.point(B.point(p))) <= tol<T> * 40);
  }
}

TEST_CASE_TEMPLATE("affine: rotations are right-handed and keep lengths", T, float, double) {
  const affine_t<T> R = affine_t<T>::rotate({T(0), T(0), T(1)}, pi<T> / 2);
  const vec3_t<T> y = R.vector({T(1), T(0), T(0)});
  CHECK(glm::length(y - vec3_t<T>(0, 1, 0)) <= tol<T>);  // x turns towards y about +z
  const vec3_t<T> v(0.3, -2, 1.5);
  CHECK(glm::length(R.vector(v)) == doctest::Approx(glm::length(v)));
  CHECK(R.is_linear());
}

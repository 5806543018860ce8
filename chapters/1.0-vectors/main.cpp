// Chapter 1.0 — vectors, linear and affine maps. Checks, with numbers, the definitions of book
// page 1.0: a matrix map is linear, a translation is affine but not linear, dot/norm/cross and
// ||a x b|| = ||a|| ||b|| sin(theta) = the parallelogram's area, an orthonormal basis built from
// a normal, and why normals are transformed by the inverse transpose.
#include <zraka/core/affine.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/onb.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/core/vec.hpp>

#include <zraka/app/cli.hpp>

#include <cstdio>
#include <string>
#include <vector>

namespace {
using namespace zraka;

std::string str(const vec3& v) {
  char s[96];
  std::snprintf(s, sizeof s, "(%.6g, %.6g, %.6g)", v.x + 0.0, v.y + 0.0, v.z + 0.0);  // no -0
  return s;
}

vec3 from_option(const std::vector<double>& x, const char* name) {
  const vec3 v(x[0], x[1], x[2]);
  if (!is_finite(v) || v == vec3(0))
    throw error(std::string(name) + " must be a non-zero finite vector, got " + str(v));
  return v;
}

// Counts the checks; a failed check is a bug in zraka, so the program will exit with 1.
struct checks {
  int passed = 0, failed = 0;
  double worst = 0;  // worst rounding-size error among the checks that should be exact
  void expect(bool ok, const char* what) {
    ok ? ++passed : ++failed;
    std::printf("   check: %s ... %s\n", what, ok ? "ok" : "FAILED");
  }
  void small(double err, double tol, const char* what) {
    worst = std::max(worst, err);
    expect(err <= tol, what);
  }
};
}  // namespace

int main(int argc, char** argv) {
  std::vector<double> a_in{2, 1, 0}, b_in{1, 3, 0.5}, n_in{0, 0, -1};
  std::uint64_t seed = 1;
  zraka::cli_app app{"Chapter 1.0: vectors, linear and affine maps (checks the definitions numerically)"};
  app.add_option("--a", a_in, "vector a (3 numbers)")->expected(3);
  app.add_option("--b", b_in, "vector b (3 numbers)")->expected(3);
  app.add_option("--normal", n_in, "a normal to build an orthonormal basis around")->expected(3);
  app.add_option("--seed", seed, "seed for the random linearity test");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return guarded([&] {
    const stopwatch clock;
    const vec3 a = from_option(a_in, "--a"), b = from_option(b_in, "--b");
    const vec3 n = normalize_or_zero(from_option(n_in, "--normal"));
    const double u = std::numeric_limits<double>::epsilon() / 2;  // unit roundoff
    checks ck;

    // [listing linear]
    // 1. A matrix map B is linear: B(alpha u + v) = alpha B(u) + B(v)  (Def 1.0.1).
    const affine B = affine::scale({2, 1, 0.5}) * affine::rotate({0, 0, 1}, pi<double> / 6);
    rng g(seed);
    double worst_linear = 0;
    for (int i = 0; i < 1000; ++i) {
      const vec3 x(g.uniform() - 0.5, g.uniform() - 0.5, g.uniform() - 0.5);
      const vec3 y(g.uniform() - 0.5, g.uniform() - 0.5, g.uniform() - 0.5);
      const double alpha = 4 * g.uniform() - 2;
      const vec3 lhs = B.vector(alpha * x + y), rhs = alpha * B.vector(x) + B.vector(y);
      worst_linear = std::max(worst_linear, glm::length(lhs - rhs) / (1 + glm::length(lhs)));
    }
    // [end]
    std::printf("1. B = scale(2, 1, 0.5) * rotate_z(30 deg) is linear (Def 1.0.1)\n");
    std::printf("   B(alpha u + v) - (alpha B(u) + B(v)), worst of 1000 random (seed %llu): %.3g "
                "(relative; u = %.3g)\n", static_cast<unsigned long long>(seed), worst_linear, u);
    ck.small(worst_linear, 16 * u, "linear up to rounding");

    // 2. A translation is affine but not linear (Def 1.0.2, 1.0.3).
    const affine A = affine::translate({1, -2, 3});
    const vec3 x(1, 1, 0), y(0, 2, 5);
    const double alpha = 2;
    const vec3 gap = A.point(alpha * x + y) - (alpha * A.point(x) + A.point(y));
    std::printf("2. A(x) = x + t, t = %s, is not linear (Def 1.0.2)\n", str(A.translation).c_str());
    std::printf("   A(0) = %s (a linear map keeps 0 fixed)\n", str(A.point(vec3(0))).c_str());
    std::printf("   A(2x + y) - (2 A(x) + A(y)) = %s = -(alpha) t, not 0\n", str(gap).c_str());
    std::printf("   but A(x) - A(y) = %s = x - y: differences (vectors) are unchanged\n",
                str(A.point(x) - A.point(y)).c_str());
    ck.expect(A.point(vec3(0)) != vec3(0) && gap == -alpha * A.translation, "translation not linear");
    ck.expect(A.point(x) - A.point(y) == x - y, "translation keeps differences");
    const affine M = A * B;  // Def 1.0.3: M(x) = B x + t
    std::printf("   M = A * B is affine: M(x) = B x + t; M(0) = %s, B(x) + t = %s, M(x) = %s\n",
                str(M.point(vec3(0))).c_str(), str(B.vector(x) + A.translation).c_str(),
                str(M.point(x)).c_str());
    ck.small(glm::length(M.point(x) - (B.vector(x) + A.translation)) / glm::length(M.point(x)),
             8 * u, "affine = linear + translation");

    // [listing cross]
    // 3. Dot, norm, cross (Def 1.0.4-1.0.6) and ||a x b|| = ||a|| ||b|| sin(theta) (Remark 1.0.7).
    const vec3 c = glm::cross(a, b);
    const double theta = std::acos(std::clamp(glm::dot(a, b) / (glm::length(a) * glm::length(b)), -1.0, 1.0));
    const double by_sine = glm::length(a) * glm::length(b) * std::sin(theta);
    // The parallelogram's area as base times height, with no angle and no cross product:
    // the height is the distance of b from the line through a.
    const vec3 b_perp = b - (glm::dot(b, a) / glm::dot(a, a)) * a;
    const double base_height = glm::length(a) * glm::length(b_perp);
    // [end]
    std::printf("3. a = %s, b = %s (Def 1.0.4-1.0.6)\n", str(a).c_str(), str(b).c_str());
    std::printf("   a.b = %.6g   ||a|| = %.6g   ||b|| = %.6g   theta = %.6g deg\n", glm::dot(a, b),
                glm::length(a), glm::length(b), theta * 180 / pi<double>);
    std::printf("   a x b = %s   (a x b).a = %.3g   (a x b).b = %.3g\n", str(c).c_str(),
                glm::dot(c, a), glm::dot(c, b));
    std::printf("   ||a x b|| = %.15g\n   ||a|| ||b|| sin(theta) = %.15g\n"
                "   base * height = %.15g   (Remark 1.0.7: the parallelogram's area)\n",
                glm::length(c), by_sine, base_height);
    const double scale = glm::length(a) * glm::length(b);
    ck.small(std::abs(glm::dot(c, a)) / (scale * glm::length(a)) +
                 std::abs(glm::dot(c, b)) / (scale * glm::length(b)), 16 * u,
             "a x b is perpendicular to a and b");
    // acos loses digits when theta is near 0 or pi, so sin(theta) is only good to about
    // sqrt(u) there; base * height has no such trouble.
    ck.small(std::abs(glm::length(c) - base_height) / scale, 16 * u, "||a x b|| = base * height");
    // So the sine route is compared, not checked: for nearly parallel vectors it says 0.
    const double sine_off = std::abs(glm::length(c) - by_sine) / std::max(glm::length(c), 1e-300);
    std::printf("   ||a|| ||b|| sin(theta) against ||a x b||: relative difference %.2g (%s)\n", sine_off,
                sine_off <= 1e-7 ? "they agree" : "they disagree: acos lost the angle");

    // [listing onb-demo]
    // 4. An orthonormal basis around a normal (onb.hpp): t, b, n unit, perpendicular, t x b = n.
    const onb frame(n);
    // [end]
    std::printf("4. orthonormal basis around n = %s\n   t = %s\n   b = %s\n", str(n).c_str(),
                str(frame.t).c_str(), str(frame.b).c_str());
    const double ortho = std::max({std::abs(glm::dot(frame.t, frame.b)), std::abs(glm::dot(frame.t, frame.n)),
                                   std::abs(glm::dot(frame.b, frame.n)), std::abs(glm::length(frame.t) - 1),
                                   std::abs(glm::length(frame.b) - 1),
                                   glm::length(glm::cross(frame.t, frame.b) - frame.n)});
    std::printf("   worst of |t.b|, |t.n|, |b.n|, | |t|-1 |, | |b|-1 |, |t x b - n| = %.3g\n", ortho);
    ck.small(ortho, 8 * u, "orthonormal and right-handed");

    // 5. Normals under a non-uniform scale: the inverse transpose keeps them perpendicular.
    const affine S = affine::scale({1, 4, 1});
    const vec3 tangent = glm::normalize(vec3(1, -1, 0)), normal = glm::normalize(vec3(1, 1, 0));
    const double right = glm::dot(S.vector(tangent), S.normal(normal));
    const double wrong = glm::dot(glm::normalize(S.vector(tangent)), glm::normalize(S.vector(normal)));
    std::printf("5. a surface with tangent %s and normal %s, scaled by (1, 4, 1)\n",
                str(tangent).c_str(), str(normal).c_str());
    std::printf("   tangent' . (S^-T n) = %.3g;  tangent' . (S n) = %.3g (an angle of %.1f deg, not 90)\n",
                right, wrong, std::acos(wrong) * 180 / pi<double>);
    ck.small(std::abs(right), 8 * u, "normals by the inverse transpose stay perpendicular");

    std::printf("summary: %d of %d checks passed, worst rounding-size error %.3g (u = %.3g), "
                "%.3f s\n", ck.passed, ck.passed + ck.failed, ck.worst, u, clock.seconds());
    if (ck.failed) throw error(std::to_string(ck.failed) + " check(s) failed");
    return 0;
  });
}

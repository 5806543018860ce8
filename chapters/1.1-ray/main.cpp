// Chapter 1.1 — the ray R(t) = O + tD, t >= 0. Prints R(t) for several t, shows that the
// stored direction has unit length even for badly scaled inputs (where the naive v / ||v||
// overflows or underflows), and what a zero or NaN direction becomes: an invalid ray that
// nothing ever hits.
#include <zraka/core/error.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/sphere.hpp>

#include <zraka/app/cli.hpp>

#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace {
using namespace zraka;

std::string str(const vec3& v) {
  char s[112];
  std::snprintf(s, sizeof s, "(%.6g, %.6g, %.6g)", v.x + 0.0, v.y + 0.0, v.z + 0.0);  // no -0
  return s;
}
}  // namespace

int main(int argc, char** argv) {
  std::vector<double> o_in{1, 0, 2}, d_in{2, -1, -2}, ts{0, 0.5, 1, 2, 10, -1};
  zraka::cli_app app{"Chapter 1.1: rays R(t) = O + tD with a unit direction"};
  app.add_option("--origin", o_in, "ray origin O (3 numbers)")->expected(3);
  app.add_option("--direction", d_in, "ray direction (3 numbers; any length, even 0)")->expected(3);
  app.add_option("--t", ts, "parameters t at which to print R(t)")->expected(1, 64);
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return guarded([&] {
    const stopwatch clock;
    const vec3 O(o_in[0], o_in[1], o_in[2]), d(d_in[0], d_in[1], d_in[2]);
    if (!is_finite(O)) throw error("--origin must be finite, got " + str(O));
    for (double t : ts)
      if (!std::isfinite(t)) throw error("--t values must be finite, got " + std::to_string(t));

    // 1. The ray and its points.
    // [listing ray-demo]
    const ray r(O, d);  // the constructor normalises d
    // [end]
    std::printf("1. O = %s, input direction %s\n", str(O).c_str(), str(d).c_str());
    std::printf("   stored D = %s, ||D|| - 1 = %.3g, valid: %s\n", str(r.direction).c_str(),
                glm::length(r.direction) - 1, r.valid() ? "yes" : "no (zero direction)");
    std::printf("   %8s  %-36s %s\n", "t", "R(t) = O + tD", "||R(t) - O||");
    for (double t : ts)
      std::printf("   %8g  %-36s %.6g%s\n", t, str(r.at(t)).c_str(), glm::length(r.at(t) - O),
                  t < 0 ? "  (t < 0: on the line, not on the ray)" : "");
    if (r.valid()) std::printf("   with ||D|| = 1, ||R(t) - O|| = |t|: t measures distance\n");

    // 2. Badly scaled directions: the stored direction is unit length anyway.
    std::printf("2. the same direction scaled by s: naive v/||v|| against the stored D\n");
    std::printf("   %-10s %-30s %-12s %s\n", "s", "naive v/||v||", "||D|| - 1", "angle to d (rad)");
    double worst = 0;
    const vec3 d_unit = r.valid() ? r.direction : vec3(0, 0, 1);
    const double denorm = std::numeric_limits<double>::denorm_min();
    for (double s : {1e200, 1e-200, 1e300, 1e-300, 2e4 * denorm, -1e250}) {
      const vec3 v = d_unit * s;
      const vec3 naive = v / std::sqrt(glm::dot(v, v));  // ||v||^2 overflows or underflows
      const ray rs(O, v);
      const double len_err = std::abs(glm::length(rs.direction) - 1);
      const double ang = std::atan2(glm::length(glm::cross(rs.direction, d_unit * (s < 0 ? -1.0 : 1.0))),
                                    glm::dot(rs.direction, d_unit * (s < 0 ? -1.0 : 1.0)));
      worst = std::max(worst, len_err);
      const bool subnormal = std::abs(v.x) < std::numeric_limits<double>::min() && v.x != 0;
      std::printf("   %-10.3g %-30s %-12.3g %.3g%s\n", s, str(naive).c_str(), len_err, ang,
                  subnormal ? "  (v is subnormal: v itself has lost bits)" : "");
    }
    // float overflows much sooner: ||v||^2 > 3.4e38 for components above 1.8e19.
    double worst_f = 0;
    for (float s : {1e30f, 1e-30f}) {
      const rayf rf(vec3f(0), vec3f(d_unit) * s);
      const double len_err = std::abs(double(glm::length(rf.direction)) - 1);
      worst_f = std::max(worst_f, len_err);
      std::printf("   %-10.3g (float) stored ||D|| - 1 = %.3g\n", double(s), len_err);
    }

    // 3. A zero (or NaN) direction makes an invalid ray: zero direction, valid() false, and
    //    no intersection routine reports a hit for it.
    const sphere ball{O + vec3(0, 0, -3), 1};
    std::printf("3. degenerate directions (a sphere of radius 1 sits 3 below O)\n");
    for (const vec3& bad : {vec3(0), vec3(std::numeric_limits<double>::quiet_NaN(), 0, -1),
                            vec3(0, 0, -std::numeric_limits<double>::infinity()), vec3(0, 0, -1)}) {
      const ray rb(O, bad);
      hit h;
      const bool got = intersect(ball, rb, 0.0, infinity<double>, h);
      std::printf("   input %-26s -> D = %-16s valid: %-3s R(5) = %-22s hits the sphere: %s\n",
                  str(bad).c_str(), str(rb.direction).c_str(), rb.valid() ? "yes" : "no",
                  str(rb.at(5)).c_str(), got ? "yes" : "no");
    }

    std::printf("summary: %zu points printed; stored ||D|| - 1 at most %.3g (double, inputs scaled "
                "1e-300..1e300), %.3g (float, 1e-30..1e30); zero/NaN/inf directions give invalid "
                "rays; %.3f s\n", ts.size(), worst, worst_f, clock.seconds());
    return 0;
  });
}

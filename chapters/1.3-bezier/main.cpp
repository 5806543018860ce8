// Chapter 1.3 — Bezier curves and patches. Evaluates cubic curves in Bernstein form and by de
// Casteljau, in float and double, and measures each against a long double reference and against
// the clock (error against run time). Checks the derivative of Lemma 1.4.6 against the explicit
// one and against central differences. Draws one curve with its control polygon into a PNG, and
// samples a 4x4 patch into an OBJ mesh.
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/bezier.hpp>
#include <zraka/geometry/bezier_patch.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/image/image_io.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>
#include <sstream>
#include <vector>

using namespace zraka;

namespace {

// The reference: the Bernstein sum in long double (64-bit significand), one coordinate at a time.
long double reference(const cubic_t<vec3>& P, int axis, long double t) {
  const long double s = 1.0L - t;
  return s * s * s * P[0][axis] + 3.0L * s * s * t * P[1][axis] + 3.0L * s * t * t * P[2][axis] +
         t * t * t * P[3][axis];
}

struct accuracy {
  double bernstein = 0, casteljau = 0, between = 0;  // max |error| / max |P|
};

// Worst errors of both forms in precision T over all curves and parameters.
template <class T> accuracy measure_accuracy(const std::vector<cubic_t<vec3>>& curves, int steps) {
  accuracy a;
  for (const auto& Pd : curves) {
    cubic_t<vec3_t<T>> P;
    double scale = 0;
    for (int i = 0; i < 4; ++i) {
      P[i] = vec3_t<T>(Pd[i]);
      scale = std::max(scale, max_component(glm::abs(Pd[i])));
    }
    for (int k = 0; k <= steps; ++k) {
      const T t = T(k) / T(steps);
      const vec3_t<T> b = eval_bernstein(P, t), c = eval_de_casteljau(P, t);
      for (int axis = 0; axis < 3; ++axis) {
        // The reference uses the rounded control points and t, so only evaluation error counts.
        cubic_t<vec3> Pr;
        for (int i = 0; i < 4; ++i) Pr[i] = vec3(P[i]);
        const long double ref = reference(Pr, axis, static_cast<long double>(t));
        a.bernstein = std::max(a.bernstein, double(std::abs(b[axis] - ref)) / scale);
        a.casteljau = std::max(a.casteljau, double(std::abs(c[axis] - ref)) / scale);
        a.between = std::max(a.between, double(std::abs(b[axis] - c[axis])) / scale);
      }
    }
  }
  return a;
}

// Nanoseconds per evaluation of `eval`: the fastest of 5 runs of `samples` evaluations (the
// machine may be busy; the minimum is the least disturbed run). The sum keeps the work alive.
template <class T, class F>
double time_per_eval(const std::vector<cubic_t<vec3>>& curves, long samples, F eval) {
  std::vector<cubic_t<vec3_t<T>>> P(curves.size());
  for (std::size_t c = 0; c < curves.size(); ++c)
    for (int i = 0; i < 4; ++i) P[c][i] = vec3_t<T>(curves[c][i]);
  double best = infinity<double>;
  for (int run = 0; run < 5; ++run) {
    vec3_t<T> sum(0);
    stopwatch clock;
    for (long k = 0; k < samples; ++k)
      sum += eval(P[std::size_t(k) % P.size()], T(k & 1023) / T(1023));
    best = std::min(best, clock.seconds() * 1e9 / double(samples));
    if (!is_finite(sum)) throw error("non-finite sum in the timing loop");
  }
  return best;
}

// Distance from point p to the segment ab (for drawing lines with soft edges).
double segment_distance(vec2 p, vec2 a, vec2 b) {
  const vec2 ab = b - a;
  const double len2 = glm::dot(ab, ab);
  const double h = len2 > 0 ? std::clamp(glm::dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
  return glm::length(p - (a + h * ab));
}

// Paints a polyline (in pixel coordinates) with the given width: coverage falls off over one
// pixel at the edge, which anti-aliases the line.
void draw_polyline(image& img, const std::vector<vec2>& pts, double width, rgb colour) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const vec2 p(x + 0.5, y + 0.5);
      double d = infinity<double>;
      for (std::size_t i = 0; i + 1 < pts.size(); ++i)
        d = std::min(d, segment_distance(p, pts[i], pts[i + 1]));
      const float cover = float(std::clamp(width / 2 + 0.5 - d, 0.0, 1.0));
      img.at(x, y) = (1 - cover) * img.at(x, y) + cover * colour;
    }
}

void draw_dot(image& img, vec2 c, double radius, rgb colour) {
  draw_polyline(img, {c, c}, 2 * radius, colour);
}

// A 4x4 patch for the OBJ: a square sheet with a bump and a dip, so the shading shows.
bezier_patch example_patch() {
  bezier_patch p;
  const double height[4][4] = {
      {0, 0.2, 0.2, 0}, {0.2, 1.2, 0.4, 0.1}, {0.1, 0.3, -0.8, 0.2}, {0, 0.1, 0.2, 0}};
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) p.P[4 * row + col] = vec3(col, row, height[row][col]);
  return p;
}

std::string to_obj(const mesh& m) {
  std::ostringstream out;
  out << "# a bicubic Bezier patch sampled by zraka chapter 1.3 (bin/bezier)\n";
  for (const auto& p : m.positions) out << "v " << p.x << ' ' << p.y << ' ' << p.z << '\n';
  for (const auto& n : m.normals) out << "vn " << n.x << ' ' << n.y << ' ' << n.z << '\n';
  for (const auto& f : m.triangles)  // OBJ indices are one-based
    out << "f " << f[0] + 1 << "//" << f[0] + 1 << ' ' << f[1] + 1 << "//" << f[1] + 1 << ' '
        << f[2] + 1 << "//" << f[2] + 1 << '\n';
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.3: Bezier curves (Bernstein vs de Casteljau) and patches", take::size | take::seed | take::out};
  cli.width = 400, cli.height = 300, cli.out = "bezier.png";
  int curves_n = 1000, grid = 8;
  std::string obj = "patch.obj";
  long samples = 1'000'000;
  cli.app.add_option("--samples", samples, "evaluations per timing run (5 runs, the fastest counts)");
  cli.app.add_option("--curves", curves_n, "random curves for the accuracy comparison");
  cli.app.add_option("--obj", obj, "the sampled patch, as a Wavefront OBJ mesh");
  cli.app.add_option("--grid", grid, "patch samples per side (grid x grid cells)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height;
  const std::uint64_t seed = cli.seed;
  const std::string& out = cli.out;
  obj = output_file(obj).string();

  return guarded([&] {
    stopwatch total;
    if (samples < 1) throw error("--samples must be at least 1, got " + std::to_string(samples));
    if (curves_n < 1) throw error("--curves must be at least 1, got " + std::to_string(curves_n));
    if (grid < 1 || grid > max_tessellation_divs)
      throw error("--grid must be in 1.." + std::to_string(max_tessellation_divs) + ", got " +
                  std::to_string(grid));
    image img(width, height, rgb(1));  // checks the size before any work

    // Random cubics with control points in [-10, 10]^3.
    rng g(seed);
    std::vector<cubic_t<vec3>> curves(static_cast<std::size_t>(curves_n));
    for (auto& P : curves)
      for (auto& p : P) p = 20.0 * vec3(g.uniform(), g.uniform(), g.uniform()) - 10.0;

    // 1. Error against run time, float and double.
    const int steps = 256;
    const accuracy af = measure_accuracy<float>(curves, steps);
    const accuracy ad = measure_accuracy<double>(curves, steps);
    auto bern = [](const auto& P, auto t) { return eval_bernstein(P, t); };
    auto cast = [](const auto& P, auto t) { return eval_de_casteljau(P, t); };
    const double tbf = time_per_eval<float>(curves, samples, bern);
    const double tcf = time_per_eval<float>(curves, samples, cast);
    const double tbd = time_per_eval<double>(curves, samples, bern);
    const double tcd = time_per_eval<double>(curves, samples, cast);
    std::printf("error relative to max|P| (vs long double), %d curves x %d parameters:\n", curves_n,
                steps + 1);
    std::printf("  %-8s %-14s %12s %10s\n", "type", "method", "max error", "ns/eval");
    std::printf("  %-8s %-14s %12.3g %10.2f\n", "float", "Bernstein", af.bernstein, tbf);
    std::printf("  %-8s %-14s %12.3g %10.2f\n", "float", "de Casteljau", af.casteljau, tcf);
    std::printf("  %-8s %-14s %12.3g %10.2f\n", "double", "Bernstein", ad.bernstein, tbd);
    std::printf("  %-8s %-14s %12.3g %10.2f\n", "double", "de Casteljau", ad.casteljau, tcd);
    std::printf("max |Bernstein - de Casteljau| / max|P|: float %.3g, double %.3g\n", af.between,
                ad.between);

    // 2. The derivative: Lemma 1.4.6 against the explicit weights and central differences.
    double lemma_vs_explicit = 0, lemma_vs_fd = 0;
    const double h = 1e-5;  // about cbrt(eps): truncation ~h^2 and rounding ~eps/h balance
    for (const auto& P : curves)
      for (int k = 0; k <= steps; ++k) {
        const double t = double(k) / steps;
        const vec3 lemma = de_casteljau(P, t).derivative;
        const vec3 fd = (eval_de_casteljau(P, t + h) - eval_de_casteljau(P, t - h)) / (2 * h);
        lemma_vs_explicit = std::max(lemma_vs_explicit,
                                     max_component(glm::abs(lemma - derivative_bernstein(P, t))));
        lemma_vs_fd = std::max(lemma_vs_fd, max_component(glm::abs(lemma - fd)));
      }
    std::printf(
        "derivative (double): max |lemma - explicit| = %.3g, max |lemma - central "
        "difference| = %.3g\n",
        lemma_vs_explicit, lemma_vs_fd);

    // [listing draw]
    // 3. One curve and its control polygon, mapped from [0,1]^2 to pixels (y up on the page),
    // with de Casteljau's construction at t = 0.4: levels 1 and 2, whose last segment is the
    // tangent (Lemma 1.4.6), and the point P(0.4).
    const cubic_t<vec2> C = {vec2(0.0, 0.1), vec2(0.2, 1.0), vec2(0.75, 0.0), vec2(1.0, 0.8)};
    const double margin = 0.08 * std::min(width, height);
    auto to_pixel = [&](vec2 q) {
      return vec2(margin + q.x * (width - 2 * margin),
                  height - margin - q.y * (height - 2 * margin));
    };
    std::vector<vec2> polygon, curve;
    for (const vec2& q : C) polygon.push_back(to_pixel(q));
    for (int k = 0; k <= 200; ++k) curve.push_back(to_pixel(eval_de_casteljau(C, k / 200.0)));
    const double t = 0.4;
    const std::vector<vec2> level1 = {to_pixel(lerp_point(C[0], C[1], t)),
                                      to_pixel(lerp_point(C[1], C[2], t)),
                                      to_pixel(lerp_point(C[2], C[3], t))};
    const std::vector<vec2> level2 = {lerp_point(level1[0], level1[1], t),
                                      lerp_point(level1[1], level1[2], t)};
    draw_polyline(img, polygon, 1.5, rgb(0.45f, 0.5f, 0.7f));
    draw_polyline(img, level1, 1.0, rgb(0.3f, 0.65f, 0.3f));
    draw_polyline(img, curve, 3.0, rgb(0.75f, 0.1f, 0.05f));
    draw_polyline(img, level2, 2.0, rgb(0.95f, 0.65f, 0.0f));
    for (const vec2& q : level1) draw_dot(img, q, 2.5, rgb(0.3f, 0.65f, 0.3f));
    for (const vec2& q : level2) draw_dot(img, q, 2.5, rgb(0.95f, 0.65f, 0.0f));
    for (const vec2& q : polygon) draw_dot(img, q, 4.0, rgb(0.05f, 0.1f, 0.4f));
    draw_dot(img, to_pixel(eval_de_casteljau(C, t)), 4.0, rgb(0, 0, 0));
    // [end]
    write_image(img, out);
    std::printf(
        "wrote %s: the curve (red), its control polygon (blue), de Casteljau at t = 0.4 "
        "(green, orange: the tangent)\n",
        out.c_str());

    // 4. A sampled 4x4 patch as an OBJ mesh (positions, patch normals, triangles).
    mesh m;
    tessellate_patch(example_patch(), grid, affine{}, m);
    write_file_atomically(obj, to_obj(m));
    std::printf("wrote %s: %zu vertices, %zu triangles\n", obj.c_str(), m.positions.size(),
                m.triangle_count());

    std::printf(
        "done in %.2f s: float/double max error Bernstein %.2g/%.2g, de Casteljau "
        "%.2g/%.2g; ns per evaluation %.1f/%.1f vs %.1f/%.1f\n",
        total.seconds(), af.bernstein, ad.bernstein, af.casteljau, ad.casteljau, tbf, tbd, tcf,
        tcd);
    return 0;
  });
}

// Every sampler of sampling.hpp against its own pdf: chi-square goodness of fit, the pdf
// integrating to one, pdf(sample) > 0 and finite, and the extreme cones.
#include <doctest/doctest.h>

#include <sstream>
#include <string>
#include <zraka/app/chi_square.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/sampling/sampling.hpp>

using namespace zraka;

namespace {

// All chi-square tests of this file together reject a correct sampler with probability 1%:
// each uses the Sidak-corrected level for this many tests (16 per scalar type).
constexpr int chi2_tests = 32;
const double chi2_level = sidak_level(0.01, chi2_tests);
constexpr long chi2_samples = 200000;

template <class T>
vec2_t<T> uniform2(rng& g) {
  if constexpr (std::is_same_v<T, float>)
    return {g.uniform_float(), g.uniform_float()};
  else
    return g.uniform2();
}

template <class T>
const char* type_name() {
  return std::is_same_v<T, float> ? "float" : "double";
}

void report(const char* what, const char* type, const chi_square_result& r) {
  std::ostringstream m;
  m << what << " <" << type << ">: X^2 = " << r.statistic << ", dof = " << r.dof
    << ", p = " << r.p_value << " (reject below " << chi2_level << ")";
  MESSAGE(m.str());
  CHECK(r.impossible == 0);
  CHECK(r.p_value > chi2_level);
}

// A local-frame direction sampler against its pdf over a (cos theta, phi) grid.
template <class T, class S, class P>
void check_directions(const char* what, S sample, P pdf, const grid2& g, std::uint64_t seed) {
  rng gen(seed);
  const auto r = chi_square_directions([&] { return sample(uniform2<T>(gen)); },
                                       [&](const vec3& w) { return double(pdf(vec3_t<T>(w))); },
                                       chi2_samples, g);
  report(what, type_name<T>(), r);
}

// The integral of a direction pdf over the sphere, by the midpoint rule in (cos theta, phi).
template <class P>
double integrate_sphere(P pdf, double cos_min = -1, int n = 400) {
  const auto e = expected_counts(
      direction_grid(n, n, cos_min),
      [&](double c, double phi) { return double(pdf(direction_from_coords(c, phi))); }, 1.0, 1);
  double s = 0;
  for (double x : e) s += x;
  return s;
}

// pdf(sample) is positive and finite for many samples.
template <class T, class S, class P>
void check_consistent(S sample, P pdf, std::uint64_t seed) {
  rng gen(seed);
  int bad = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto w = sample(uniform2<T>(gen));
    const double p = double(pdf(w));
    if (!(p > 0) || !std::isfinite(p) || !is_finite(w)) ++bad;
  }
  CHECK(bad == 0);
}

}  // namespace

TEST_CASE_TEMPLATE("the linear pdf p(r) = r/2 of book 1.6, sampled by inversion r = 2 sqrt(u)", T,
                   float, double) {
  rng gen(1);
  const auto r = chi_square_2d(
      [&]() -> std::optional<vec2> { return vec2(double(sample_linear(uniform2<T>(gen).x)), 0.5); },
      [](double x, double) { return double(linear_pdf(T(x))); }, chi2_samples,
      grid2{40, 1, 0, 2, 0, 1});
  report("linear r/2", type_name<T>(), r);
  // Its integral over [0,2] is 1 (midpoint rule is exact for a linear function: 1e-12 rounding).
  double s = 0;
  for (double e : expected_counts(
           grid2{1000, 1, 0, 2, 0, 1}, [](double x, double) { return double(linear_pdf(T(x))); },
           1.0, 1))
    s += e;
  CHECK(s == doctest::Approx(1).epsilon(1e-6));
  CHECK(sample_linear(T(0)) == T(0));
  CHECK(sample_linear(T(1)) < T(2));  // u = 1 is clamped below one
  CHECK(linear_pdf(T(-0.1)) == T(0));
  CHECK(linear_pdf(T(2.1)) == T(0));
}

TEST_CASE_TEMPLATE("the concentric disk is uniform, pdf 1/pi", T, float, double) {
  // Binned over (r^2, phi), in which dA = 1/2 d(r^2) d(phi): the density there is pdf/2.
  rng gen(2);
  const auto r = chi_square_2d(
      [&]() -> std::optional<vec2> {
        const vec2_t<T> p = sample_disk_concentric(uniform2<T>(gen));
        double phi = std::atan2(double(p.y), double(p.x));
        if (phi < 0) phi += 2 * pi<double>;
        return vec2(double(glm::dot(p, p)), phi);
      },
      [](double r2, double phi) {
        const double rr = std::sqrt(r2);
        return 0.5 * double(disk_pdf(vec2_t<T>(T(rr * std::cos(phi)), T(rr * std::sin(phi)))));
      },
      chi2_samples, grid2{20, 32, 0, 1, 0, 2 * pi<double>});
  report("disk (concentric)", type_name<T>(), r);
  CHECK(sample_disk_concentric(vec2_t<T>(T(0.5), T(0.5))) == vec2_t<T>(0));
  rng g2(3);
  for (int i = 0; i < 1000; ++i)
    CHECK(glm::dot(sample_disk_concentric(uniform2<T>(g2)),
                   sample_disk_concentric(uniform2<T>(g2))) <= T(1.0001));
}

TEST_CASE_TEMPLATE("uniform sphere, uniform hemisphere and cosine hemisphere follow their pdfs", T,
                   float, double) {
  const grid2 g = direction_grid(20, 40);
  check_directions<T>(
      "uniform sphere", [](vec2_t<T> u) { return sample_uniform_sphere(u); },
      [](vec3_t<T>) { return uniform_sphere_pdf<T>(); }, g, 4);
  check_directions<T>(
      "uniform hemisphere", [](vec2_t<T> u) { return sample_uniform_hemisphere(u); },
      [](vec3_t<T> w) { return uniform_hemisphere_pdf(w); }, g, 5);
  check_directions<T>(
      "cosine hemisphere", [](vec2_t<T> u) { return sample_cosine_hemisphere(u); },
      [](vec3_t<T> w) { return cosine_hemisphere_pdf(w); }, g, 6);

  // Each pdf integrates to 1 over the sphere (400x400 midpoint rule: the pdfs are linear in
  // cos theta, so only rounding remains; 1e-9).
  CHECK(integrate_sphere([](const vec3&) { return uniform_sphere_pdf<T>(); }) ==
        doctest::Approx(1).epsilon(1e-6));
  CHECK(integrate_sphere([](const vec3& w) { return uniform_hemisphere_pdf(vec3_t<T>(w)); }) ==
        doctest::Approx(1).epsilon(1e-6));
  CHECK(integrate_sphere([](const vec3& w) { return cosine_hemisphere_pdf(vec3_t<T>(w)); }) ==
        doctest::Approx(1).epsilon(1e-6));

  check_consistent<T>([](vec2_t<T> u) { return sample_uniform_sphere(u); },
                      [](vec3_t<T>) { return uniform_sphere_pdf<T>(); }, 7);
  check_consistent<T>([](vec2_t<T> u) { return sample_uniform_hemisphere(u); },
                      [](vec3_t<T> w) { return uniform_hemisphere_pdf(w); }, 8);
  check_consistent<T>([](vec2_t<T> u) { return sample_cosine_hemisphere(u); },
                      [](vec3_t<T> w) { return cosine_hemisphere_pdf(w); }, 9);

  // Unit length within a few roundings (4 eps), also at the corners u = 0 and u = 1 (clamped).
  rng gen(10);
  for (int i = 0; i < 1000; ++i) {
    const vec2_t<T> u = i < 4 ? vec2_t<T>(T(i & 1), T(i >> 1)) : uniform2<T>(gen);
    for (const vec3_t<T>& w :
         {sample_uniform_sphere(u), sample_uniform_hemisphere(u), sample_cosine_hemisphere(u)})
      CHECK(std::abs(glm::length(w) - T(1)) <= 4 * std::numeric_limits<T>::epsilon());
    CHECK(sample_uniform_hemisphere(u).z > T(0));
    CHECK(sample_cosine_hemisphere(u).z > T(0));  // never on the horizon, even for u = 1
  }
}

TEST_CASE_TEMPLATE("the unit ball is uniform, pdf 3/(4 pi)", T, float, double) {
  // Binned over (r^3, cos theta), in which dV = (2 pi/3) d(r^3) d(cos theta) after integrating phi.
  rng gen(11);
  const auto r = chi_square_2d(
      [&]() -> std::optional<vec2> {
        const vec2_t<T> a = uniform2<T>(gen);
        const vec3_t<T> p = sample_unit_ball(vec3_t<T>(a.x, a.y, uniform2<T>(gen).x));
        const double len = glm::length(vec3(p));
        return vec2(len * len * len, len > 0 ? double(p.z) / len : 0.0);
      },
      [](double r3, double c) {
        const vec3 p = std::cbrt(r3) * direction_from_coords(c, 0);
        return 2 * pi<double> / 3 * double(unit_ball_pdf(vec3_t<T>(p * (1 - 1e-7))));
      },
      chi2_samples, grid2{20, 20, 0, 1, -1, 1});
  report("unit ball", type_name<T>(), r);
}

TEST_CASE_TEMPLATE("cones of 30, 60 and 90 degrees and the full sphere are uniform in solid angle",
                   T, float, double) {
  int seed = 20;
  for (double deg : {30.0, 60.0, 90.0, 180.0}) {
    const double theta = deg * pi<double> / 180;
    const T h = deg == 180 ? T(2) : T(1 - std::cos(theta));  // 1 - cos(theta_max)
    // The grid ends exactly at the cone's edge, so no bin straddles the pdf's discontinuity.
    const grid2 g = direction_grid(20, 30, 1 - double(h));
    const std::string what = "cone " + std::to_string(int(deg)) + " deg";
    check_directions<T>(
        what.c_str(), [h](vec2_t<T> u) { return sample_cone(u, h); },
        [h](vec3_t<T>) { return cone_pdf(h); }, g, std::uint64_t(seed++));
    // The pdf integrates to 1 over the cone (constant: exact up to rounding).
    CHECK(integrate_sphere(
              [h](const vec3& w) { return in_cone(vec3_t<T>(w), h) ? double(cone_pdf(h)) : 0.0; },
              1 - double(h), 100) == doctest::Approx(1).epsilon(1e-4));
    check_consistent<T>([h](vec2_t<T> u) { return sample_cone(u, h); },
                        [h](vec3_t<T> w) { return in_cone(w, h) ? cone_pdf(h) : T(0); },
                        std::uint64_t(seed++));
  }
}

TEST_CASE_TEMPLATE("tiny, far, near-full and inside cones: no cancellation, no NaN", T, float,
                   double) {
  // 1 - cos(theta_max) for r/d = 1e-6 is 5e-13: the naive 1 - sqrt(1 - s^2) gives 0 in float
  // (and only 1 digit in double). Ours is within 1e-6 relative of s^2/2 (the next term is s^4/8).
  const T h_tiny = cone_one_minus_cos(T(1e-6), T(1));
  CHECK(double(h_tiny) == doctest::Approx(0.5e-12).epsilon(1e-6));
  CHECK(double(cone_one_minus_cos(T(1), T(1e6))) == doctest::Approx(0.5e-12).epsilon(1e-6));
  // Far beyond the range of T (s^2 underflows): the cone is clamped to the smallest normal number,
  // so the pdf stays finite.
  CHECK(cone_one_minus_cos(T(1e-30), T(1e30)) > T(0));
  CHECK(std::isfinite(cone_pdf(cone_one_minus_cos(T(1e-30), T(1e30)))));
  // Radii and distances whose squares overflow T still work (r/d is formed first).
  CHECK(double(cone_one_minus_cos(T(1e30), T(2e30))) ==
        doctest::Approx(1 - std::sqrt(0.75)).epsilon(1e-6));
  // Inside or on the sphere: every direction.
  CHECK(cone_one_minus_cos(T(1), T(1)) == T(2));
  CHECK(cone_one_minus_cos(T(2), T(1)) == T(2));

  const T near_full = cone_one_minus_cos(T(1), T(1) + T(1e-7));
  CHECK(near_full < T(1));
  CHECK(near_full > T(0.99));
  rng gen(40);
  for (T h : {h_tiny, near_full, cone_one_minus_cos(T(1e-30), T(1e30)), T(2)}) {
    const T p = cone_pdf(h);
    CHECK(std::isfinite(p));
    CHECK(p > T(0));
    for (int i = 0; i < 1000; ++i) {
      const vec3_t<T> w = sample_cone(uniform2<T>(gen), h);
      REQUIRE(is_finite(w));
      CHECK(std::abs(glm::length(w) - T(1)) <= 4 * std::numeric_limits<T>::epsilon());
      CHECK(in_cone(w, h));  // inside its own cone, also when cos(theta) rounds to 1
    }
  }
  // The tiny cone's directions really spread over its width: sin(theta) up to about r/d.
  double max_sin = 0;
  for (int i = 0; i < 1000; ++i) {
    const vec3_t<T> w = sample_cone(uniform2<T>(gen), h_tiny);
    max_sin = std::max(max_sin, std::hypot(double(w.x), double(w.y)));
  }
  CHECK(max_sin > 0.9e-6);
  CHECK(max_sin <= 1.0e-6 * 1.0001);

  // The world-frame cone towards a small far sphere: directions hit the sphere.
  const vec3_t<T> from(1, 2, 3), center(T(1) + T(1e3), 2, 3);
  const cone_t<T> cone(from, center, T(1e-3));
  for (int i = 0; i < 100; ++i) {
    const vec3_t<T> w = cone.sample(uniform2<T>(gen));
    const vec3 to_c = vec3(center - from);
    const double miss =
        glm::length(glm::cross(to_c, vec3(w)));  // distance of the line from the centre
    CHECK(miss <= 1e-3 * (1 + 1e-3) + 1e3 * 8 * double(std::numeric_limits<T>::epsilon()));
    CHECK(cone.pdf(w) > T(0));
  }
  // From the centre of the sphere itself the cone is the whole sphere.
  const cone_t<T> inside(center, center, T(1));
  CHECK(inside.pdf(inside.sample(vec2_t<T>(T(0.3), T(0.7)))) == uniform_sphere_pdf<T>());
}

TEST_CASE_TEMPLATE("the Phong lobe of exponent 1, 10, 100 follows (s+1)/(2 pi) cos^s", T, float,
                   double) {
  int seed = 50;
  for (double s : {1.0, 10.0, 100.0}) {
    // Bins over the part of the lobe that holds all but 1e-3 of its mass; the rest is one bin.
    const double c_min = std::pow(1e-3, 1 / (s + 1));
    const std::string what = "phong lobe s=" + std::to_string(int(s));
    check_directions<T>(
        what.c_str(), [s](vec2_t<T> u) { return sample_phong_lobe(u, T(s)); },
        [s](vec3_t<T> w) { return phong_lobe_pdf(std::min(w.z, T(1)), T(s)); },
        direction_grid(20, 20, c_min), std::uint64_t(seed++));
  }
  // The pdf integrates to 1 for every exponent up to 1e4: 1D midpoint rule over cos(alpha) with
  // 2e5 points (error ~ s^2 h^2 / 24 < 1e-3 for s = 1e4), times 2 pi for phi.
  for (double s : {1.0, 10.0, 100.0, 1e3, 1e4}) {
    const int n = 200000;
    double sum = 0;
    for (int i = 0; i < n; ++i)
      sum += double(phong_lobe_pdf(T((i + 0.5) / n), T(s))) * 2 * pi<double> / n;
    CHECK(sum == doctest::Approx(1).epsilon(2e-3));
  }
  // Shininess 1e4: directions are unit and within a few degrees of the axis, pdf finite.
  rng gen(60);
  for (int i = 0; i < 1000; ++i) {
    const vec3_t<T> w = sample_phong_lobe(uniform2<T>(gen), T(1e4));
    CHECK(std::abs(glm::length(w) - T(1)) <= 4 * std::numeric_limits<T>::epsilon());
    const T p = phong_lobe_pdf(std::min(w.z, T(1)), T(1e4));
    CHECK(std::isfinite(p));
    CHECK(p > T(0));
    CHECK(std::hypot(double(w.x), double(w.y)) > 0);  // sin(alpha) did not cancel to zero
  }
}

TEST_CASE_TEMPLATE("a triangle and a parallelogram are sampled uniformly, pdf 1/area", T, float,
                   double) {
  const vec3_t<T> p0(1, 2, 3), p1(4, -1, 2), p2(0, 5, -2);
  const vec3_t<T> e1 = p1 - p0, e2 = p2 - p0;
  // Barycentrics of a point in the plane, from the Gram matrix (independent of the sampler).
  const double g11 = glm::dot(vec3(e1), vec3(e1)), g12 = glm::dot(vec3(e1), vec3(e2)),
               g22 = glm::dot(vec3(e2), vec3(e2));
  const double det = g11 * g22 - g12 * g12;
  auto coords = [&](const vec3_t<T>& p) {
    const vec3 q = vec3(p) - vec3(p0);
    const double a = glm::dot(q, vec3(e1)), b = glm::dot(q, vec3(e2));
    return vec2((g22 * a - g12 * b) / det, (g11 * b - g12 * a) / det);
  };

  // Triangle: bins are the n^2 congruent triangles of a regular subdivision, so each bin's
  // expected count is exact: n_samples * pdf * area / n^2 (pdf evaluated at the bin's centroid).
  {
    constexpr int n = 10;
    // Bin (i, j, upper): cell (i, j) of the n x n grid in barycentrics (b1, b2), cut by its
    // diagonal; only cells with i + j < n lie in the triangle (upper ones need i + j + 1 < n).
    auto index = [](int i, int j, int upper) { return std::size_t((j * n + i) * 2 + upper); };
    std::vector<double> observed(2 * n * n, 0.0), expected(2 * n * n, 0.0);
    rng gen(70);
    for (long k = 0; k < chi2_samples; ++k) {
      const vec2 b = coords(sample_triangle(uniform2<T>(gen), p0, p1, p2));
      const double x = std::clamp(b.x * n, 0.0, n - 1e-9), y = std::clamp(b.y * n, 0.0, n - 1e-9);
      const int i = int(x), j = int(y);
      observed[index(i, j, (x - i) + (y - j) > 1 ? 1 : 0)] += 1;
    }
    const double area = double(triangle_area(p0, p1, p2));
    for (int j = 0; j < n; ++j)
      for (int i = 0; i + j < n; ++i) {
        const double e = double(chi2_samples) * double(triangle_pdf(p0, p1, p2)) * area / (n * n);
        expected[index(i, j, 0)] = e;
        if (i + j + 1 < n) expected[index(i, j, 1)] = e;
      }
    report("triangle", type_name<T>(), chi_square_test(observed, expected));
  }
  // Parallelogram: bins over (s, t) in [0,1]^2; the density there is pdf * |e1 x e2|.
  {
    rng gen(71);
    const auto r = chi_square_2d(
        [&]() -> std::optional<vec2> {
          return coords(sample_parallelogram(uniform2<T>(gen), p0, e1, e2));
        },
        [&](double, double) {
          return double(parallelogram_pdf(e1, e2)) * glm::length(glm::cross(vec3(e1), vec3(e2)));
        },
        chi2_samples, grid2{20, 20, 0, 1, 0, 1});
    report("parallelogram", type_name<T>(), r);
  }
  // pdf = 1/area, the area by the cross product (relative 1e-5 for float rounding).
  CHECK(double(triangle_pdf(p0, p1, p2)) == doctest::Approx(2 / std::sqrt(det)).epsilon(1e-5));
  CHECK(double(parallelogram_pdf(e1, e2)) == doctest::Approx(1 / std::sqrt(det)).epsilon(1e-5));
  // Barycentrics stay in the triangle, also for u = 1.
  for (T a : {T(0), T(0.5), T(1)})
    for (T b : {T(0), T(0.5), T(1)}) {
      const vec2_t<T> w = sample_triangle_barycentric(vec2_t<T>(a, b));
      CHECK(w.x >= T(0));
      CHECK(w.y >= T(0));
      CHECK(w.x + w.y <= T(1));
    }
  // Area to solid angle: p_A d^2 / |cos|, and zero for a light seen edge-on.
  CHECK(area_to_solid_angle_pdf(T(0.5), T(4), T(-0.5)) == T(4));
  CHECK(area_to_solid_angle_pdf(T(0.5), T(4), T(0)) == T(0));
}

TEST_CASE_TEMPLATE("a mixture of a cosine lobe and a cone samples its mixture pdf", T, float,
                   double) {
  const vec3_t<T> n = normalize_or_zero(vec3_t<T>(0.2, 0.3, 1));
  using mix = mixture_t<cosine_hemisphere_t<T>, cone_t<T>, T>;
  // The cone around +z has cos(theta_max) = 0.9 (r/d = sqrt(0.19)), a bin edge of the 40 bins
  // over cos theta in [-1,1], so no bin straddles its edge; the cosine lobe is tilted.
  const mix m{cosine_hemisphere_t<T>(n),
              cone_t<T>(vec3_t<T>(0), vec3_t<T>(0, 0, 1), T(std::sqrt(0.19))), T(0.3)};
  rng gen(80);
  const auto r = chi_square_directions([&] { return m.sample(uniform2<T>(gen)); },
                                       [&](const vec3& w) { return double(m.pdf(vec3_t<T>(w))); },
                                       chi2_samples, direction_grid(40, 40), 8);
  report("mixture cosine+cone", type_name<T>(), r);
  // The mixture's pdf is the mixture of the pdfs, exactly (the same arithmetic).
  rng g2(81);
  for (int i = 0; i < 100; ++i) {
    const vec3_t<T> w = sample_uniform_sphere(uniform2<T>(g2));
    CHECK(m.pdf(w) == T(0.3) * m.a.pdf(w) + (T(1) - T(0.3)) * m.b.pdf(w));
  }
  // Weights 0 and 1 reduce to one part.
  const mix only_a{m.a, m.b, T(1)}, only_b{m.a, m.b, T(0)};
  const vec2_t<T> u(T(0.25), T(0.6));
  CHECK(only_a.sample(u) == m.a.sample(u));
  CHECK(only_b.sample(u) == m.b.sample(u));
}

TEST_CASE_TEMPLATE("the remaining pdfs integrate to one and are positive where they sample", T,
                   float, double) {
  // Disk: midpoint rule on a 2000^2 grid over [-1,1]^2; the indicator's edge costs O(1/2000)
  // relative, hence 2e-3.
  {
    const int m = 2000;
    double s = 0;
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const vec2_t<T> p(T(-1 + 2 * (i + 0.5) / m), T(-1 + 2 * (j + 0.5) / m));
        s += double(disk_pdf(p)) * 4.0 / (double(m) * m);
      }
    CHECK(s == doctest::Approx(1).epsilon(2e-3));
  }
  // Ball: the same in 3D on a 200^3 grid (edge error O(1/200): 2e-2).
  {
    const int m = 200;
    double s = 0;
    for (int k = 0; k < m; ++k)
      for (int j = 0; j < m; ++j)
        for (int i = 0; i < m; ++i) {
          const vec3_t<T> p(T(-1 + 2 * (i + 0.5) / m), T(-1 + 2 * (j + 0.5) / m),
                            T(-1 + 2 * (k + 0.5) / m));
          s += double(unit_ball_pdf(p)) * 8.0 / (double(m) * m * m);
        }
    CHECK(s == doctest::Approx(1).epsilon(2e-2));
  }
  // Triangle and parallelogram: a constant density times the area (relative 1e-6 for float).
  const vec3_t<T> p0(1, 2, 3), p1(4, -1, 2), p2(0, 5, -2), e1 = p1 - p0, e2 = p2 - p0;
  CHECK(double(triangle_pdf(p0, p1, p2) * triangle_area(p0, p1, p2)) ==
        doctest::Approx(1).epsilon(1e-6));
  CHECK(double(parallelogram_pdf(e1, e2) * glm::length(glm::cross(e1, e2))) ==
        doctest::Approx(1).epsilon(1e-6));
  // The mixture of a cosine lobe and a cone (its edge on a grid line of the 400x400 grid): 1e-4.
  using mix = mixture_t<cosine_hemisphere_t<T>, cone_t<T>, T>;
  const mix m{cosine_hemisphere_t<T>(normalize_or_zero(vec3_t<T>(0.2, 0.3, 1))),
              cone_t<T>(vec3_t<T>(0), vec3_t<T>(0, 0, 1), T(std::sqrt(0.19))), T(0.3)};
  CHECK(integrate_sphere([&](const vec3& w) { return double(m.pdf(vec3_t<T>(w))); }) ==
        doctest::Approx(1).epsilon(1e-3));

  // pdf(sample) > 0 and finite.
  rng g(90);
  for (int i = 0; i < 2000; ++i) {
    const vec2_t<T> u = uniform2<T>(g), v = uniform2<T>(g);
    const T r = sample_linear(u.x);
    CHECK(((linear_pdf(r) > T(0) && std::isfinite(linear_pdf(r))) ||
           r == T(0)));  // p(0) = 0 is the density's own zero
    CHECK(disk_pdf(sample_disk_concentric(u)) > T(0));
    CHECK(unit_ball_pdf(sample_unit_ball(vec3_t<T>(u.x, u.y, v.x))) > T(0));
    const vec3_t<T> w = m.sample(v);
    CHECK(std::isfinite(m.pdf(w)));
    CHECK(m.pdf(w) > T(0));
  }
}

#pragma once
// Pearson's chi-square goodness-of-fit test: do a sampler's samples follow its own pdf?
// (book 5.3; after the tests in pbrt). Histogram the samples over a grid of bins, integrate the
// pdf over each bin for the expected counts, pool the bins expecting fewer than 5 samples,
// compute X^2 = sum (O - E)^2 / E and its p-value, the probability that a correct sampler gives
// an X^2 at least this large. Reject when p is below the significance level; with k tests in a
// run, correct that level for repeated trials (sidak_level).
//
//     const auto r = zraka::chi_square_directions(
//         [&] { return zraka::sample_cosine_hemisphere(g.uniform2()); },  // local frame, +z up
//         [](const zraka::vec3& w) { return zraka::cosine_hemisphere_pdf(w); },
//         100000, zraka::direction_grid(20, 40));
//     CHECK(r.p_value > zraka::sidak_level(0.01, number_of_tests));
//
// Directions are binned over (cos theta, phi), where d(omega) = d(cos theta) d(phi): a pdf per
// steradian is then integrated over a bin with no Jacobian.
#include <zraka/core/vec.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

namespace zraka {

// ---------------------------------------------------------------- the incomplete gamma function
// Q(a, x) = Gamma(a, x) / Gamma(a), the regularised upper incomplete gamma function; the chi-square
// tail is p = Q(dof/2, X^2/2). Two expansions, each where it converges fast:
//  * x < a + 1: the series P(a,x) = x^a e^-x / Gamma(a+1) * sum_n x^n / ((a+1)...(a+n)), Q = 1 - P;
//  * otherwise: Legendre's continued fraction for Q, evaluated by the modified Lentz method,
//    which keeps tiny tail probabilities (1e-300) accurate instead of computing 1 - 0.99999...
// [listing gamma-q]
inline double gamma_q(double a, double x) {
  if (!(a > 0) || !(x >= 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0) return 1;
  if (std::isinf(x)) return 0;
  const double log_prefix = a * std::log(x) - x - std::lgamma(a);  // log(x^a e^-x / Gamma(a))
  constexpr double eps = 1e-16;
  if (x < a + 1) {
    double term = 1 / a, sum = term;
    for (int n = 1; n < 10000 && std::abs(term) > eps * std::abs(sum); ++n) {
      term *= x / (a + n);
      sum += term;
    }
    return std::clamp(1 - sum * std::exp(log_prefix), 0.0, 1.0);
  }
  constexpr double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < eps) break;
  }
  return std::clamp(std::exp(log_prefix) * h, 0.0, 1.0);
}
// [end]

inline double chi_square_p_value(double statistic, double dof) {
  return gamma_q(dof / 2, statistic / 2);
}

// Per-test significance so that k independent tests together reject a correct sampler with
// probability alpha: Sidak 1 - (1 - alpha)^(1/k); Bonferroni alpha/k is slightly stricter.
inline double sidak_level(double alpha, int tests) {
  return -std::expm1(std::log1p(-alpha) / tests);
}
inline double bonferroni_level(double alpha, int tests) { return alpha / tests; }

// ---------------------------------------------------------------- the statistic
struct chi_square_result {
  double statistic = 0;
  int dof = 0;           // pooled bins - 1 (the total count is fixed)
  double p_value = 1;    // 0 when a sample fell where the pdf is zero
  int bins = 0;          // bins after pooling
  long impossible = 0;   // samples observed in bins with zero expected count
};

// Bins with expected < min_expected are pooled, smallest first, into groups that each expect at
// least min_expected (a leftover group joins the smallest regular bin), because the chi-square
// distribution of X^2 needs every expected count to be reasonably large.
inline chi_square_result chi_square_test(const std::vector<double>& observed,
                                         const std::vector<double>& expected,
                                         double min_expected = 5) {
  chi_square_result r;
  std::vector<std::size_t> order(observed.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return expected[i] < expected[j]; });
  std::vector<std::pair<double, double>> groups;  // (observed, expected)
  double pool_o = 0, pool_e = 0;
  for (std::size_t i : order) {
    const double o = observed[i], e = expected[i];
    if (e <= 0) {
      r.impossible += long(o);
      continue;
    }
    if (e < min_expected || pool_e > 0) {
      pool_o += o;
      pool_e += e;
      if (pool_e >= min_expected) {
        groups.emplace_back(pool_o, pool_e);
        pool_o = pool_e = 0;
      }
    } else {
      groups.emplace_back(o, e);
    }
  }
  if (pool_e > 0) {
    if (groups.empty()) groups.emplace_back(pool_o, pool_e);
    else {
      groups.front().first += pool_o;
      groups.front().second += pool_e;
    }
  }
  for (const auto& [o, e] : groups) r.statistic += (o - e) * (o - e) / e;
  r.bins = int(groups.size());
  r.dof = r.bins - 1;
  if (r.impossible > 0) r.p_value = 0;
  else if (r.dof > 0) r.p_value = chi_square_p_value(r.statistic, r.dof);
  return r;
}

// ---------------------------------------------------------------- bins
// nx by ny rectangular bins over [x0,x1] x [y0,y1]; a 1D domain is ny = 1.
struct grid2 {
  int nx = 1, ny = 1;
  double x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  int size() const { return nx * ny; }
  // The bin holding (x, y), or none outside the grid.
  std::optional<int> bin(double x, double y) const {
    if (!(x >= x0 && x <= x1 && y >= y0 && y <= y1)) return std::nullopt;
    const int i = std::min(nx - 1, int((x - x0) / (x1 - x0) * nx));
    const int j = std::min(ny - 1, int((y - y0) / (y1 - y0) * ny));
    return j * nx + i;
  }
};

// (cos theta, phi) over the sphere, or over theta in [0, theta_max] with cos_min = cos theta_max.
inline grid2 direction_grid(int n_cos, int n_phi, double cos_min = -1) {
  return {n_cos, n_phi, cos_min, 1, 0, 2 * pi<double>};
}
template <class T> vec2 direction_coords(const vec3_t<T>& w) {
  const double len = glm::length(vec3(w));
  double phi = std::atan2(double(w.y), double(w.x));
  if (phi < 0) phi += 2 * pi<double>;
  return {std::clamp(double(w.z) / len, -1.0, 1.0), phi};
}
inline vec3 direction_from_coords(double cos_theta, double phi) {
  const double s = std::sqrt(std::max(0.0, (1 - cos_theta) * (1 + cos_theta)));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// n times the integral of density(x, y) over each bin, by the midpoint rule on sub x sub points.
template <class Density>
std::vector<double> expected_counts(const grid2& g, Density&& density, double n, int sub = 8) {
  std::vector<double> e(std::size_t(g.size()), 0.0);
  const double dx = (g.x1 - g.x0) / (g.nx * sub), dy = (g.y1 - g.y0) / (g.ny * sub);
  for (int j = 0; j < g.ny * sub; ++j)
    for (int i = 0; i < g.nx * sub; ++i) {
      const double x = g.x0 + (i + 0.5) * dx, y = g.y0 + (j + 0.5) * dy;
      e[std::size_t((j / sub) * g.nx + i / sub)] += double(density(x, y)) * dx * dy * n;
    }
  return e;
}

// The test on a 2D domain. sample() returns std::optional<vec2> (none: the sampler rejected);
// samples outside the grid and rejections each go to one extra bin, which expects whatever
// probability the pdf leaves outside the grid, so a pdf that integrates to less than one over
// the grid (a sub-probability density, like a BRDF lobe cut by the horizon) is tested exactly.
template <class Sample, class Density>
chi_square_result chi_square_2d(Sample&& sample, Density&& density, long n, const grid2& g,
                                int sub = 8, double min_expected = 5) {
  std::vector<double> observed(std::size_t(g.size()) + 1, 0.0);
  for (long k = 0; k < n; ++k) {
    const std::optional<vec2> p = sample();
    const auto b = p ? g.bin(p->x, p->y) : std::nullopt;
    observed[b ? std::size_t(*b) : observed.size() - 1] += 1;
  }
  std::vector<double> expected = expected_counts(g, density, double(n), sub);
  double inside = 0;
  for (double e : expected) inside += e;
  const double rest = double(n) - inside;
  expected.push_back(rest > 1e-6 * double(n) ? rest : 0.0);  // below: quadrature error, not mass
  return chi_square_test(observed, expected, min_expected);
}

// The test for directions in a local frame (+z up), binned over (cos theta, phi).
// sample() returns a vec3_t<T> (a zero or non-finite vector counts as a rejection) or an
// std::optional of one; pdf(w) is per steradian.
template <class Sample, class Pdf>
chi_square_result chi_square_directions(Sample&& sample, Pdf&& pdf, long n, const grid2& g,
                                        int sub = 8, double min_expected = 5) {
  auto as_optional = [](const auto& w) -> std::optional<vec3> {
    if constexpr (requires { w.has_value(); }) {
      if (!w) return std::nullopt;
      return vec3(*w);
    } else {
      return vec3(w);
    }
  };
  return chi_square_2d(
      [&]() -> std::optional<vec2> {
        const std::optional<vec3> w = as_optional(sample());
        if (!w || !is_finite(*w) || !(length2(*w) > 0)) return std::nullopt;
        return direction_coords(*w);
      },
      [&](double c, double phi) { return double(pdf(direction_from_coords(c, phi))); }, n, g,
      sub, min_expected);
}

}  // namespace zraka

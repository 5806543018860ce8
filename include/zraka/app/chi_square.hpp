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
  double p_value = 1;    // 0 when a sample fell where the pdf is zero, or the pdf's mass is > 1
  int bins = 0;          // bins after pooling
  long impossible = 0;   // samples observed in bins with zero expected count (with the extra bin's)
  // Filled by chi_square_2d (and chi_square_directions):
  long samples = 0;            // draws of the sampler
  long rejected = 0;           // draws that returned no sample (none, a zero or non-finite vector)
  long outside = 0;            // samples that fell outside the grid
  double pdf_mass = 0;         // the integral of the pdf over the grid
  double quadrature_error = 0; // its estimated error (all bins)
  int unresolved_bins = 0;     // bins whose integral missed its tolerance within the budget
  long impossible_outside = 0; // rejected or outside samples, where the pdf leaves no mass
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

// n times the integral of density(x, y) over each bin, fine enough for the test. A cell's
// integral is the k x k midpoint rule (k = sub/2); its error is estimated by splitting it in two
// along x and along y. Each bin is refined (the cell with the largest error estimate split along
// the axis that changed more) until it is within 0.05 sqrt(E + 1) expected samples of its own
// noise, so that X^2 moves by much less than its spread. Then the bins with the largest errors
// are refined further, because the extra bin of chi_square_2d expects n minus the sum of the
// others and collects their errors (GGX at alpha 0.001: 70 samples in a bin that expects none,
// X^2 = 106 for 32 dof): until the errors of all bins together, d, add at most s = 5 % of X^2's
// spread sqrt(2 m) to it (m: the bins expecting 5 or more), d <= max(s, sqrt(s rest)), s >= 0.5.
// A lobe narrower than the first points (alpha = 0.001 is 1e-6 wide in cos theta) is invisible
// to the estimate, so the samples guide it too: a cell holding 16 or more samples, 90 % of them
// in one half along an axis, is split there first. That only chooses where to look closer: a
// sampler cannot make a wrong pdf's integral look right, and mass that the pdf puts where no
// sample goes is still found where the pdf varies (else it is left to the extra bin).
// points[b] holds the samples that fell in bin b (reordered here); it may be empty.
struct adaptive_counts {
  std::vector<double> expected;
  double error = 0;       // the sum of the bins' error estimates, in samples
  int unresolved = 0;     // bins left above their own tolerance when the budget ran out
};
template <class Density>
adaptive_counts expected_counts_adaptive(const grid2& g, Density&& density, double n, int sub,
                                         std::vector<std::vector<vec2>>& points,
                                         int max_cells_per_bin = 512) {
  const int k = std::max(1, sub / 2);
  auto midpoint = [&](double x0, double x1, double y0, double y1) {
    const double dx = (x1 - x0) / k, dy = (y1 - y0) / k;
    double sum = 0;
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) sum += double(density(x0 + (i + 0.5) * dx, y0 + (j + 0.5) * dy));
    return sum * dx * dy;
  };
  struct cell {
    double x0, x1, y0, y1;
    double value;            // k x k midpoint rule over the cell
    double sx[2], sy[2];     // the same over its halves along x and along y
    std::size_t begin, end;  // its samples in points[b]
    double estimate() const { return 0.5 * (sx[0] + sx[1] + sy[0] + sy[1]); }
    double error_x() const { return std::abs(sx[0] + sx[1] - value); }
    double error_y() const { return std::abs(sy[0] + sy[1] - value); }
    double error() const { return std::max(error_x(), error_y()); }
  };
  auto make = [&](double x0, double x1, double y0, double y1, double value, std::size_t b,
                  std::size_t e) {
    cell c{x0, x1, y0, y1, value, {0, 0}, {0, 0}, b, e};
    const double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1);
    c.sx[0] = midpoint(x0, xm, y0, y1), c.sx[1] = midpoint(xm, x1, y0, y1);
    c.sy[0] = midpoint(x0, x1, y0, ym), c.sy[1] = midpoint(x0, x1, ym, y1);
    return c;
  };
  const std::size_t nb = std::size_t(g.size());
  const double bw = (g.x1 - g.x0) / g.nx, bh = (g.y1 - g.y0) / g.ny;
  points.resize(nb);
  std::vector<std::vector<cell>> cells(nb);
  std::vector<double> total(nb, 0.0), error(nb, 0.0);
  auto split = [&](std::size_t b, std::size_t at, int axis) {
    std::vector<vec2>& pts = points[b];
    const cell c = cells[b][at];
    const double xm = 0.5 * (c.x0 + c.x1), ym = 0.5 * (c.y0 + c.y1);
    const auto mid = std::partition(pts.begin() + std::ptrdiff_t(c.begin), pts.begin() + std::ptrdiff_t(c.end),
                                    [&](const vec2& p) { return axis == 0 ? p.x < xm : p.y < ym; });
    const std::size_t m = std::size_t(mid - pts.begin());
    if (axis == 0) {
      cells[b][at] = make(c.x0, xm, c.y0, c.y1, c.sx[0], c.begin, m);
      cells[b].push_back(make(xm, c.x1, c.y0, c.y1, c.sx[1], m, c.end));
    } else {
      cells[b][at] = make(c.x0, c.x1, c.y0, ym, c.sy[0], c.begin, m);
      cells[b].push_back(make(c.x0, c.x1, ym, c.y1, c.sy[1], m, c.end));
    }
  };
  // Sums the bin's cells; returns its least sure cell.
  auto tally = [&](std::size_t b) {
    std::size_t worst = 0;
    total[b] = error[b] = 0;
    for (std::size_t i = 0; i < cells[b].size(); ++i) {
      total[b] += cells[b][i].estimate();
      error[b] += cells[b][i].error();
      if (cells[b][i].error() > cells[b][worst].error()) worst = i;
    }
    return worst;
  };
  auto refine_worst = [&](std::size_t b, std::size_t worst) {
    const cell& c = cells[b][worst];
    split(b, worst, c.error_x() >= c.error_y() ? 0 : 1);
  };
  // The axis (0: x, 1: y) along which 90 % of a cell's samples lie in one half, or -1.
  auto concentrated = [&](std::size_t b, const cell& c) {
    const std::vector<vec2>& pts = points[b];
    const std::size_t m = c.end - c.begin;
    if (m < 16) return -1;
    std::size_t low_x = 0, low_y = 0;
    const double xm = 0.5 * (c.x0 + c.x1), ym = 0.5 * (c.y0 + c.y1);
    for (std::size_t i = c.begin; i < c.end; ++i) low_x += pts[i].x < xm, low_y += pts[i].y < ym;
    auto lopsided = [&](std::size_t low) { return std::max(low, m - low) * 10 >= m * 9; };
    // no further than 1e-13 of the bin (a sampler that always returns one point)
    const bool ax = c.x1 - c.x0 > 1e-13 * bw && lopsided(low_x);
    const bool ay = c.y1 - c.y0 > 1e-13 * bh && lopsided(low_y);
    if (ax && ay) return std::max(low_x, m - low_x) >= std::max(low_y, m - low_y) ? 0 : 1;
    return ax ? 0 : ay ? 1 : -1;
  };
  adaptive_counts out;
  for (std::size_t b = 0; b < nb; ++b) {
    const double x0 = g.x0 + double(int(b) % g.nx) * bw, y0 = g.y0 + double(int(b) / g.nx) * bh;
    cells[b].push_back(make(x0, x0 + bw, y0, y0 + bh, midpoint(x0, x0 + bw, y0, y0 + bh), 0, points[b].size()));
    // First where the samples crowd, then where the estimate is least sure.
    for (std::size_t i = 0; i < cells[b].size() && int(cells[b].size()) < max_cells_per_bin;) {
      const int axis = concentrated(b, cells[b][i]);
      if (axis < 0) ++i;
      else split(b, i, axis);
    }
    auto unsure = [&] { return error[b] * n > 0.05 * std::sqrt(std::max(0.0, total[b]) * n + 1); };
    for (std::size_t worst = tally(b); unsure() && int(cells[b].size()) < max_cells_per_bin; worst = tally(b))
      refine_worst(b, worst);
  }
  // All bins together, for the extra bin: refine the bin with the largest error.
  double sum = 0, sum_error = 0;
  for (std::size_t b = 0; b < nb; ++b) sum += total[b], sum_error += error[b];
  double m = 0;
  for (std::size_t b = 0; b < nb; ++b) m += total[b] * n >= 5;
  const double spread = std::max(0.5, 0.05 * std::sqrt(2 * m));
  for (long budget = 8L * long(nb) + 4096; budget > 0; --budget) {
    const double rest = std::max(0.0, 1 - sum) * n;
    if (!(sum_error * n > std::max(spread, std::sqrt(spread * rest)))) break;
    const std::size_t b = std::size_t(std::max_element(error.begin(), error.end()) - error.begin());
    sum -= total[b], sum_error -= error[b];
    std::size_t worst = 0;
    for (std::size_t i = 1; i < cells[b].size(); ++i)
      if (cells[b][i].error() > cells[b][worst].error()) worst = i;
    refine_worst(b, worst);
    tally(b);
    sum += total[b], sum_error += error[b];
  }
  out.expected.resize(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    out.expected[b] = total[b] * n, out.error += error[b] * n;
    out.unresolved += error[b] * n > 0.05 * std::sqrt(std::max(0.0, total[b]) * n + 1);
  }
  return out;
}

// The test on a 2D domain. sample() returns std::optional<vec2> (none: the sampler rejected);
// samples outside the grid and rejections each go to one extra bin, which expects whatever
// probability the pdf leaves outside the grid, so a pdf that integrates to less than one over
// the grid (a sub-probability density, like a BRDF lobe cut by the horizon) is tested exactly.
// The pdf is integrated over each bin by expected_counts_adaptive, starting from sub x sub points.
// A pdf whose integral over the grid exceeds 1 by more than the quadrature's error is rejected
// (p = 0): no sampler can follow it.
template <class Sample, class Density>
chi_square_result chi_square_2d(Sample&& sample, Density&& density, long n, const grid2& g,
                                int sub = 8, double min_expected = 5) {
  std::vector<double> observed(std::size_t(g.size()) + 1, 0.0);
  std::vector<std::vector<vec2>> points(std::size_t(g.size()));
  long rejected = 0, outside = 0;
  for (long k = 0; k < n; ++k) {
    const std::optional<vec2> p = sample();
    const auto b = p ? g.bin(p->x, p->y) : std::nullopt;
    if (!p) ++rejected;
    else if (!b) ++outside;
    else points[std::size_t(*b)].push_back(*p);
    observed[b ? std::size_t(*b) : observed.size() - 1] += 1;
  }
  adaptive_counts counts = expected_counts_adaptive(g, density, double(n), sub, points);
  std::vector<double>& expected = counts.expected;
  double inside = 0;
  for (double e : expected) inside += e;
  const double rest = double(n) - inside;
  expected.push_back(rest > 1e-6 * double(n) ? rest : 0.0);  // below: rounding, not mass
  const long impossible_outside = expected.back() > 0 ? 0 : long(observed.back());
  chi_square_result r = chi_square_test(observed, expected, min_expected);
  r.samples = n, r.rejected = rejected, r.outside = outside;
  r.pdf_mass = inside / double(n), r.quadrature_error = counts.error / double(n);
  r.unresolved_bins = counts.unresolved, r.impossible_outside = impossible_outside;
  if (-rest > counts.error + 1e-3 * double(n)) r.p_value = 0;  // the pdf integrates to more than 1
  return r;
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

// Chapter 1.6 — Monte Carlo integration. Estimates integrals by averaging random samples and
// measures how the error falls with the number of samples N and with the run time:
//   1. pi by dart throwing;  2. the integral of x^2 over [0,2] with uniform samples;
//   3. sampling the linear density p(r) = r/2 by inverting its CDF (a text histogram);
//   4. the same integral by importance sampling with p(x) = x/2, and with p ~ x^2 (zero variance);
//   5. the integral of sin(x^2) over [0,1], which has no elementary antiderivative, against a
//      long-double quadrature, uniform against importance sampling;
//   6. the comparison: variance per sample, time per sample, time to reach a given error.
// For every estimator: a table of N = 2^k, seconds, estimate, |error|, standard error, the
// fitted slope of log(error) against log(N) (expect -1/2), and a CSV file for
// tools/plot_convergence.py.
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/core/vec.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/estimator.hpp>

#include <zraka/app/program_options.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace {

using namespace zraka;

struct settings {
  std::uint64_t seed = 1;
  int min_log2n = 4, max_log2n = 20;
  std::string csv_dir = ".";
  long hist_samples = 1 << 16;
};

// [listing pi]
// Example 1.6.2: a dart (x, y) uniform in the square [-1,1]^2 lands in the unit disk with
// probability (area of disk) / (area of square) = pi/4, so 4 * [inside] has mean pi.
double pi_dart(rng& g) {
  const double x = 2 * g.uniform() - 1, y = 2 * g.uniform() - 1;
  return x * x + y * y < 1 ? 4.0 : 0.0;
}
// [end]

// [listing uniform]
// Def 1.6.1 with one sample: x uniform on [a,b] has density 1/(b-a), so (b-a) f(x) has mean
// equal to the integral of f over [a,b]. Here f(x) = x^2 on [0,2].
double x2_uniform(rng& g) {
  const double x = 2 * g.uniform();
  return (2 - 0) * x * x;
}
// [end]

// [listing inverse-cdf]
// The linear density p(r) = r/2 on [0,2] (Example 1.6.9). Its CDF is P(r) = r^2/4; solving
// P(r) = xi gives r = 2 sqrt(xi). We use xi = 1 - uniform() in (0,1], so r is never 0 and the
// weight f(r)/p(r) below never divides by p(0) = 0.
double linear_pdf(double r) { return r / 2; }
double sample_linear(rng& g) { return 2 * std::sqrt(1 - g.uniform()); }
// [end]

// [listing importance]
// Importance sampling: x drawn with density p, weight f(x)/p(x); the mean is still the integral
// of f, but the spread of f/p is smaller when p is shaped like f.
double x2_importance_linear(rng& g) {
  const double x = sample_linear(g);
  return x * x / linear_pdf(x);  // = 2x: spread over [0,4] instead of (b-a) f over [0,8]
}

// p proportional to f itself: p(x) = 3x^2/8, CDF x^3/8, x = 2 cbrt(xi). Then f/p = 8/3 for
// every x: zero variance. It needs the normalising constant 8/3, which is the answer we seek.
double quadratic_pdf(double x) { return 3 * x * x / 8; }
double x2_importance_quadratic(rng& g) {
  const double x = 2 * std::cbrt(1 - g.uniform());
  return x * x / quadratic_pdf(x);
}
// [end]

// [listing sin-x2]
// The integral of sin(x^2) over [0,1] (a Fresnel integral: no elementary antiderivative).
// Uniform samples, and importance samples from p(x) = 3x^2 (since sin(x^2) ~ x^2 near 0):
// CDF x^3, x = cbrt(xi), and the weight sin(x^2)/(3x^2) stays within [0.28, 0.34].
double sinx2_uniform(rng& g) {
  const double x = g.uniform();
  return std::sin(x * x);
}
double sinx2_importance(rng& g) {
  const double x = std::cbrt(1 - g.uniform());
  return std::sin(x * x) / (3 * x * x);
}
// [end]

// [listing quadrature]
// A reference value without Monte Carlo: composite Simpson's rule in long double, with
// compensated (Neumaier) summation so that 2^16 terms add no rounding error of their own. The
// rule's error falls as h^4; comparing n and 2n intervals estimates it (Richardson: the error of
// the finer one is about |S_2n - S_n| / 15).
template <class F> long double simpson(F f, long double a, long double b, long n) {
  const long double h = (b - a) / n;
  long double sum = 0, c = 0;  // c: the low-order bits that sum lost
  for (long i = 0; i <= n; ++i) {
    const long double w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
    const long double term = w * f(a + i * h), t = sum + term;
    c += std::fabs(sum) >= std::fabs(term) ? (sum - t) + term : (term - t) + sum;
    sum = t;
  }
  return (sum + c) * h / 3;
}
// [end]

// [listing measure]
// One convergence table: for N = 2^k, an independent stream (seed, estimator id, k), N samples
// into an estimator, the time it took, and the error against the known value.
template <class Sample>
convergence_log measure(const std::string& title, std::uint32_t id, double reference,
                        Sample sample, const settings& s) {
  convergence_log log(title);
  for (int k = s.min_log2n; k <= s.max_log2n; ++k) {
    rng g(s.seed, id, std::uint32_t(k));
    estimator e;
    const stopwatch clock;
    for (std::uint64_t i = 0; i < (std::uint64_t(1) << k); ++i) e.add(sample(g));
    log.add(clock.seconds(), e, reference);
  }
  return log;
}
// [end]

struct result {
  std::string name;
  double variance, exact_variance, ns_per_sample, slope, slope_stderr;
};

// Prints a table and its slopes, writes its CSV, and keeps the numbers for the comparison.
result report(const convergence_log& log, const std::string& csv, const std::string& name,
              double exact_variance, const settings& s) {
  std::printf("\n%s", log.table().c_str());
  if (exact_variance > 0)
    std::printf("%s   (one run per N: scatters around -0.5)\n", log.slope_line().c_str());
  else
    std::printf("abs_error is rounding only (0 or an ulp at every N): no 1/sqrt(N) to fit\n");
  std::printf("%s   (smooth: sigma/sqrt(N))\n", log.slope_line("std_error").c_str());
  const auto path = std::filesystem::path(s.csv_dir) / csv;
  log.write_csv(path);
  std::printf("wrote %s\n", path.string().c_str());
  const auto& last = log.rows().back();
  const double se = last.values[2];
  const auto f = log.fit();
  // Time per sample: the least over the larger runs, since a busy machine only ever adds time.
  double ns = 1e9 * last.seconds / double(last.n);
  for (const auto& r : log.rows())
    if (r.n >= last.n / 64) ns = std::min(ns, 1e9 * r.seconds / double(r.n));
  return {name, se * se * double(last.n), exact_variance, ns, f.slope, f.slope_stderr};
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.6: Monte Carlo integration, error against N and against run time", take::seed};
  settings s;
  cli.seed = s.seed;
  s.csv_dir = zraka::output_dir();
  cli.app.add_option("--min-log2n", s.min_log2n, "smallest run has N = 2^this samples (default 4)");
  cli.app.add_option("--max-log2n", s.max_log2n,
                     "largest run has N = 2^this samples (default 20, about 1 s in all; at most 28)");
  cli.app.add_option("--csv-dir", s.csv_dir, "folder for the CSV files (from inside the checkout: build/out)");
  cli.app.add_option("--hist-samples", s.hist_samples, "samples for the histogram of r = 2 sqrt(xi)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  s.seed = cli.seed;

  return zraka::guarded([&] {
    using namespace zraka;
    if (s.min_log2n < 1 || s.max_log2n > 28 || s.min_log2n > s.max_log2n)
      throw error("need 1 <= --min-log2n <= --max-log2n <= 28, got " +
                  std::to_string(s.min_log2n) + " and " + std::to_string(s.max_log2n));
    if (s.hist_samples < 10) throw error("--hist-samples must be at least 10");
    if (!std::filesystem::is_directory(s.csv_dir))
      throw error("--csv-dir " + s.csv_dir + " is not a folder");
    const stopwatch total;
    std::printf("Chapter 1.6: Monte Carlo integration (seed %llu, N = 2^%d .. 2^%d)\n",
                static_cast<unsigned long long>(s.seed), s.min_log2n, s.max_log2n);
    std::vector<result> results;

    // 1. pi by dart throwing. Each dart scores 4 or 0: variance 16 (pi/4)(1 - pi/4) = pi(4 - pi).
    const double pi_ = pi<double>;
    results.push_back(report(measure("1. pi by dart throwing (true value pi)", 1, pi_, pi_dart, s),
                             "1.6-pi.csv", "pi, darts", pi_ * (4 - pi_), s));

    // 2. x^2 on [0,2], uniform. Var[2 x^2] = 4 E[x^4] - (8/3)^2 = 64/5 - 64/9 = 256/45.
    const auto x2u = measure("2. integral of x^2 over [0,2], uniform samples (true value 8/3)", 2,
                             8.0 / 3, x2_uniform, s);
    const double mean_x2 = x2u.rows().back().values[0] / 2;
    results.push_back(report(x2u, "1.6-x2-uniform.csv", "x^2, uniform", 256.0 / 45, s));
    std::printf("average of x^2 over [0,2] = %.4f, so I = (b - a) * average = 2 * %.4f = %.4f"
                " (8/3 = %.4f)\n",
                mean_x2, mean_x2, 2 * mean_x2, 8.0 / 3);

    // 3. The linear density p(r) = r/2: histogram of r = 2 sqrt(xi) against p.
    {
      constexpr int bins = 10;
      std::vector<long> count(bins, 0);
      rng g(s.seed, 3, 0);
      for (long i = 0; i < s.hist_samples; ++i)
        ++count[std::size_t(std::min(bins - 1, int(sample_linear(g) / 2 * bins)))];
      std::printf("\n3. r = 2 sqrt(xi) has density p(r) = r/2 on [0,2]: %ld samples, %d bins\n",
                  s.hist_samples, bins);
      std::printf("   r from .. to   observed density   p averaged over the bin\n");
      double chi2 = 0;
      const double width = 2.0 / bins;
      for (int b = 0; b < bins; ++b) {
        const double r0 = b * width, r1 = r0 + width;
        const double prob = (r1 * r1 - r0 * r0) / 4;  // CDF(r1) - CDF(r0)
        const double expected = prob * double(s.hist_samples);
        const double observed = double(count[std::size_t(b)]) / double(s.hist_samples) / width;
        chi2 += (double(count[std::size_t(b)]) - expected) * (double(count[std::size_t(b)]) - expected) /
                expected;
        std::printf("   %4.1f .. %3.1f   %16.4f   %10.4f  %s\n", r0, r1, observed, prob / width,
                    std::string(std::size_t(std::lround(observed * 40)), '#').c_str());
      }
      std::printf("   chi^2 = %.2f with %d degrees of freedom (0.1%% critical value 27.88): %s\n",
                  chi2, bins - 1, chi2 < 27.88 ? "consistent with r/2" : "NOT consistent with r/2");
      std::printf("   a density is not a probability: p(2) = %.2f for r/2, and p(2) = %.2f for "
                  "3x^2/8; P(r = 2 exactly) = 0\n",
                  linear_pdf(2.0), quadratic_pdf(2.0));
    }

    // 4. Importance sampling of the same integral. Var[2x] with x ~ r/2: 4 E[x^2] - (8/3)^2 = 8/9.
    results.push_back(report(measure("4a. integral of x^2 over [0,2], importance p(x) = x/2", 4,
                                     8.0 / 3, x2_importance_linear, s),
                             "1.6-x2-linear.csv", "x^2, p = x/2", 8.0 / 9, s));
    results.push_back(report(measure("4b. integral of x^2 over [0,2], importance p(x) = 3x^2/8", 5,
                                     8.0 / 3, x2_importance_quadratic, s),
                             "1.6-x2-quadratic.csv", "x^2, p = 3x^2/8", 0.0, s));
    std::printf("p proportional to f: every weight is 8/3, the errors are rounding only\n");

    // 5. A reference value by quadrature, then uniform against importance sampling.
    const auto f = [](long double x) { return std::sin(x * x); };
    constexpr long n = 1 << 16;
    const long double ref = simpson(f, 0.0L, 1.0L, n), coarse = simpson(f, 0.0L, 1.0L, n / 2);
    const long double accuracy = std::fabs(ref - coarse) / 15;
    // Exact variances by the same rule: E[f^2] - I^2 (uniform) and E[(f/p)^2] under p (importance).
    const long double ef2 = simpson([&](long double x) { return f(x) * f(x); }, 0.0L, 1.0L, n);
    const long double efp = simpson(
        [&](long double x) { return x > 0 ? f(x) * f(x) / (3 * x * x) : 0.0L; }, 0.0L, 1.0L, n);
    std::printf("\n5. reference: integral of sin(x^2) over [0,1] = %.17Lf\n"
                "   (Simpson's rule in long double, %ld intervals; Richardson error estimate %.1Le;"
                " long double rounding ~1e-19)\n",
                ref, n, accuracy);
    const double I = double(ref);
    results.push_back(report(measure("5a. integral of sin(x^2) over [0,1], uniform samples", 6, I,
                                     sinx2_uniform, s),
                             "1.6-sinx2-uniform.csv", "sin(x^2), uniform", double(ef2 - ref * ref), s));
    results.push_back(report(measure("5b. integral of sin(x^2) over [0,1], importance p(x) = 3x^2",
                                     7, I, sinx2_importance, s),
                             "1.6-sinx2-importance.csv", "sin(x^2), p = 3x^2",
                             double(efp - ref * ref), s));

    // 6. The comparison. The error after N samples is about sigma/sqrt(N), so reaching error eps
    // takes N = sigma^2/eps^2 samples, i.e. sigma^2 * (time per sample) / eps^2 seconds: the
    // product variance x time is what to compare, not either alone.
    std::printf("\n6. comparison (variance: the largest run; time: the least per sample)\n");
    std::printf("   %-20s %11s %11s %10s %15s %17s\n", "estimator", "variance", "exact",
                "ns/sample", "slope", "s for error 1e-4");
    for (const auto& r : results) {
      char slope[32] = "(rounding only)";
      if (r.exact_variance > 0) std::snprintf(slope, sizeof slope, "%+.3f+-%.3f", r.slope, r.slope_stderr);
      std::printf("   %-20s %11.4g %11.4g %10.1f %15s %17.3g\n", r.name.c_str(), r.variance,
                  r.exact_variance, r.ns_per_sample, slope, r.variance * r.ns_per_sample * 1e-9 / 1e-8);
    }
    std::printf("   variance drop from importance sampling: x^2 %.1fx (exact 6.4x), sin(x^2) %.0fx\n",
                results[1].variance / results[2].variance, results[4].variance / results[5].variance);

    std::printf("\nsummary: 6 estimators, N = 2^%d..2^%d; slopes of log(error) vs log(N), "
                "zero-variance one left out:", s.min_log2n, s.max_log2n);
    for (const auto& r : results)
      if (r.exact_variance > 0) std::printf(" %+.2f", r.slope);
    std::printf(" (expect -0.5); %.2f s\n", total.seconds());
    return 0;
  });
}

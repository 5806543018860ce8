// estimator.hpp: Welford's mean and variance on ill-conditioned data, merging for parallel
// sums, the standard error and the coverage of the confidence interval.
#include <zraka/core/rng.hpp>
#include <zraka/sampling/estimator.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <vector>

using zraka::estimator_t;

namespace {

// The reference: two-pass mean and variance in long double of the data as stored in T.
template <class T> void two_pass(const std::vector<T>& x, long double& mean, long double& var) {
  mean = 0;
  for (T v : x) mean += v;
  mean /= (long double)x.size();
  var = 0;
  for (T v : x) var += ((long double)v - mean) * ((long double)v - mean);
  var /= (long double)(x.size() - 1);
}

// Mean M, spread about 1: uniform in [M - 1.7, M + 1.7] has variance ~1.
template <class T> std::vector<T> ill_conditioned(T M, int n, std::uint64_t seed) {
  zraka::rng g(seed);
  std::vector<T> x;
  for (int i = 0; i < n; ++i) x.push_back(M + T(3.4 * (g.uniform() - 0.5)));
  return x;
}

// Mean 1e9 in double. Float cannot hold 1e9 +- 1 (its spacing there is 64), so float gets the
// same difficulty at its own scale: mean^2 / variance ~ 1 / eps^(1.x), i.e. mean 1e4.
template <class T> T big_mean() { return sizeof(T) == 4 ? T(1e4) : T(1e9); }

}  // namespace

TEST_CASE_TEMPLATE("Welford matches two-pass on mean 1e9 (1e4 in float), spread 1", T, float,
                   double) {
  const T M = big_mean<T>();
  const auto x = ill_conditioned<T>(M, 100'000, 17);
  long double ref_mean, ref_var;
  two_pass(x, ref_mean, ref_var);
  REQUIRE(ref_var > 0.5L);  // the data really has spread ~1 (float rounds it to 2^-10 steps)

  estimator_t<T> e;
  for (T v : x) e.add(v);
  // Welford's error grows like n * eps * spread^2 at worst, not eps * mean^2: 1e-3 relative
  // (float) and 1e-6 (double) leave a wide margin over what is seen (3.5e-5 and 3.4e-8).
  const double tol = sizeof(T) == 4 ? 1e-3 : 1e-6;
  CHECK(std::abs(double(e.variance()) - double(ref_var)) < tol * double(ref_var));
  // The mean to a few ulps of M (a relative 1e-6 float, 1e-14 double)
  CHECK(std::abs(double(e.mean()) - double(ref_mean)) < (sizeof(T) == 4 ? 1e-6 : 1e-14) * double(M));

  T mean = 0, sum2 = 0, sum = 0;
  for (T v : x) sum += v, sum2 += v * v;
  const T n = T(x.size());
  const T naive = (sum2 - sum * sum / n) / (n - 1);
  for (T v : x) mean += v;
  mean /= n;
  T var2 = 0;
  for (T v : x) var2 += (v - mean) * (v - mean);
  var2 /= (n - 1);
  // Two-pass in T is fine in double. In float it is not: the plain sum of 1e5 values of 1e4
  // reaches 1e9, where float's spacing is 64, so its mean is off by ~0.1-1 and every
  // deviation with it. Welford's running mean never forms that big sum.
  if (sizeof(T) == 8) CHECK(std::abs(double(var2) - double(ref_var)) < 0.01 * double(ref_var));
  else CHECK(!(std::abs(double(var2) - double(ref_var)) < 0.01 * double(ref_var)));
  // The naive E[x^2] - E[x]^2 is off by far more than the variance itself (or negative).
  CHECK(!(std::abs(double(naive) - double(ref_var)) < 1.0 * double(ref_var)));
}

TEST_CASE_TEMPLATE("merging estimators equals adding the samples one by one", T, float, double) {
  const auto x = ill_conditioned<T>(big_mean<T>(), 10'000, 5);
  estimator_t<T> all;
  for (T v : x) all.add(v);
  // Uneven chunks, including an empty one and a single sample.
  const std::vector<std::size_t> cuts = {0, 0, 1, 37, 1000, 1001, 6000, x.size()};
  std::vector<estimator_t<T>> parts(cuts.size() - 1);
  for (std::size_t c = 0; c + 1 < cuts.size(); ++c)
    for (std::size_t i = cuts[c]; i < cuts[c + 1]; ++i) parts[c].add(x[i]);
  estimator_t<T> merged;
  for (const auto& p : parts) merged.merge(p);
  // As a tree, (p0+p1)+(p2+p3)+..., the way a parallel reduction does it.
  estimator_t<T> left, right;
  for (std::size_t c = 0; c < parts.size(); ++c) (c < parts.size() / 2 ? left : right).merge(parts[c]);
  left.merge(right);
  CHECK(merged.count() == all.count());
  CHECK(left.count() == all.count());
  // Both orders round differently. The variance: relative 1e-3 (float) and 1e-8 (double).
  // The mean: each running update rounds at the scale of the mean itself, so 100 ulps of it.
  const double tol = sizeof(T) == 4 ? 1e-3 : 1e-8;
  const double tol_mean = 100 * double(std::numeric_limits<T>::epsilon()) * double(big_mean<T>());
  for (const auto* e : {&merged, &left}) {
    CHECK(std::abs(double(e->variance() - all.variance())) < tol * double(all.variance()));
    CHECK(std::abs(double(e->mean() - all.mean())) < tol_mean);
  }
  // Merging with an empty estimator changes nothing, bit for bit.
  estimator_t<T> copy = all;
  copy.merge(estimator_t<T>{});
  CHECK(copy.mean() == all.mean());
  CHECK(copy.variance() == all.variance());
}

TEST_CASE("small cases: no samples, one sample, a known set") {
  zraka::estimator e;
  CHECK(e.count() == 0);
  CHECK(std::isnan(e.mean()));  // no estimate yet
  e.add(3.0);
  CHECK(e.mean() == 3.0);
  CHECK(std::isnan(e.variance()));  // one sample says nothing about the spread
  CHECK(std::isnan(e.standard_error()));
  for (double v : {1.0, 2.0, 4.0}) e.add(v);  // {3, 1, 2, 4}: mean 2.5, variance 5/3
  CHECK(e.mean() == doctest::Approx(2.5).epsilon(1e-15));
  CHECK(e.variance() == doctest::Approx(5.0 / 3.0).epsilon(1e-15));
  CHECK(e.standard_error() == doctest::Approx(std::sqrt(5.0 / 3.0 / 4.0)).epsilon(1e-15));
  const auto ci = e.confidence_interval(0.95);
  CHECK(ci.hi - ci.lo == doctest::Approx(2 * 1.959963984540054 * e.standard_error()));
}

TEST_CASE("normal quantiles") {
  // Reference values of the standard normal, to 1e-12 (bisection to double precision).
  CHECK(zraka::normal_two_sided_quantile(0.95) == doctest::Approx(1.959963984540054).epsilon(1e-12));
  CHECK(zraka::normal_two_sided_quantile(0.99) == doctest::Approx(2.575829303548901).epsilon(1e-12));
  CHECK(zraka::normal_two_sided_quantile(0.6826894921370859) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(std::isnan(zraka::normal_two_sided_quantile(1.0)));
  CHECK(std::isnan(zraka::normal_two_sided_quantile(0.0)));
}

TEST_CASE("the 95% interval covers the true mean in about 95% of 200 runs") {
  // Each run: 100 samples of an exponential variable (mean 1, skewed, so the normal
  // approximation is being tested, not assumed). Coverage count ~ Binomial(200, 0.95): mean 190,
  // sd 3.1. Accept 180..199: a correct interval lands outside with probability ~1e-3; an
  // interval with the wrong width (e.g. sigma instead of sigma/sqrt(n): 100%, or half-width:
  // ~68%) cannot.
  int covered = 0, covered_68 = 0;
  for (std::uint32_t run = 0; run < 200; ++run) {
    zraka::rng g(2, 0, run);
    zraka::estimator e;
    for (int i = 0; i < 100; ++i) e.add(-std::log(1.0 - g.uniform()));
    covered += e.confidence_interval(0.95).contains(1.0);
    covered_68 += e.confidence_interval(0.6826894921370859).contains(1.0);
  }
  CHECK(covered >= 180);
  CHECK(covered <= 199);
  // The 1-sigma interval: Binomial(200, 0.683), mean 137, sd 6.6; 4 sd each way.
  CHECK(covered_68 >= 110);
  CHECK(covered_68 <= 163);
}

TEST_CASE("the standard error falls as 1/sqrt(n)") {
  zraka::rng g(8);
  zraka::estimator small, large;
  for (int i = 0; i < 1000; ++i) small.add(g.uniform());
  for (int i = 0; i < 100'000; ++i) large.add(g.uniform());
  // sigma of U[0,1) is 1/sqrt(12); sample sigma from 1000 samples is within ~3% of it.
  CHECK(small.standard_deviation() == doctest::Approx(1 / std::sqrt(12.0)).epsilon(0.05));
  CHECK(small.standard_error() / large.standard_error() == doctest::Approx(10.0).epsilon(0.05));
}

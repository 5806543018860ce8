#pragma once
// A Monte Carlo estimate and how sure we are of it (book 1.6): the running mean of the samples,
// their variance by Welford's update, the standard error of the mean and a normal-approximation
// confidence interval. Two estimators merge exactly, so threads can each keep one and add them
// up at the end.
//
// Why Welford: the textbook formula var = E[x^2] - E[x]^2 subtracts two huge, nearly equal
// numbers when the mean is large against the spread (a pixel value of 1e9 +- 1 in double, or
// 1e4 +- 1 in float) and returns noise or a negative variance. Welford keeps the running mean
// and the sum of squared deviations from it, which never cancels that way.
#include <cmath>
#include <cstdint>
#include <limits>

namespace zraka {

// The z with P(|Z| <= z) = level for a standard normal Z (1.96 for 0.95), by bisection on erfc:
// slower than a rational approximation but exact to double precision and needs no table.
inline double normal_two_sided_quantile(double level) {
  if (!(level > 0.0 && level < 1.0)) return std::numeric_limits<double>::quiet_NaN();
  double lo = 0.0, hi = 40.0;  // erfc(40/sqrt 2) underflows to 0, below any 1 - level
  for (int i = 0; i < 200 && hi - lo > 0.0; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (mid == lo || mid == hi) break;
    (std::erfc(mid / std::sqrt(2.0)) > 1.0 - level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

template <class T> struct confidence_interval_t {
  T lo, hi;
  bool contains(T x) const { return lo <= x && x <= hi; }
};

template <class T> class estimator_t {
 public:
  // [listing welford]
  void add(T x) {
    ++n_;
    const T delta = x - mean_;         // deviation from the old mean
    mean_ += delta / T(n_);
    m2_ += delta * (x - mean_);        // old deviation times new deviation
  }
  // [end]

  // [listing merge]
  // Chan, Golub and LeVeque's pairwise update: the same result as adding b's samples one by one
  // (up to rounding), in O(1).
  void merge(const estimator_t& b) {
    if (b.n_ == 0) return;
    if (n_ == 0) {
      *this = b;
      return;
    }
    const T n = T(n_ + b.n_);
    const T delta = b.mean_ - mean_;
    mean_ += delta * (T(b.n_) / n);
    m2_ += b.m2_ + delta * delta * (T(n_) * (T(b.n_) / n));
    n_ += b.n_;
  }
  // [end]

  std::uint64_t count() const { return n_; }
  // The sample mean; NaN before the first sample (there is no estimate yet).
  T mean() const { return n_ ? mean_ : std::numeric_limits<T>::quiet_NaN(); }
  // The unbiased sample variance (divides by n - 1); NaN for fewer than two samples, since one
  // sample says nothing about the spread.
  T variance() const { return n_ > 1 ? m2_ / T(n_ - 1) : std::numeric_limits<T>::quiet_NaN(); }
  T standard_deviation() const { return std::sqrt(variance()); }
  // [listing standard-error]
  // How far the mean typically is from the true value: sigma / sqrt(n).
  T standard_error() const { return std::sqrt(variance() / T(n_)); }
  // The true value lies in mean +- z * standard error in about `level` of all runs, as long as
  // n is large enough for the mean to be nearly normal (the central limit theorem).
  confidence_interval_t<T> confidence_interval(double level = 0.95) const {
    const T half = T(normal_two_sided_quantile(level)) * standard_error();
    return {mean() - half, mean() + half};
  }
  // [end]

 private:
  std::uint64_t n_ = 0;
  T mean_ = 0;
  T m2_ = 0;  // sum of squared deviations from the current mean
};

using estimator = estimator_t<double>;

}  // namespace zraka

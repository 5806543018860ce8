#pragma once
// Piecewise-constant distributions (book 5.3): sample in proportion to a table of weights.
//
// 1D: n bins of equal width on [0,1), bin i with weight f_i >= 0. The density is
//     p(x) = f_i / (mean f)   for x in bin i,
// its CDF is piecewise linear through the summed weights, and inverting it is a binary search
// plus a linear step inside the bin.
// 2D (an image, rows v, columns u): p(u, v) = p(v) p(u | v), the marginal over the rows times
// the conditional of the row that v falls in, so a sample is two 1D inversions.
//
// Careful cases: bins of weight 0 are never sampled (the search skips them, also at the last
// bin where u * total can round up to the total); an all-zero table samples uniformly (so that
// a sampler always returns something, with a pdf that says what it did); the CDF is kept in
// double and the result clamped below 1, so a float caller never sees x = 1.
#include <zraka/core/error.hpp>
#include <zraka/sampling/sampling.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>
#include <vector>

namespace zraka {

// [listing distribution-1d]
class distribution_1d {
 public:
  distribution_1d() = default;
  explicit distribution_1d(std::vector<double> f) : f_(std::move(f)) {
    if (f_.empty()) throw error("distribution: no bins");
    cdf_.assign(f_.size() + 1, 0.0);
    for (std::size_t i = 0; i < f_.size(); ++i) {
      if (!(f_[i] >= 0) || !std::isfinite(f_[i]))
        throw error("distribution: weight " + std::to_string(i) + " is negative or not finite");
      cdf_[i + 1] = cdf_[i] + f_[i];
    }
    total_ = cdf_.back();
    if (!std::isfinite(total_)) throw error("distribution: the weights sum to infinity");
    if (!(total_ > 0)) {  // nothing to prefer: uniform
      for (std::size_t i = 0; i <= f_.size(); ++i) cdf_[i] = double(i);
      std::fill(f_.begin(), f_.end(), 1.0);
      total_ = double(f_.size());
      uniform_ = true;
    }
  }

  std::size_t size() const { return f_.size(); }
  double integral() const { return uniform_ ? 0.0 : total_ / double(f_.size()); }  // mean weight
  double weight(std::size_t i) const { return uniform_ ? 0.0 : f_[i]; }

  // x in [0,1) with density pdf(x); bin is the bin it fell in.
  template <class T> T sample(T u, double& pdf, std::size_t& bin) const {
    const double target = double(clamp_unit(u)) * total_;
    // The last bin whose start is <= target; bins of zero width before it are skipped.
    std::size_t i = std::size_t(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin()) - 1;
    i = std::min(i, f_.size() - 1);
    while (f_[i] == 0 && i > 0) --i;  // target rounded to the total: back to the last weighted bin
    const double t = std::clamp((target - cdf_[i]) / f_[i], 0.0, 1.0);
    bin = i;
    pdf = f_[i] * double(f_.size()) / total_;
    const double x = (double(i) + t) / double(f_.size());
    return std::min(T(x), one_minus_epsilon<T>);
  }
  // The density at x in [0,1] (0 outside).
  double pdf(double x) const {
    if (!(x >= 0 && x <= 1)) return 0;
    const std::size_t i = std::min(std::size_t(x * double(f_.size())), f_.size() - 1);
    return f_[i] * double(f_.size()) / total_;
  }
  double bin_pdf(std::size_t i) const { return f_[i] * double(f_.size()) / total_; }
  // The tables sample() searches, as they are (an all-zero table reads as uniform here), for a
  // copy that must sample the same way (the OpenCL kernel: gpu_scene.hpp).
  const std::vector<double>& bins() const { return f_; }
  const std::vector<double>& cdf() const { return cdf_; }
  double total() const { return total_; }

 private:
  std::vector<double> f_, cdf_;
  double total_ = 0;
  bool uniform_ = false;
};
// [end]

// [listing distribution-2d]
// weights[v * nu + u]: nv rows of nu columns; (u, v) in [0,1)^2, row v = 0 first.
class distribution_2d {
 public:
  distribution_2d() = default;
  distribution_2d(const std::vector<double>& weights, std::size_t nu, std::size_t nv) : nu_(nu), nv_(nv) {
    if (nu == 0 || nv == 0 || weights.size() != nu * nv)
      throw error("distribution: " + std::to_string(weights.size()) + " weights for " + std::to_string(nu) +
                  " x " + std::to_string(nv) + " bins");
    std::vector<double> row_sums(nv);
    rows_.reserve(nv);
    for (std::size_t v = 0; v < nv; ++v) {
      rows_.emplace_back(std::vector<double>(weights.begin() + std::ptrdiff_t(v * nu),
                                             weights.begin() + std::ptrdiff_t((v + 1) * nu)));
      row_sums[v] = rows_.back().integral();
    }
    marginal_ = distribution_1d(std::move(row_sums));
  }

  // (u, v) with density pdf per unit area of [0,1)^2.
  template <class T> vec2_t<T> sample(const vec2_t<T>& u, double& pdf) const {
    double pv = 0, pu = 0;
    std::size_t row = 0, col = 0;
    const T v = marginal_.sample(u.y, pv, row);
    const T x = rows_[row].sample(u.x, pu, col);
    pdf = pv * pu;
    return {x, v};
  }
  double pdf(double u, double v) const {
    if (!(u >= 0 && u <= 1 && v >= 0 && v <= 1)) return 0;
    const std::size_t row = std::min(std::size_t(v * double(nv_)), nv_ - 1);
    return marginal_.bin_pdf(row) * rows_[row].pdf(u);
  }
  std::size_t width() const { return nu_; }
  std::size_t height() const { return nv_; }
  const distribution_1d& marginal() const { return marginal_; }
  const distribution_1d& row(std::size_t v) const { return rows_[v]; }

 private:
  std::size_t nu_ = 0, nv_ = 0;
  std::vector<distribution_1d> rows_;
  distribution_1d marginal_;
};
// [end]

}  // namespace zraka

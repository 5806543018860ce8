#pragma once
// Region means of images rendered with several seeds, for tests that compare two estimators
// (test_bdpt.cpp, test_metropolis.cpp): an image is cut into R x R regions, each batch (one
// seed) gives a mean per region and channel, and two estimators agree where their means differ
// by at most k combined standard errors.
#include <zraka/image/image.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/scene/scene.hpp>

#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace zraka_tests {

using namespace zraka;

constexpr int R = 4;  // R x R regions

// A scene at a test's small size, its acceleration built.
inline scene small(scene sc, int w, int h) {
  sc.settings.width = w;
  sc.settings.height = h;
  sc.build_acceleration();
  return sc;
}

// Per region and channel, the mean over the batches and its standard error.
struct region_stats {
  std::vector<estimator_t<double>> v;
};
inline std::vector<double> region_means(const image& img) {
  std::vector<double> m(R * R * 3, 0.0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const int r = (y * R / img.height) * R + x * R / img.width;
      for (int c = 0; c < 3; ++c) m[std::size_t(r * 3 + c)] += img.at(x, y)[c];
    }
  for (double& v : m) v /= double(img.width * img.height) / (R * R);
  return m;
}
inline region_stats batches(int n, const std::function<image(std::uint64_t)>& render_one) {
  region_stats s;
  s.v.resize(R * R * 3);
  for (int b = 0; b < n; ++b) {
    const auto m = region_means(render_one(std::uint64_t(100 + 7 * b)));
    for (std::size_t i = 0; i < m.size(); ++i) s.v[i].add(m[i]);
  }
  return s;
}
// How many region channels differ by more than k combined standard errors.
inline int disagreements(const region_stats& a, const region_stats& b, double k, std::string& report) {
  int bad = 0;
  for (std::size_t i = 0; i < a.v.size(); ++i) {
    const double d = a.v[i].mean() - b.v[i].mean();
    const double se = std::hypot(a.v[i].standard_error(), b.v[i].standard_error());
    if (std::abs(d) > k * se + 1e-6) {
      ++bad;
      report += " region " + std::to_string(i / 3) + " channel " + std::to_string(i % 3) + ": " +
                std::to_string(a.v[i].mean()) + " vs " + std::to_string(b.v[i].mean()) + " (se " + std::to_string(se) + ");";
    }
  }
  return bad;
}

}  // namespace zraka_tests

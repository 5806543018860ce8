#pragma once
// The picture for assignment 02: the GGX lobe seen from above, twice. Left: D(h) at each pixel
// of the projected hemisphere (x, y) of h. Right: a histogram of sample() in the same pixels,
// divided by the number of samples and the pixel's area. Since d(omega) = dA / cos(theta),
// pdf(h) / cos(theta) = D(h) is the density per unit area of (x, y): a correct sampler makes
// the two halves look alike, up to noise. Shared by render.cpp (target.png) and the test.
#include "ggx.hpp"

#include <zraka/core/rng.hpp>
#include <zraka/image/image.hpp>

#include <cmath>
#include <vector>

namespace course {

inline zraka::image render_lobe(const ggx& d, int size, long samples, std::uint64_t seed) {
  zraka::image img(2 * size, size, zraka::rgb(1.0f));
  const double pixel = 2.0 / size, area = pixel * pixel;
  const double scale = 1.0 / d.D({0.0, 0.0, 1.0});  // the peak maps to 1
  auto shade = [&](double v) {
    const float s = float(std::sqrt(std::clamp(v * scale, 0.0, 1.0)));  // sqrt: shows the tail
    return zraka::rgb(s, 0.6f * s, 0.15f + 0.85f * (1 - s) * 0.3f);
  };
  std::vector<double> counts(std::size_t(size) * std::size_t(size), 0.0);
  zraka::rng g(seed);
  for (long k = 0; k < samples; ++k) {
    const zraka::vec3 h = d.sample(g.uniform2());
    const int i = int((h.x + 1) / pixel), j = int((1 - h.y) / pixel);
    if (i >= 0 && i < size && j >= 0 && j < size) counts[std::size_t(j) * size + i] += 1;
  }
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      const double x = -1 + (i + 0.5) * pixel, y = 1 - (j + 0.5) * pixel;
      if (x * x + y * y >= 1) continue;  // outside the hemisphere: white
      const zraka::vec3 h(x, y, std::sqrt(1 - x * x - y * y));
      img.at(i, j) = shade(d.D(h));
      img.at(size + i, j) = shade(counts[std::size_t(j) * size + i] / (double(samples) * area));
    }
  return img;
}

}  // namespace course

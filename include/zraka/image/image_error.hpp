#pragma once
// How far a rendered image is from a reference image (book 4.2): the numbers an "error against
// run time" plot is made of.
//   rmse    sqrt(mean over pixels and channels of (x - ref)^2): in radiance units;
//   relmse  mean of (x - ref)^2 / (ref^2 + 0.01): relative, so dark and bright regions weigh
//           alike; the 0.01 keeps black reference pixels from dividing by zero (a common choice,
//           e.g. in Rousselle et al. 2011); it falls as 1/spp for an unbiased renderer;
//   channel_mean  the mean of each channel, to tell a bias (means differ) from noise.
// Sums are in double: a million squared float differences lose digits in float.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image.hpp>

#include <cmath>
#include <string>

namespace zraka {

ZRAKA_COMPILED_FN void check_same_size(const image& a, const image& ref)
#if ZRAKA_COMPILED_DEFINITIONS
{
  if (a.width != ref.width || a.height != ref.height)
    throw error("the reference is " + std::to_string(ref.width) + "x" + std::to_string(ref.height) +
                ", the image " + std::to_string(a.width) + "x" + std::to_string(a.height));
}
#else
    ;
#endif

// [listing rmse]
inline double rmse(const image& a, const image& ref) {
  check_same_size(a, ref);
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const vec3 d = vec3(a.pixels[i]) - vec3(ref.pixels[i]);
    sum += glm::dot(d, d);
  }
  return std::sqrt(sum / (3.0 * double(a.pixels.size())));
}

inline double relmse(const image& a, const image& ref) {
  check_same_size(a, ref);
  double sum = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double r = ref.pixels[i][c], d = double(a.pixels[i][c]) - r;
      sum += d * d / (r * r + 0.01);
    }
  return sum / (3.0 * double(a.pixels.size()));
}
// [end]

inline vec3 channel_mean(const image& a) {
  vec3 sum(0);
  for (const rgb& p : a.pixels) sum += vec3(p);
  return a.pixels.empty() ? vec3(0) : sum / double(a.pixels.size());
}

}  // namespace zraka

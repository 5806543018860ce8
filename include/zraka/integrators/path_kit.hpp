#pragma once
// The path kit (book 2.3, 5.1): the pieces every path-building renderer shares, so that the path
// tracer (path.hpp), BDPT (bdpt.hpp), the photons (photons.hpp) and the GPU packing
// (gpu_scene.hpp) reach them without the whole path loop: the power heuristic of multiple
// importance sampling, Russian roulette, and where a path's random numbers live in its stream.
// The OpenCL kernel (kernels/pathtrace.cl) mirrors the three.
#include <zraka/core/rng.hpp>
#include <zraka/image/image.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace zraka {

// The power heuristic (exponent 2) for a sample of density a, the other technique's being b.
template <class T> T power_heuristic(T a, T b) {
  if (!(a > T(0))) return T(0);
  if (std::isinf(a)) return T(1);
  const T r = b / a;  // a^2 / (a^2 + b^2) without overflowing a^2
  return T(1) / (T(1) + r * r);
}

// [listing path-dimensions]
// Where a path's numbers live in its stream when a sampler backs it (samplers.hpp, book 5.1):
// the camera's coordinates first, then a block per bounce, so coordinate k means the same draw
// in every sample and the sampler's 2-D pairs (coordinates 2i, 2i + 1) fall on the 2-D draws.
// A bounce that draws less leaves the rest of its block unused; one that draws more (a
// medium's free flights) pushes its later draws on, as rng::seek only jumps forward. Two stream
// numbers make one coordinate (a double). Plain streams ignore all this: their numbers are
// independent wherever they are.
enum class path_slot : std::uint32_t {
  light_choice = 0,  // 1 (coordinate 1 of the block unused)
  light_point = 2,   // 2
  bsdf = 4,          // 2 for the direction (or 1 for glass, 3 for fuzzy metal), 1 for the lobe
  roulette = 7,      // 1
};
inline constexpr std::uint32_t camera_coordinates = 4;  // the pixel position (0, 1), the lens (2, 3)
inline constexpr std::uint32_t bounce_coordinates = 8;
constexpr std::uint32_t path_number(int bounce, path_slot s) {
  return 2 * (camera_coordinates + bounce_coordinates * std::uint32_t(bounce) + std::uint32_t(s));
}
// [end]

// [listing roulette]
// Russian roulette: true if the path goes on (then beta has been divided by q).
inline bool survives_roulette(rgb& beta, int bounce, int rr_depth, rng& g) {
  if (bounce < rr_depth) return true;
  g.seek(path_number(bounce, path_slot::roulette));
  const float q = std::min(1.0f, max_component(beta));
  if (!(g.uniform() < q)) return false;
  beta /= q;
  return true;
}
// [end]

}  // namespace zraka

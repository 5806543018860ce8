#pragma once
// A linear-light RGB image of floats. Conventions: pixel (0,0) is the top-left corner, x runs
// right, y runs down; values are linear radiance (no gamma) until a writer encodes them.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/core/vec.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace zraka {

using rgb = vec3_t<float>;

struct image {
  static constexpr int max_side = 16384;                   // larger is almost surely a typo
  static constexpr std::size_t max_pixels = 1u << 27;      // 134 M pixels, 1.6 GB of floats

  int width = 0, height = 0;
  std::vector<rgb> pixels;

  image() = default;
  image(int w, int h, rgb fill = rgb(0)) : width(w), height(h) {
    check_size(w, h);
    pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), fill);
  }

  rgb& at(int x, int y) { return pixels[static_cast<std::size_t>(y) * width + x]; }
  const rgb& at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * width + x]; }

  // Pixels with a NaN or infinite channel.
  std::size_t count_nonfinite() const {
    std::size_t n = 0;
    for (const rgb& p : pixels) n += is_finite(p) ? 0 : 1;
    return n;
  }

  // Throws zraka::error unless w x h is a legal image size (each side 1..max_side, the limits).
  ZRAKA_COMPILED_FN static void check_size(long long w, long long h);
};

// Rec. 709 luminance of a linear RGB colour: one brightness number for a colour.
inline double luminance(const rgb& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// Images of one size in a row, `gap` white pixels apart (the figures of part 6).
ZRAKA_COMPILED_FN image side_by_side(const std::vector<image>& tiles, int gap = 2);

// Compiled into zraka::compiled (compiled.hpp) unless header-only.
#if ZRAKA_COMPILED_DEFINITIONS
ZRAKA_COMPILED_FN image side_by_side(const std::vector<image>& tiles, int gap) {
  const int w = tiles.at(0).width, h = tiles[0].height;
  image out(int(tiles.size()) * w + (int(tiles.size()) - 1) * gap, h, rgb(1));
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    if (tiles[i].width != w || tiles[i].height != h) throw error("side_by_side: the images differ in size");
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) out.at(int(i) * (w + gap) + x, y) = tiles[i].at(x, y);
  }
  return out;
}

ZRAKA_COMPILED_FN void image::check_size(long long w, long long h) {
  if (w < 1 || h < 1 || w > max_side || h > max_side ||
      static_cast<std::size_t>(w) * static_cast<std::size_t>(h) > max_pixels)
    throw error("image size " + std::to_string(w) + "x" + std::to_string(h) +
                " is out of range (each side 1.." + std::to_string(max_side) + ")");
  // Below the hard maximum, the raisable one (limits.hpp) keeps a run within the memory.
  check_limit(std::uint64_t(w) * std::uint64_t(h), limits().pixels, "pixels",
              "the image size " + std::to_string(w) + "x" + std::to_string(h) + " in pixels");
}
#endif

}  // namespace zraka

#pragma once
// Writing and reading images: PNG (8-bit sRGB, via stb_image_write), PPM P3 (the thesis's
// "text file with the pixel matrix", also sRGB) and PFM (32-bit float, linear: for reference
// images). Every write is atomic (see atomic_file.hpp). NaN and infinite pixels are never
// written silently: they are counted, written as magenta in PNG/PPM, reported on stderr and
// returned; PFM refuses them, since a reference image with NaN would poison every comparison.
#include <zraka/atomic_file.hpp>
#include <zraka/image.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

namespace zraka {

// The sRGB transfer function (IEC 61966-2-1), clamped to [0,1]; NaN gives 0 (std::clamp
// would pass NaN through, and lround(NaN) is undefined).
inline float linear_to_srgb(float v) {
  if (!(v > 0.0f)) return 0.0f;
  v = std::min(v, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}
inline float srgb_to_linear(float s) {
  s = std::clamp(s, 0.0f, 1.0f);
  return s <= 0.04045f ? s / 12.92f : std::pow((s + 0.055f) / 1.055f, 2.4f);
}
inline std::uint8_t to_byte(float linear) {
  return static_cast<std::uint8_t>(std::lround(linear_to_srgb(linear) * 255.0f));
}

namespace detail {
inline std::size_t encode_8bit(const image& img, std::string& rgb8) {
  rgb8.resize(img.pixels.size() * 3);
  std::size_t bad = 0;
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    rgb p = img.pixels[i];
    if (!is_finite(p)) { ++bad; p = rgb(1, 0, 1); }
    for (int c = 0; c < 3; ++c) rgb8[3 * i + c] = static_cast<char>(to_byte(p[c]));
  }
  return bad;
}
inline void report_nonfinite(std::size_t bad, const std::filesystem::path& path) {
  if (bad)
    std::cerr << "warning: " << bad << " NaN/inf pixel(s) written as magenta to " << path.string()
              << '\n';
}
}  // namespace detail

// Returns the number of NaN/inf pixels (written as magenta).
inline std::size_t write_png(const image& img, const std::filesystem::path& path) {
  std::string rgb8;
  const std::size_t bad = detail::encode_8bit(img, rgb8);
  std::string png;
  auto sink = [](void* ctx, void* data, int size) {
    static_cast<std::string*>(ctx)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_png_to_func(sink, &png, img.width, img.height, 3, rgb8.data(), img.width * 3))
    throw error("cannot encode PNG " + path.string());
  write_file_atomically(path, png);
  detail::report_nonfinite(bad, path);
  return bad;
}

// PPM P3: plain text, one pixel per line, as the thesis's CPU programs wrote.
inline std::size_t write_ppm(const image& img, const std::filesystem::path& path) {
  std::string rgb8;
  const std::size_t bad = detail::encode_8bit(img, rgb8);
  std::ostringstream out;
  out << "P3\n" << img.width << ' ' << img.height << "\n255\n";
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    out << int(std::uint8_t(rgb8[3 * i])) << ' ' << int(std::uint8_t(rgb8[3 * i + 1])) << ' '
        << int(std::uint8_t(rgb8[3 * i + 2])) << '\n';
  write_file_atomically(path, out.str());
  detail::report_nonfinite(bad, path);
  return bad;
}

// PFM: little-endian floats, rows stored bottom to top (the format's rule).
static_assert(std::endian::native == std::endian::little, "PFM I/O assumes a little-endian host");
inline void write_pfm(const image& img, const std::filesystem::path& path) {
  if (const std::size_t bad = img.count_nonfinite())
    throw error("refusing to write " + path.string() + ": " + std::to_string(bad) +
                " NaN/inf pixel(s)");
  std::string out = "PF\n" + std::to_string(img.width) + ' ' + std::to_string(img.height) +
                    "\n-1.0\n";
  const std::size_t header = out.size();
  const std::size_t row = std::size_t(img.width) * 3 * sizeof(float);
  out.resize(header + row * std::size_t(img.height));
  for (int y = 0; y < img.height; ++y)
    std::memcpy(out.data() + header + row * std::size_t(img.height - 1 - y), &img.at(0, y), row);
  write_file_atomically(path, out);
}

inline image read_pfm(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw error("cannot open " + path.string());
  std::string magic;
  long long w = 0, h = 0;
  double scale = 0;
  in >> magic >> w >> h >> scale;
  if (magic != "PF" || !in || scale >= 0)
    throw error(path.string() + ": not a little-endian colour PFM file");
  image::check_size(w, h);
  in.get();  // the single whitespace after the scale
  image img(static_cast<int>(w), static_cast<int>(h));
  const std::size_t row = std::size_t(w) * 3 * sizeof(float);
  for (long long y = h - 1; y >= 0; --y)
    if (!in.read(reinterpret_cast<char*>(&img.at(0, int(y))), std::streamsize(row)))
      throw error(path.string() + ": file ends early (truncated PFM)");
  return img;
}

// Writes by extension: .png, .ppm or .pfm.
inline void write_image(const image& img, const std::filesystem::path& path) {
  const auto ext = path.extension().string();
  if (ext == ".png") write_png(img, path);
  else if (ext == ".ppm") write_ppm(img, path);
  else if (ext == ".pfm") write_pfm(img, path);
  else throw error("unknown image type '" + ext + "' for " + path.string() + " (use .png, .ppm or .pfm)");
}

}  // namespace zraka

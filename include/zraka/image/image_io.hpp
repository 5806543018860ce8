#pragma once
// Writing and reading images: PNG (8-bit sRGB, via stb_image_write), PPM P3 (the thesis's
// "text file with the pixel matrix", also sRGB), PFM and OpenEXR (32-bit float, linear: for
// reference images; EXR through tinyexr, which image viewers and Mitsuba read). Every write is
// atomic (see atomic_file.hpp). NaN and infinite pixels are never written silently: they are
// counted, written as magenta in PNG/PPM, reported on stderr and returned; PFM and EXR refuse
// them, since a reference image with NaN would poison every comparison.
#include <zraka/core/atomic_file.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/image/image.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

// The writers and the PFM reader are compiled into zraka::compiled (compiled.hpp): with
// stb_image_write's implementation they cost every unit that writes an image ~1.5 CPU-s at -O3.
// stb is static, in the library's unit or (header-only) in the program's: it never clashes with
// an stb of the program's own.
#if ZRAKA_COMPILED_DEFINITIONS
#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#include <tinyexr.h>  // declarations; the library is libtinyexr
#endif

static_assert(std::endian::native == std::endian::little, "PFM I/O assumes a little-endian host");

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

// [listing srgb-steps]
// to_byte's 255 steps: steps[b] (b = 1..255) is the smallest float that to_byte makes b or
// more; steps[0] is 0 and never read. to_byte(x) is then the number of steps at or below x, found
// with eight comparisons: how the real-time kernel encodes its display, giving to_byte's bytes
// without a pow per channel (PoCL's pow was two fifths of a one-sample frame). Each step is found
// by bisecting the bit patterns of the floats in [0, 1], which are in the order of their values,
// with to_byte itself as the judge, so it holds wherever to_byte is monotone.
inline std::array<float, 256> srgb_byte_steps() {
  std::array<float, 256> steps{};
  for (int b = 1; b < 256; ++b) {
    std::uint32_t lo = 0, hi = std::bit_cast<std::uint32_t>(1.0f);  // to_byte(lo) < b <= to_byte(hi)
    while (hi - lo > 1) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      (to_byte(std::bit_cast<float>(mid)) >= b ? hi : lo) = mid;
    }
    steps[std::size_t(b)] = std::bit_cast<float>(hi);
  }
  return steps;
}
// [end]

namespace detail {
// What every image reader checks, with the file's name in front of the message: the size the
// header states, before any pixel is decoded, and the pixels after (the first NaN/inf is named).
inline void check_size_of(const std::string& name, long long w, long long h) {
  try {
    image::check_size(w, h);
  } catch (const error& e) {
    throw error(name + ": " + e.what());
  }
}
inline void refuse_nonfinite(const image& img, const std::string& name) {
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      if (!is_finite(img.at(x, y)))
        throw error(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) + ") is NaN or infinite");
}

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

// Each returns the number of NaN/inf pixels (written as magenta).
ZRAKA_COMPILED_FN std::size_t write_png(const image& img, const std::filesystem::path& path);
// PPM P3: plain text, one pixel per line, as the thesis's CPU programs wrote.
ZRAKA_COMPILED_FN std::size_t write_ppm(const image& img, const std::filesystem::path& path);
// PFM: little-endian floats, rows stored bottom to top (the format's rule); refuses NaN/inf.
ZRAKA_COMPILED_FN void write_pfm(const image& img, const std::filesystem::path& path);
// Writes by extension: .png, .ppm or .pfm.
ZRAKA_COMPILED_FN void write_image(const image& img, const std::filesystem::path& path);

// Strict: the header "PF W H SCALE" with a negative (little-endian) finite scale, exactly W*H
// pixels after it, every one finite (a reference with NaN would poison every comparison).
// parse_pfm reads the bytes of a PFM file (`name` for messages); read_pfm a file.
ZRAKA_COMPILED_FN image parse_pfm(std::string_view bytes, const std::string& name);
ZRAKA_COMPILED_FN image read_pfm(const std::filesystem::path& path);

// OpenEXR through tinyexr, compiled once like the writers above: write_exr writes three float
// channels, ZIP compressed; parse_exr/read_exr read a single-part image, its size checked before
// any pixel is decoded, every pixel finite; read_float_image reads a reference, .exr as OpenEXR,
// any other name as PFM.
ZRAKA_COMPILED_FN void write_exr(const image& img, const std::filesystem::path& path);
ZRAKA_COMPILED_FN image parse_exr(std::string_view bytes, const std::string& name);
ZRAKA_COMPILED_FN image read_exr(const std::filesystem::path& path);
ZRAKA_COMPILED_FN image read_float_image(const std::filesystem::path& path);

#if ZRAKA_COMPILED_DEFINITIONS
// [listing exr]
// OpenEXR: three channels of 32-bit float (B, G, R: the order EXR files list them in), ZIP
// compressed (lossless), scanlines top to bottom. Encoded in memory, then written atomically.
ZRAKA_COMPILED_FN void write_exr(const image& img, const std::filesystem::path& path) {
  if (const std::size_t bad = img.count_nonfinite())
    throw error("refusing to write " + path.string() + ": " + std::to_string(bad) + " NaN/inf pixel(s)");
  const std::size_t n = img.pixels.size();
  std::vector<float> planes(3 * n);  // B, G, R planes
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) planes[std::size_t(2 - c) * n + i] = img.pixels[i][c];
  unsigned char* channels[3] = {reinterpret_cast<unsigned char*>(planes.data()),
                                reinterpret_cast<unsigned char*>(planes.data() + n),
                                reinterpret_cast<unsigned char*>(planes.data() + 2 * n)};
  EXRHeader header;
  InitEXRHeader(&header);
  EXRImage exr;
  InitEXRImage(&exr);
  exr.images = channels;
  exr.width = img.width;
  exr.height = img.height;
  exr.num_channels = 3;
  EXRChannelInfo info[3] = {};
  int types[3] = {TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT, TINYEXR_PIXELTYPE_FLOAT};
  for (int c = 0; c < 3; ++c) info[c].name[0] = "BGR"[c];
  header.num_channels = 3;
  header.channels = info;
  header.pixel_types = types;            // as stored in `channels`
  header.requested_pixel_types = types;  // as written: float, so that a reference round-trips exactly
  header.compression_type = TINYEXR_COMPRESSIONTYPE_ZIP;
  unsigned char* memory = nullptr;
  const char* err = nullptr;
  const std::size_t size = SaveEXRImageToMemory(&exr, &header, &memory, &err);
  if (size == 0 || !memory) {
    const std::string why = err ? err : "unknown error";
    if (err) FreeEXRErrorMessage(err);
    std::free(memory);
    throw error("cannot encode EXR " + path.string() + ": " + why);
  }
  std::string bytes(reinterpret_cast<const char*>(memory), size);
  std::free(memory);
  write_file_atomically(path, bytes);
}

// The RGB of an EXR file's bytes (a single-part scanline or tiled image; a one-channel image is
// grey). Its size is checked before any pixel is decoded, and every pixel must be finite.
ZRAKA_COMPILED_FN image parse_exr(std::string_view bytes, const std::string& name) {
  const auto* mem = reinterpret_cast<const unsigned char*>(bytes.data());
  EXRVersion version;
  if (ParseEXRVersionFromMemory(&version, mem, bytes.size()) != TINYEXR_SUCCESS)
    throw error(name + ": not an OpenEXR file (no EXR version header)");
  if (version.multipart || version.non_image)
    throw error(name + ": a multi-part or deep EXR file; only single-part images are read");
  auto fail = [&](const char* what, int code, const char* err) {
    const std::string why = err ? err : ("tinyexr error " + std::to_string(code));
    if (err) FreeEXRErrorMessage(err);
    throw error(name + ": " + what + ": " + why);
  };
  EXRHeader header;
  InitEXRHeader(&header);
  const char* err = nullptr;
  if (const int rc = ParseEXRHeaderFromMemory(&header, &version, mem, bytes.size(), &err); rc != TINYEXR_SUCCESS) {
    FreeEXRHeader(&header);  // what it parsed before the fault
    fail("malformed EXR header", rc, err);
  }
  const long long w = 1LL + header.data_window.max_x - header.data_window.min_x;
  const long long h = 1LL + header.data_window.max_y - header.data_window.min_y;
  FreeEXRHeader(&header);
  detail::check_size_of(name, w, h);
  float* rgba = nullptr;
  int width = 0, height = 0;
  if (const int rc = LoadEXRFromMemory(&rgba, &width, &height, mem, bytes.size(), &err); rc != TINYEXR_SUCCESS) {
    std::free(rgba);
    fail("cannot decode EXR", rc, err);
  }
  if (width != w || height != h) {
    std::free(rgba);
    throw error(name + ": the EXR pixels do not match its data window");
  }
  image img(width, height);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = rgb(rgba[4 * i], rgba[4 * i + 1], rgba[4 * i + 2]);
  std::free(rgba);
  detail::refuse_nonfinite(img, name);
  return img;
}
ZRAKA_COMPILED_FN image read_exr(const std::filesystem::path& path) {
  return parse_exr(read_input_file(path), path.string());
}
// [end]

// Reads a float image (a reference): .exr as OpenEXR, any other name as PFM (whose reader
// checks its header and says so when it is not one).
ZRAKA_COMPILED_FN image read_float_image(const std::filesystem::path& path) {
  return path.extension() == ".exr" ? read_exr(path) : read_pfm(path);
}

ZRAKA_COMPILED_FN std::size_t write_png(const image& img, const std::filesystem::path& path) {
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

ZRAKA_COMPILED_FN std::size_t write_ppm(const image& img, const std::filesystem::path& path) {
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

ZRAKA_COMPILED_FN void write_pfm(const image& img, const std::filesystem::path& path) {
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

ZRAKA_COMPILED_FN image parse_pfm(std::string_view bytes, const std::string& name) {
  std::size_t pos = 0;
  auto field = [&](const char* what) {
    while (pos < bytes.size() && std::isspace(static_cast<unsigned char>(bytes[pos]))) ++pos;
    const std::size_t start = pos;
    while (pos < bytes.size() && !std::isspace(static_cast<unsigned char>(bytes[pos])) && pos - start < 32) ++pos;
    if (start == pos) throw error(name + ": not a PFM file (the header ends before the " + what + ")");
    return bytes.substr(start, pos - start);
  };
  if (field("magic") != "PF") throw error(name + ": not a little-endian colour PFM file (it does not start with PF)");
  auto integer = [&](const char* what) {
    const std::string_view t = field(what);
    long long x = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    if (ec != std::errc() || end != t.data() + t.size())
      throw error(name + ": the " + what + " '" + std::string(t) + "' is not an integer");
    return x;
  };
  const long long w = integer("width"), h = integer("height");
  const std::string_view st = field("scale");
  double scale = 0;
  const auto [end, ec] = std::from_chars(st.data(), st.data() + st.size(), scale);
  if (ec != std::errc() || end != st.data() + st.size() || !std::isfinite(scale) || scale == 0)
    throw error(name + ": the scale '" + std::string(st) + "' is not a finite non-zero number");
  if (scale > 0) throw error(name + ": a big-endian PFM (positive scale); only little-endian is read");
  detail::check_size_of(name, w, h);
  if (pos >= bytes.size() || !std::isspace(static_cast<unsigned char>(bytes[pos])))
    throw error(name + ": file ends early (truncated PFM)");
  ++pos;  // the single whitespace after the scale
  const std::size_t row = std::size_t(w) * 3 * sizeof(float), need = row * std::size_t(h);
  if (bytes.size() - pos < need) throw error(name + ": file ends early (truncated PFM)");
  if (bytes.size() - pos > need)
    throw error(name + ": " + std::to_string(bytes.size() - pos - need) + " bytes after the last pixel");
  image img(static_cast<int>(w), static_cast<int>(h));
  for (long long y = h - 1; y >= 0; --y, pos += row)
    std::memcpy(&img.at(0, int(y)), bytes.data() + pos, row);
  detail::refuse_nonfinite(img, name);
  return img;
}
ZRAKA_COMPILED_FN image read_pfm(const std::filesystem::path& path) {
  return parse_pfm(read_input_file(path), path.string());  // a regular file within limits().file_bytes
}

// Writes by extension: .png, .ppm, .pfm or .exr.
ZRAKA_COMPILED_FN void write_image(const image& img, const std::filesystem::path& path) {
  check_output_name(path);  // "" or "folder/" say so, rather than "unknown image type ''"
  const auto ext = path.extension().string();
  if (ext == ".png") write_png(img, path);
  else if (ext == ".ppm") write_ppm(img, path);
  else if (ext == ".pfm") write_pfm(img, path);
  else if (ext == ".exr") write_exr(img, path);
  else throw error("unknown image type '" + ext + "' for " + path.string() + " (use .png, .ppm, .pfm or .exr)");
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

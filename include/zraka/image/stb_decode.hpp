#pragma once
// Decoding a PNG or a Radiance HDR file's bytes with stb_image, the same way for textures
// (texture_file.hpp) and environment maps (environment_file.hpp): the header is read first and
// the size checked (image::check_size) before any pixel is decoded, and every error names the
// file. Alpha, if any, is dropped; row 0 is at the top.
#include <zraka/core/error.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/image/stb_image.hpp>

#include <cstddef>
#include <string>
#include <string_view>

namespace zraka::detail {

enum class stb_format { png, hdr };

// PNG: each channel's byte / 255, not yet linearised (the caller knows whether it is sRGB).
// HDR: the linear floats of the file.
inline image decode_with_stb(std::string_view bytes, const std::string& name, stb_format format) {
  const char* kind = format == stb_format::png ? "PNG" : "HDR";
  const auto* in = reinterpret_cast<const stbi_uc*>(bytes.data());
  if (bytes.size() > std::size_t(1) << 31) throw error(name + ": too large for the " + kind + " reader");
  const int len = int(bytes.size());
  auto why = [&] { const char* r = stbi_failure_reason(); return std::string(r ? r : "corrupt data"); };
  if (format == stb_format::hdr && !stbi_is_hdr_from_memory(in, len))
    throw error(name + ": not a Radiance HDR file (no #?RADIANCE or #?RGBE header)");
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(in, len, &w, &h, &channels))
    throw error(name + (format == stb_format::png ? ": not a PNG image: " : ": malformed HDR header: ") + why());
  check_size_of(name, w, h);
  image img;
  if (format == stb_format::png) {
    stbi_uc* data = stbi_load_from_memory(in, len, &w, &h, &channels, 3);
    if (!data) throw error(name + ": cannot decode PNG: " + why());
    img = image(w, h);
    for (std::size_t i = 0; i < img.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) img.pixels[i][c] = float(data[3 * i + std::size_t(c)]) / 255.0f;
    stbi_image_free(data);
  } else {
    float* data = stbi_loadf_from_memory(in, len, &w, &h, &channels, 3);
    if (!data) throw error(name + ": cannot decode HDR: " + why());
    img = image(w, h);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = rgb(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
    stbi_image_free(data);
  }
  return img;
}

}  // namespace zraka::detail

#pragma once
// Reading an image texture (texture.hpp) from a file, by extension:
//   .png            8-bit, decoded from sRGB to linear (srgb = true, the usual case for colour
//                   images) or read as linear values / 255 (srgb = false, e.g. data maps);
//   .hdr .exr .pfm  linear floats (environment_file.hpp, image_io.hpp).
// An albedo above 1 would create energy, so every texel must lie in [0, 1]; every error names
// the file (and the texel). The bytes come through read_input_file (a regular file within the
// size limit), and the image size is checked before decoding.
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/image/stb_decode.hpp>
#include <zraka/lights/environment_file.hpp>

#include <filesystem>
#include <string>
#include <string_view>

namespace zraka {

// A PNG's bytes as linear RGB (alpha, if any, is dropped), row 0 at the top.
inline image parse_png_texture(std::string_view bytes, const std::string& name, bool srgb) {
  image img = detail::decode_with_stb(bytes, name, detail::stb_format::png);
  if (srgb)
    for (rgb& p : img.pixels)
      for (int c = 0; c < 3; ++c) p[c] = srgb_to_linear(p[c]);
  return img;
}

// [listing load-texture]
inline image load_texture_image(const std::filesystem::path& path, bool srgb = true) {
  const std::string ext = path.extension().string();
  image img;
  if (ext == ".png") img = parse_png_texture(read_input_file(path), path.string(), srgb);
  else if (ext == ".hdr" || ext == ".exr" || ext == ".pfm") img = read_hdr_image(path);
  else throw error(path.string() + ": unknown texture image type '" + ext + "' (use .png, .hdr, .exr or .pfm)");
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c)
        if (const float v = img.at(x, y)[c]; !(v >= 0 && v <= 1))
          throw error(path.string() + ": texel (" + std::to_string(x) + ", " + std::to_string(y) +
                      ") has " + std::to_string(v) + ", but an albedo must be in [0, 1]");
  return img;
}
// [end]

}  // namespace zraka

#pragma once
// Reading an environment map (environment.hpp) from a file, by extension:
//   .hdr  Radiance RGBE (stb_image's stbi_loadf_from_memory), the usual format of sky maps;
//   .exr  OpenEXR (image_io.hpp, tinyexr);
//   .pfm  portable float map (image_io.hpp).
// The bytes come through read_input_file (input_file.hpp: a regular file within the size
// limit); the image size is checked before decoding; every error names the file.
#include <zraka/environment.hpp>
#include <zraka/image_io.hpp>
#include <zraka/input_file.hpp>
#include <zraka/stb_image.hpp>

#include <filesystem>
#include <string>

namespace zraka {

// A Radiance .hdr file as linear RGB, row 0 at the top.
inline image parse_radiance_hdr(std::string_view bytes, const std::string& name) {
  const auto* in = reinterpret_cast<const stbi_uc*>(bytes.data());
  if (bytes.size() > std::size_t(1) << 31) throw error(name + ": too large for the HDR reader");
  const int len = int(bytes.size());
  if (!stbi_is_hdr_from_memory(in, len)) throw error(name + ": not a Radiance HDR file (no #?RADIANCE or #?RGBE header)");
  int w = 0, h = 0, channels = 0;
  auto why = [] { const char* r = stbi_failure_reason(); return std::string(r ? r : "corrupt HDR"); };
  if (!stbi_info_from_memory(in, len, &w, &h, &channels)) throw error(name + ": malformed HDR header: " + why());
  try {
    image::check_size(w, h);
  } catch (const error& e) {
    throw error(name + ": " + e.what());
  }
  float* data = stbi_loadf_from_memory(in, len, &w, &h, &channels, 3);
  if (!data) throw error(name + ": cannot decode HDR: " + why());
  image img(w, h);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = rgb(data[3 * i], data[3 * i + 1], data[3 * i + 2]);
  stbi_image_free(data);
  return img;
}

inline image read_hdr_image(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".hdr") return parse_radiance_hdr(read_input_file(path), path.string());
  if (ext == ".exr" || ext == ".pfm") return read_float_image(path);
  throw error(path.string() + ": unknown environment map type '" + ext + "' (use .hdr, .exr or .pfm)");
}

// [listing load-environment]
inline environment_map load_environment(const std::filesystem::path& path, float scale = 1.0f,
                                        double rotate_degrees = 0.0) {
  return environment_map::from_image(read_hdr_image(path), path.string(), scale, rotate_degrees);
}
// [end]

}  // namespace zraka

#pragma once
// Reading an environment map (environment.hpp) from a file, by extension:
//   .hdr  Radiance RGBE (stb_image's stbi_loadf_from_memory), the usual format of sky maps;
//   .exr  OpenEXR (image_io.hpp, tinyexr);
//   .pfm  portable float map (image_io.hpp).
// The bytes come through read_input_file (input_file.hpp: a regular file within the size
// limit); the image size is checked before decoding; every error names the file.
#include <zraka/core/input_file.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/image/stb_decode.hpp>
#include <zraka/lights/environment.hpp>

#include <filesystem>
#include <string>

namespace zraka {

// A Radiance .hdr file as linear RGB, row 0 at the top.
inline image parse_radiance_hdr(std::string_view bytes, const std::string& name) {
  return detail::decode_with_stb(bytes, name, detail::stb_format::hdr);
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

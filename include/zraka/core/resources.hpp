#pragma once
// One resource root for scenes/ and kernels/, so every program works from any directory.
// The root is compiled in (ZRAKA_RESOURCE_DIR, set by CMake: the source tree when building,
// <prefix>/share/zraka when installed) and the environment variable ZRAKA_ROOT overrides it.
#include <zraka/core/error.hpp>

#include <cstdlib>
#include <filesystem>
#include <string_view>

#ifndef ZRAKA_RESOURCE_DIR
#define ZRAKA_RESOURCE_DIR "."
#endif

namespace zraka {

inline std::filesystem::path resource_root() {
  if (const char* env = std::getenv("ZRAKA_ROOT"); env && *env) return env;
  return ZRAKA_RESOURCE_DIR;
}

namespace detail {
// resource_path with the root given: for code compiled into zraka::compiled, which must not read
// ZRAKA_RESOURCE_DIR itself (compiled.hpp).
inline std::filesystem::path resource_path_in(std::string_view relative, const std::filesystem::path& root) {
  const std::filesystem::path p(relative);
  if (p.is_absolute() || std::filesystem::exists(p)) return p;
  const auto full = root / p;
  if (!std::filesystem::exists(full))
    throw error("resource not found: " + full.string() +
                " (set ZRAKA_ROOT to the folder that holds scenes/ and kernels/)");
  return full;
}
}  // namespace detail

// A path relative to the root, e.g. resource_path("scenes/teapot.bpt"). An absolute path or one
// that exists relative to the working directory is returned as it is.
inline std::filesystem::path resource_path(std::string_view relative) {
  return detail::resource_path_in(relative, resource_root());
}

}  // namespace zraka

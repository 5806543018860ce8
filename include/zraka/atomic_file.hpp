#pragma once
// Writing a file so that readers never see half of it: write a temporary file beside the
// target, then rename it over the target (rename is atomic within one file system).
#include <zraka/error.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <unistd.h>

namespace zraka {

inline void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  const auto dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir))
    throw error("cannot write " + path.string() + ": folder " + dir.string() + " does not exist");
  // Built piecewise: GCC 12 gives a false -Wrestrict on `"." + std::string` once inlined.
  std::string tmp_name = ".";
  tmp_name += path.filename().string();
  tmp_name += ".tmp";
  tmp_name += std::to_string(::getpid());
  const auto tmp = dir / tmp_name;
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) {
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw error("cannot write " + path.string() + " (disk full or no permission?)");
    }
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw error("cannot write " + path.string() + ": " + ec.message());
  }
}

}  // namespace zraka

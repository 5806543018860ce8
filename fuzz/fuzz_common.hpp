#pragma once
// Shared by the fuzz targets (fuzz/README.md). Each target defines LLVMFuzzerTestOneInput; with
// -fsanitize=fuzzer libFuzzer drives it, and in the normal build fuzz/replay.cpp feeds it the
// seed corpus and every kept crash (tests/fuzz-regressions/<target>/) as a regression test.
//
// A clean run is a success or a zraka::error; anything else that escapes (a YAML or filesystem
// exception, std::bad_alloc, ...) reaches std::terminate, which libFuzzer reports as a crash:
// the readers promise a located error for every bad input, nothing else.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace zraka_fuzz {

// A private folder for readers that take a path: under $TMPDIR (tools/fuzz.sh points it at a
// RAM disk) or /tmp; removed at a normal exit, and by tools/fuzz.sh after a crash.
inline const std::filesystem::path& scratch() {
  static const std::filesystem::path dir = [] {
    const char* t = std::getenv("TMPDIR");
    std::string tmpl = std::string(t && *t ? t : "/tmp") + "/zraka-fuzz-XXXXXX";
    if (!mkdtemp(tmpl.data())) {
      std::perror("zraka fuzz: mkdtemp");
      std::abort();
    }
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(scratch(), ec);
    });
    return std::filesystem::path(tmpl);
  }();
  return dir;
}

// Writes the input to scratch()/name and returns that path.
inline std::filesystem::path input_file(const std::uint8_t* data, std::size_t size, const char* name) {
  const std::filesystem::path p = scratch() / name;
  std::FILE* f = std::fopen(p.c_str(), "wb");
  if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror("zraka fuzz: writing the input file");
    std::abort();
  }
  return p;
}

}  // namespace zraka_fuzz

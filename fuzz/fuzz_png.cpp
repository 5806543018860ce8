// Fuzz target: the PNG reader of reference images, zraka::testing::read_png_display (stb_image,
// compiled into this program and so instrumented with it).
#include "fuzz_common.hpp"

#include <zraka/app/testing.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path p = zraka_fuzz::input_file(data, size, "input.png");
  try {
    (void)zraka::testing::read_png_display(p);
  } catch (const zraka::error&) {
  }
  return 0;
}

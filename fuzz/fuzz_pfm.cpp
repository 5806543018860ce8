// Fuzz target: the PFM reader (image_io.hpp), which reads reference images.
#include "fuzz_common.hpp"

#include <zraka/image/image_io.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path p = zraka_fuzz::input_file(data, size, "input.pfm");
  try {
    (void)zraka::read_pfm(p);
  } catch (const zraka::error&) {
  }
  return 0;
}

// Fuzz target: the .bpt (Bezier patch) reader, in double and float, and the tessellation of what
// it accepts (at a small, fixed level: the level is the scene file's business).
#include "fuzz_common.hpp"

#include <zraka/geometry/tessellate.hpp>
#include <zraka/io/bpt.hpp>

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    std::istringstream in(text);
    const auto set = zraka::parse_bpt<double>(in, "fuzz.bpt");
    (void)zraka::tessellate(set.all_patches(), 2);
  } catch (const zraka::error&) {
  }
  try {
    std::istringstream in(text);
    (void)zraka::parse_bpt<float>(in, "fuzz.bpt");
  } catch (const zraka::error&) {
  }
  return 0;
}

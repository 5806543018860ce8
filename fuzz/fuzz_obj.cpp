// Fuzz target: the OBJ reader (obj_file.hpp, zraka's own, so the whole parser is instrumented).
#include "fuzz_common.hpp"

// The reader under test (one place to change if it moves).
#include <zraka/io/obj_file.hpp>
#define ZRAKA_FUZZ_LOAD_OBJ zraka::load_obj

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // In a folder of its own: an 'mtllib' line finds nothing beside it.
  const std::filesystem::path p = zraka_fuzz::input_file(data, size, "input.obj");
  try {
    (void)ZRAKA_FUZZ_LOAD_OBJ(p);
  } catch (const zraka::error&) {
  }
  return 0;
}

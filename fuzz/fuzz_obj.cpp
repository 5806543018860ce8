// Fuzz target: the OBJ reader. The fuzz build compiles tinyobjloader's implementation into this
// program (fuzz/CMakeLists.txt), so its parser is instrumented too.
#include "fuzz_common.hpp"

// The reader under test (one place to change if it moves).
#include <zraka/scene_file.hpp>
#define ZRAKA_FUZZ_LOAD_OBJ zraka::detail::load_obj

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // In a folder of its own: an 'mtllib' line finds nothing beside it.
  const std::filesystem::path p = zraka_fuzz::input_file(data, size, "input.obj");
  try {
    (void)ZRAKA_FUZZ_LOAD_OBJ(p);
  } catch (const zraka::error&) {
  }
  return 0;
}

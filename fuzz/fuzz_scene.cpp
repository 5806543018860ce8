// Fuzz target: the YAML scene reader, zraka::parse_scene(text, name, dir). The scene's folder is
// scenes/ of the resource root, so seeds that name meshes/cube.obj or teapot.bpt load them.
// Debian's yaml-cpp is not instrumented: coverage guides the search through our reader only.
#include "fuzz_common.hpp"

#include <zraka/core/resources.hpp>
#include <zraka/io/scene_file.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    (void)zraka::parse_scene(text, "fuzz.yaml", zraka::resource_root() / "scenes");
  } catch (const zraka::error&) {
  }
  return 0;
}

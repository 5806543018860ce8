// Fuzz target: PLY and glTF meshes (mesh_file.hpp). assimp itself is not instrumented (Debian's
// library); what is fuzzed is zraka's side: the PLY header's count check before assimp reads,
// the checks of what assimp returns, and that every refusal is a zraka::error. The input's first
// bytes choose the reader: "glTF" a .glb, '{' a .gltf, anything else a .ply.
#include "fuzz_common.hpp"

#include <zraka/io/mesh_file.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view head(reinterpret_cast<const char*>(data), size < 4 ? size : 4);
  const char* name = head == "glTF" ? "input.glb" : (size > 0 && data[0] == '{') ? "input.gltf" : "input.ply";
  const std::filesystem::path p = zraka_fuzz::input_file(data, size, name);
  try {
    (void)zraka::load_mesh_file(p);
  } catch (const zraka::error&) {
  }
  return 0;
}

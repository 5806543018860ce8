// Fuzz target: the Mitsuba 3 XML reader, zraka::mitsuba_xml_to_yaml(text, name, dir), then the
// YAML it writes through parse_scene, as load_mitsuba_xml does. The scene's folder is
// scenes/mitsuba/ of the resource root, so seeds that name ../meshes/icosphere.obj or ../sky.hdr
// load them. Debian's pugixml is not instrumented: coverage guides the search through our reader.
#include "fuzz_common.hpp"

#include <zraka/core/resources.hpp>
#include <zraka/io/mitsuba_xml.hpp>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const std::filesystem::path dir = zraka::resource_root() / "scenes" / "mitsuba";
  try {
    (void)zraka::parse_scene(zraka::mitsuba_xml_to_yaml(text, "fuzz.xml", dir), "fuzz.xml (as zraka YAML)", dir);
  } catch (const zraka::error&) {
  }
  return 0;
}

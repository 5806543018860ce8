// A course's binary from an installed zraka: its own torus and matte material (the course's
// header, tests/course/torus.hpp) registered by name, and the whole `pathtrace` command line of
// chapter 2.3 around them (zraka::pathtrace_main, compiled into zraka::compiled).
//   course --scene torus.yaml --spp 16 --out torus.png
#include "torus.hpp"

#include <zraka/app/pathtrace_main.hpp>

// [listing course-main]
int main(int argc, char** argv) {
  zraka::scene_registry reg;
  course::register_types(reg);  // reg.add_shape("torus", ...), reg.add_material("matte", ...)
  return zraka::pathtrace_main(argc, argv, reg);
}
// [end]

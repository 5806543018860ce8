// Chapter 2.2 — the Whitted ray tracer. Takes a scene (--scene: a name such as `default` or
// `box`, or a scene file, book 4.1, scenes/README.md), builds what the scene needs (an object
// BVH only when it pays, a triangle BVH per mesh), renders it on all cores with whitted.hpp,
// and writes the image (and optionally a linear PFM).
//
//   whitted                                   renders the default scene to whitted.png
//   whitted --scene box --out box.png --spp 4
//
// The image is the same for the same seed on any number of threads.
//
// The program is one function of the library, zraka::whitted_main (app/whitted_main.hpp: read it
// there), so that a course's own program can offer it, with its own shapes and materials in the
// scene files (book 2.3, "Extending zraka"). Here without them: the built-in kinds only.
#include <zraka/app/whitted_main.hpp>

int main(int argc, char** argv) { return zraka::whitted_main(argc, argv); }

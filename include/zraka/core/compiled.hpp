#pragma once
// zraka is header-only, with a few exceptions: non-template code that nearly every program calls
// and that every unit would otherwise compile again at -O3 (a chapter's main.cpp went from
// 9.6 to ~2 CPU-s): the command-line layer on CLI11 (cli.hpp), the shared options' parsing and
// checks (program_options.hpp), writing images with stb_image_write's PNG encoder (image_io.hpp),
// atomic file writing (atomic_file.hpp), image::check_size (image.hpp), reading input files and
// the limits' checks (input_file.hpp, limits.hpp, render.hpp), the built-in scenes
// (default_scene.hpp, named_scenes.hpp), the convergence table (convergence.hpp), the Mitsuba
// export (mitsuba_export.hpp) and the triangle BVH's builder (triangle_bvh.hpp). Scene files (scene_file.hpp) and PLY/glTF meshes (mesh_file.hpp)
// follow the same pattern under their own macros, ZRAKA_COMPILED_SCENE_FILE and
// ZRAKA_COMPILED_MESH_FILE, defined when zraka was built with yaml-cpp and assimp, and so does the
// preview window of --window and gl.hpp's shaders (ZRAKA_COMPILED_GL, with GLFW and libepoxy),
// and the OpenCL host side of cl.hpp and realtime.hpp (ZRAKA_COMPILED_OPENCL, with OpenCL).
// Part 6's mis reference (reference.hpp) is compiled with the scene files, in src/reference.cpp.
// Their functions are marked ZRAKA_COMPILED_FN:
//   - linking the library zraka::compiled (src/compiled.cpp, built and installed with zraka) defines
//     ZRAKA_COMPILED: the headers only declare them, the library holds them, compiled once;
//   - without it (an outside project with only include/ on its path) they are inline functions
//     defined in the headers, and cli.hpp needs CLI11's headers (README.md's table).
// Every unit of one program must be built the same way; linking zraka::compiled does that.
// A function not defined here must not use ZRAKA_RESOURCE_DIR (resources.hpp): the library is
// built with the build tree's, an installed program has the install prefix's.
#if defined(ZRAKA_COMPILED)
#define ZRAKA_COMPILED_FN
#else
#define ZRAKA_COMPILED_FN inline
#endif
// Whether this unit sees the definitions: header-only, or src/compiled.cpp (ZRAKA_COMPILING).
#if !defined(ZRAKA_COMPILED) || defined(ZRAKA_COMPILING)
#define ZRAKA_COMPILED_DEFINITIONS 1
#else
#define ZRAKA_COMPILED_DEFINITIONS 0
#endif

// Templates at double, the precision of every chapter, are compiled once in the library too (and
// at float where a chapter uses it: the BVH builder, the .bpt reader and tessellation); among
// them the scene, lights, path tracer, BDPT, MLT, media, photon mapping and SPPM.
// ZRAKA_INSTANCE(declaration), written after a template's definition, is
//   - for the library's users an explicit instantiation declaration (extern template): a unit
//     calls the library's copy instead of compiling its own;
//   - in src/instances.cpp (ZRAKA_INSTANTIATING) the explicit instantiation definition;
//   - header-only, nothing.
// Only what is not inline benefits: a function template not declared inline, or a member defined
// outside its class. A member defined inside its class is inline and is still compiled wherever
// it is used, so the costly members of such classes are defined below them.
#if defined(ZRAKA_COMPILED) && defined(ZRAKA_INSTANTIATING)
#define ZRAKA_INSTANCE(...) template __VA_ARGS__;
#elif defined(ZRAKA_COMPILED)
#define ZRAKA_INSTANCE(...) extern template __VA_ARGS__;
#else
#define ZRAKA_INSTANCE(...)
#endif

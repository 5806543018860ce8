// The compiled part of zraka, the library zraka::compiled (include/zraka/compiled.hpp): the
// definitions that the headers below hold for header-only use, compiled once here instead of in
// every program. One unit, so that each is defined once.
#ifndef ZRAKA_COMPILED
#error "build src/compiled.cpp through the zraka_compiled target (it defines ZRAKA_COMPILED)"
#endif
#define ZRAKA_COMPILING
#include <zraka/atomic_file.hpp>
#include <zraka/cli.hpp>
#include <zraka/convergence.hpp>
#include <zraka/default_scene.hpp>
#include <zraka/image.hpp>
#include <zraka/image_error.hpp>
#include <zraka/image_io.hpp>
#include <zraka/input_file.hpp>
#include <zraka/limits.hpp>
#include <zraka/mitsuba_export.hpp>
#include <zraka/named_scenes.hpp>
#include <zraka/obj_file.hpp>
#include <zraka/program_options.hpp>
#include <zraka/progressive.hpp>
#include <zraka/render.hpp>
#include <zraka/scene_registry.hpp>
#include <zraka/triangle_bvh.hpp>
#if defined(ZRAKA_COMPILED_MESH_FILE)  // built with assimp
#include <zraka/mesh_file.hpp>
#endif
#if defined(ZRAKA_COMPILED_SCENE_FILE)  // built with yaml-cpp
#include <zraka/scene_argument.hpp>
#include <zraka/scene_file.hpp>
#endif
#if defined(ZRAKA_COMPILED_MITSUBA_XML)  // and pugixml
#include <zraka/mitsuba_xml.hpp>
#endif

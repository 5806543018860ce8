// The compiled part of zraka, the library zraka::compiled (include/zraka/core/compiled.hpp): the
// definitions that the headers below hold for header-only use, compiled once here instead of in
// every program. One unit, so that each is defined once.
#ifndef ZRAKA_COMPILED
#error "build src/compiled.cpp through the zraka_compiled target (it defines ZRAKA_COMPILED)"
#endif
#define ZRAKA_COMPILING
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/app/cli.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/core/atomic_file.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/core/parallel.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/mitsuba_export.hpp>
#include <zraka/io/obj_file.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/scene/default_scene.hpp>
#include <zraka/scene/named_scenes.hpp>
#include <zraka/scene/scene_registry.hpp>
#if defined(ZRAKA_COMPILED_MESH_FILE)  // built with assimp
#include <zraka/io/mesh_file.hpp>
#endif
#if defined(ZRAKA_COMPILED_SCENE_FILE)  // built with yaml-cpp
#include <zraka/io/scene_argument.hpp>
#include <zraka/io/scene_file.hpp>
#endif
#if defined(ZRAKA_COMPILED_MITSUBA_XML)  // and pugixml
#include <zraka/io/mitsuba_xml.hpp>
#endif

// The templates that zraka's headers mark ZRAKA_INSTANCE, compiled here once at double (and the
// BVH builder, the .bpt reader and tessellation at float, for meshes and the GPU), instead of in
// every program that uses them (compiled.hpp).
// Every header that marks one is included here, so that each instance is defined exactly once.
#ifndef ZRAKA_COMPILED
#error "build src/instances.cpp through the zraka_compiled target (it defines ZRAKA_COMPILED)"
#endif
#define ZRAKA_INSTANTIATING
#include <zraka/bdpt.hpp>
#include <zraka/bpt.hpp>
#include <zraka/bvh.hpp>
#include <zraka/camera.hpp>
#include <zraka/cornell.hpp>
#include <zraka/gpu_scene.hpp>
#include <zraka/lights.hpp>
#include <zraka/material.hpp>
#include <zraka/media.hpp>
#include <zraka/medium.hpp>
#include <zraka/metropolis.hpp>
#include <zraka/path.hpp>
#include <zraka/photon_mapping.hpp>
#include <zraka/photons.hpp>
#include <zraka/scene.hpp>
#include <zraka/scene_query.hpp>
#include <zraka/sppm.hpp>
#include <zraka/tessellate.hpp>
#include <zraka/triangle_bvh.hpp>
#include <zraka/texture.hpp>

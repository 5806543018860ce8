// The templates that zraka's headers mark ZRAKA_INSTANCE, compiled here once at double (and the
// BVH builder, the .bpt reader and tessellation at float, for meshes and the GPU), instead of in
// every program that uses them (compiled.hpp).
// Every header that marks one is included here, so that each instance is defined exactly once.
#ifndef ZRAKA_COMPILED
#error "build src/instances.cpp through the zraka_compiled target (it defines ZRAKA_COMPILED)"
#endif
#define ZRAKA_INSTANTIATING
#include <zraka/accel/bvh.hpp>
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/cameras/camera.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/metropolis.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/photon_mapping.hpp>
#include <zraka/integrators/photons.hpp>
#include <zraka/integrators/sppm.hpp>
#include <zraka/io/bpt.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/media/medium.hpp>
#include <zraka/scene/cornell.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/media.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>
#include <zraka/textures/texture.hpp>

#pragma once
// A course's own integrator, written as an instructor would against zraka (not part of the
// library): ambient occlusion. Where the camera ray first meets a surface, the estimate is the
// fraction of the cosine-weighted hemisphere above it that is free of other surfaces within
// `max_distance`: one direction from the cosine density per sample, 1 if it is free, 0 if not (so
// the pixel's mean is that fraction, unbiased). A ray that meets nothing gives 0: nothing is seen.
// Registered by name, so `--integrator ao` picks it in a program built on zraka::pathtrace_main;
// used by tests/test_course_program.cpp.
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/sampling/sampling.hpp>
#include <zraka/scene/scene_query.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <cmath>
#include <cstdint>
#include <string>

namespace course {

// The estimate of one camera sample.
inline zraka::rgb ambient_occlusion(const zraka::scene& sc, const zraka::ray& r, zraka::rng& g, std::uint64_t& rays,
                                    double max_distance) {
  zraka::scene_hit sh;
  ++rays;
  if (!zraka::nearest_hit(sc, r, sh)) return zraka::rgb(0);
  // The hemisphere on the side the camera ray came from.
  const zraka::vec3 n = glm::dot(sh.h.normal, r.direction) < 0 ? sh.h.normal : -sh.h.normal;
  const zraka::vec3 wi = zraka::cosine_hemisphere_dist(n).sample(zraka::vec2(g.uniform2()));
  zraka::scene_hit blocker;
  ++rays;
  return zraka::rgb(zraka::nearest_hit(sc, zraka::spawn_ray(sh.h, wi), blocker, max_distance) ? 0.0f : 1.0f);
}

// [listing register-ao]
inline void register_ao(zraka::scene_registry& reg, double max_distance) {
  if (!(max_distance > 0)) throw zraka::error("ao: the maximum distance must be positive");
  reg.add_integrator("ao", [max_distance](const zraka::scene& sc, const zraka::path_options&) {
    return [&sc, max_distance](const zraka::ray& r, zraka::rng& g, std::uint64_t& rays) {
      return ambient_occlusion(sc, r, g, rays, max_distance);
    };
  });
}
// [end]

}  // namespace course

#pragma once
// A compact path tracer over a scene (book 2.3, the loop of Listing 4.6 done right): follow one
// path from the camera, at each hit add the light emitted there, then continue in the direction
// the material scatters to, multiplying the throughput by the material's weight f cos / pdf
// (erratum C6: the weight, not "colour times cosine").
//
// With next_event on (the default) it also samples a light at every non-specular hit and adds
// its contribution if the shadow segment is free (next-event estimation, erratum C4). Emission
// found by the scattered ray after such a hit is then skipped, or it would be counted twice.
// Mirrors and glass cannot use light samples (a point light is never in their exact direction),
// so emission seen through them is always counted. Paths longer than three bounces continue
// with probability min(1, max throughput) (Russian roulette), which keeps the mean unchanged.
//
// integrators.hpp holds the full versions of book 2.3 (naive, nee, mis, selectable; glowing
// surfaces and point lights sampled too); this compact one serves chapters 1.7 and 1.8.
#include <zraka/material.hpp>
#include <zraka/rng.hpp>
#include <zraka/scene.hpp>
#include <zraka/spawn.hpp>

#include <cstdint>

namespace zraka {

struct path_options {
  int max_depth = 8;         // bounces; 1 = direct light only
  bool next_event = true;    // sample the lights at diffuse hits
};

// [listing path]
template <class T>
rgb path_radiance(const scene_t<T>& sc, ray_t<T> r, rng& g, const path_options& opt, std::uint64_t& rays) {
  rgb L(0), beta(1);
  bool count_emission = true;  // camera rays, and rays after a specular bounce or without NEE
  for (int depth = 0; depth <= opt.max_depth; ++depth) {
    scene_hit_t<T> sh;
    ++rays;
    if (!nearest_hit(sc, r, sh)) {
      L += beta * sc.background;  // the sky is a light no sampler knows about: always counted
      break;
    }
    const material& m = sc.materials[sh.material];
    if (count_emission) L += beta * emitted(m, sh.h);
    if (m.kind == material_kind::emitter || depth == opt.max_depth) break;

    const vec3_t<T> wo = -r.direction;
    if (opt.next_event && !is_specular(m)) {
      if (const auto ls = sample_light(sc, sh.h.p, g); ls && ls->radiance != rgb(0)) {
        ++rays;
        if (!occluded(sc, spawn_segment(sh.h, ls->point)))
          L += beta * brdf_cos(m, sh.h, wo, ls->wi) * ls->radiance / float(ls->pdf);
      }
    }
    const auto s = scatter(m, r.direction, sh.h, g);
    if (!s) break;  // absorbed
    beta *= s->weight;
    count_emission = s->specular || !opt.next_event;
    if (depth >= 3) {  // Russian roulette
      const float q = std::min(1.0f, max_component(beta));
      if (!(g.uniform() < q)) break;
      beta /= q;
    }
    r = spawn_ray(sh.h, s->direction);
  }
  return L;
}
// [end]

}  // namespace zraka

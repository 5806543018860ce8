#pragma once
// Photons (book 6.3): light followed from the lights, the other way round from the path loop.
// A photon leaves a light chosen by power at a point and in a direction drawn by
// light_set_t::sample_emission (lights.hpp) and carries the flux
//     Phi = L_e |cos theta_l| / (p_A(x) p_w(w))      (a point light: I / (P(choose) / 4 pi)),
// so that the mean of Phi over the photons of a pass is the lights' total power. At every hit it
// scatters with the core's materials (scatter() in material.hpp: the weight f |cos| / p is what
// the flux is multiplied by), specular kinds included; it is stored only where the material has a
// density (has_density: a Lambert, Phong or custom surface), because a density estimate needs a
// BRDF to evaluate. Russian roulette is the path loop's (survives_roulette, path_kit.hpp). Glass needs no
// eta^2 factor here: flux, unlike radiance, is not compressed across a boundary.
//
// Photons of a pass are traced in fixed chunks, parallel_for's items (parallel.hpp); photon i of
// pass k has its own stream rng(seed, i, photon_stream + k), and the chunks are merged in chunk
// order, so the photons (and everything made from them) are the same for any number of threads.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/parallel.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/integrators/path_kit.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

namespace zraka {

template <class T> struct photon_t {
  vec3_t<T> p{T(0)};   // where it landed
  vec3_t<T> wi{T(0)};  // unit, back towards where it came from
  rgb power{0};        // flux Phi (watts, per photon; divide by the photons emitted)
  int bounces = 0;     // scatterings before it landed: 0 = straight from a light
  bool caustic = false;  // L S+ D: at least one bounce, every one specular
};

struct photon_options {
  int max_depth = 8;  // bounces, as the path loop counts them
  int rr_depth = 3;   // Russian roulette from this many bounces on
  int chunk = 1024;   // photons per work unit (fixed: the result must not depend on threads)
};

// Camera streams use rng(seed, pixel, pass); photon streams are offset in the second word.
constexpr std::uint32_t photon_stream = 0x80000000u;

// Photon mapping cannot start photons at emitters the light set does not sample (the
// background, an infinite plane, a user shape without area sampling): refuse them by name.
template <class T> void check_photon_scene(const scene_t<T>& sc, const light_set_t<T>& lights) {
  if (!sc.media.empty())
    throw error("photon mapping: the scene has participating media (" + sc.media_names() +
                "), which these photons do not scatter in (no volume photons); render it with pathtrace");
  if (sc.environment)
    throw error("photon mapping: the scene has an environment light ('" + sc.environment->name() +
                "'), which photons cannot be emitted from (no environment emission); render it with pathtrace");
  if (sc.background != rgb(0))
    throw error("photon mapping: the background emits, and photons cannot leave it (no environment emission)");
  if (!lights.hit_only().empty()) {
    std::string names;
    for (const auto& n : lights.hit_only()) names += (names.empty() ? "" : ", ") + n;
    throw error("photon mapping: emitters that cannot emit photons (hit only): " + names);
  }
  if (lights.empty()) throw error("photon mapping: the scene has no lights");
}
ZRAKA_INSTANCE(void check_photon_scene(const scene_t<double>&, const light_set_t<double>&))  // compiled.hpp

// [listing trace-photon]
// One photon from stream g; store(const photon_t&) sees every landing on a surface with a
// density. Returns the emitted flux (zero when the emission sample failed).
template <class T, class Store>
rgb trace_photon(const scene_t<T>& sc, const light_set_t<T>& lights, rng& g, const photon_options& opt,
                 Store&& store, std::uint64_t& rays) {
  const T u_select = T(g.uniform());
  const vec2_t<T> u_pos(g.uniform2());
  const vec2_t<T> u_dir(g.uniform2());
  const auto e = lights.sample_emission(u_select, u_pos, u_dir);
  if (!e || e->Le == rgb(0)) return rgb(0);
  const T cos_l = e->delta_position ? T(1) : std::abs(glm::dot(e->normal, e->direction));
  const rgb Phi = e->Le * float(cos_l / (e->pdf_position * e->pdf_direction));
  if (!is_finite(Phi)) return rgb(0);
  ray_t<T> r{e->delta_position ? e->point : offset_origin(e->point, e->p_error, e->normal, e->direction),
             e->direction};
  rgb beta(1);
  bool all_specular = true;
  for (int bounce = 0; bounce <= opt.max_depth; ++bounce) {
    scene_hit_t<T> sh;
    ++rays;
    if (!nearest_hit(sc, r, sh)) break;
    const material& m = sc.materials[std::size_t(sh.material)];
    if (has_density(m)) store(photon_t<T>{sh.h.p, -r.direction, Phi * beta, bounce, bounce > 0 && all_specular});
    if (bounce == opt.max_depth) break;
    const auto s = scatter(m, r.direction, sh.h, g);
    if (!s) break;  // absorbed (or an emitter, which does not reflect)
    beta *= s->weight;
    all_specular = all_specular && s->specular;
    if (!survives_roulette(beta, bounce, opt.rr_depth, g)) break;
    r = spawn_ray(sh.h, s->direction);
  }
  return Phi;
}
// [end]

template <class T> struct photon_pass_t {
  std::vector<photon_t<T>> photons;  // in photon order
  std::uint64_t emitted = 0;         // photons emitted (count)
  vec3 emitted_flux{0};              // sum of Phi over them (double)
  std::uint64_t rays = 0;
};

// [listing photon-pass]
// `count` photons of pass `pass`; keep(const photon_t&) decides which are stored.
template <class T, class Keep>
photon_pass_t<T> trace_photons(const scene_t<T>& sc, const light_set_t<T>& lights, std::uint64_t count,
                               std::uint64_t seed, std::uint32_t pass, const photon_options& opt, int threads,
                               Keep&& keep) {
  if (count == 0) throw error("photon mapping: the number of photons must be positive");
  if (count > 0xffffffffull) throw error("photon mapping: at most 2^32 - 1 photons per pass");
  if (opt.chunk < 1) throw error("photon mapping: the chunk size must be positive");
  const std::uint64_t chunk = std::uint64_t(opt.chunk), chunks = (count + chunk - 1) / chunk;
  std::vector<photon_pass_t<T>> parts(chunks);
  parallel_for(chunks, threads, [&](std::size_t c) {
    photon_pass_t<T>& part = parts[c];
    for (std::uint64_t i = c * chunk; i < std::min(count, (c + 1) * chunk); ++i) {
      rng g(seed, std::uint32_t(i), photon_stream + pass);
      const rgb Phi = trace_photon(sc, lights, g, opt, [&](const photon_t<T>& p) {
        if (keep(p)) part.photons.push_back(p);
      }, part.rays);
      part.emitted_flux += vec3(Phi);
      ++part.emitted;
    }
  });
  photon_pass_t<T> all;  // merged in chunk order: the same for any thread count
  for (auto& part : parts) {
    all.photons.insert(all.photons.end(), part.photons.begin(), part.photons.end());
    all.emitted += part.emitted, all.emitted_flux += part.emitted_flux, all.rays += part.rays;
  }
  return all;
}
// [end]

}  // namespace zraka

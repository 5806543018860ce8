#pragma once
// The path tracer (book 2.3): one loop that estimates the rendering equation
//     L_o(x, wo) = L_e(x, wo) + integral f(x, wi, wo) L_i(x, wi) |cos theta_i| dwi
// by following one path from the camera. Its option `method` decides how light is found, with
// the same mean and different noise:
//   naive  the thesis's algorithm (Listing 2.3, iterative as in its Listing 4.6): follow the
//          scattered ray and add the light it happens to hit. The throughput beta is multiplied
//          by f cos / pdf, the cosine counted once (erratum C6). It cannot find point lights (a
//          ray never hits a point), so it refuses scenes that have them.
//   nee    next-event estimation (erratum C4): at every hit with a density also pick a point on
//          a light (lights.hpp) and add its light if the shadow segment is free. Emission the
//          scattered ray then finds on a sampled light is skipped: it was counted.
//   mis    multiple importance sampling (Veach and Guibas 1995): the light sample and the
//          BSDF-sampled ray that hits a light are both kept, each weighted by the power heuristic
//          of the two densities for its direction, so the two weights of one path sum to one.
// Emission nobody samples (the background colour, an infinite plane: lights.hpp) is always
// counted where a ray finds it; the environment light (environment.hpp) is sampled like any
// light, and a ray that leaves the scene finds it. Paths stop at max_depth bounces and, from
// rr_depth bounces on, go on with probability q = min(1, max throughput), dividing by q
// (Russian roulette: unbiased).
//
// Participating media (book 6.1, media.hpp): in a medium each segment first samples a
// free-flight distance (medium.hpp); a medium event is a vertex like a surface's, with the phase
// function as its BSDF: next-event estimation with a transmittance-weighted shadow ray, MIS with
// phase sampling. Index-matched boundaries are crossed without counting a bounce. All of it runs
// only when the scene has media: other scenes draw exactly the numbers they always did.
//
// The OpenCL kernel (kernels/pathtrace.cl) mirrors this loop line for line (without media:
// gpu_scene.hpp refuses them).
#include <zraka/core/compiled.hpp>
#include <zraka/core/enum_names.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/integrators/next_event.hpp>
#include <zraka/integrators/path_kit.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/media/phase.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/media.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <algorithm>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace zraka {

enum class integrator { naive, nee, mis };
inline constexpr enum_name<integrator> integrator_names[] = {
    {integrator::naive, "naive"}, {integrator::nee, "nee"}, {integrator::mis, "mis"}};
constexpr std::span<const enum_name<integrator>> enum_names(integrator) { return integrator_names; }  // enum_names.hpp
inline integrator parse_integrator(std::string_view s) { return parse_enum<integrator>(s, "integrator"); }

struct path_options {
  integrator method = integrator::mis;
  int max_depth = 8;  // bounces; 0 = only what the camera ray hits (the thesis's depth 1)
  int rr_depth = 3;   // Russian roulette from this many bounces on
  light_selection lights = light_selection::power;
  medium_options media;  // book 6.1: delta tracking or ray marching (medium.hpp)
};

// [listing path]
template <class T>
rgb path_radiance(const scene_t<T>& sc, const light_set_t<T>& lights, ray_t<T> r, rng& g,
                  const path_options& opt, std::uint64_t& rays) {
  const bool nee = opt.method != integrator::naive, mis = opt.method == integrator::mis;
  rgb L(0), beta(1);
  bool specular = true;  // the last bounce had no density (camera rays count as specular)
  T bsdf_pdf = T(0);     // the density of the last scattered direction
  vec3_t<T> from(T(0));  // the point it left from
  const bool media = !sc.media.empty();
  int current = sc.global_medium;  // the medium the path is in (-1: none)
  for (int bounce = 0;; ++bounce) {
    scene_hit_t<T> sh;
    ++rays;
    const bool found = nearest_hit(sc, r, sh);
    if (media && current >= 0) {  // in a medium: does the path interact before the surface?
      const medium& md = sc.media[std::size_t(current)];
      const auto f = sample_flight(md, r, found ? sh.h.t : infinity<T>, g, opt.media);
      beta *= f.weight;
      if (f.scattered) {  // a medium event: the phase function is this vertex's BSDF
        if (bounce == opt.max_depth || beta == rgb(0)) return L;
        hit_t<T> mh;  // a point in space: no normal, no rounding to step off
        mh.p = r.at(f.t);
        const phase_t<T> ph{T(md.g)};
        const vec3_t<T> wo = -r.direction;
        if (nee) {  // the next event (next_event.hpp), its shadow ray through the media
          const auto through_media = [&](const light_sample_t<T>& e) {
            return shadow_transmittance(sc, e.shadow, current, g, opt.media, rays);
          };
          if (const auto ne = next_event(lights, mh, medium_vertex_t<T>{ph, wo}, mis, bounce, g, through_media, rays))
            L += ne->estimate(beta);
        }
        g.seek(path_number(bounce, path_slot::bsdf));
        const phase_sample_t<T> ps = ph.sample(wo, vec2_t<T>(g.uniform2()));  // weight p / pdf = 1
        specular = false;
        bsdf_pdf = ps.pdf;
        from = mh.p;
        if (!survives_roulette(beta, bounce, opt.rr_depth, g)) return L;
        r = ray_t<T>(mh.p, ps.wi);
        continue;
      }
    }
    if (!found) {
      if (!sc.environment) return L + beta * sc.background;  // no sampler knows a plain background
      // The environment light, found by this ray: by the same rule as emission below.
      const rgb Le = sc.environment->radiance(r.direction);
      if (!nee || specular || lights.environment_index() < 0) return L + beta * Le;
      if (mis) return L + beta * Le * float(power_heuristic(bsdf_pdf, lights.environment_pdf(r.direction)));
      return L;
    }
    const material& m = sc.materials[std::size_t(sh.material)];
    if (media && is_index_matched(m)) {  // a boundary only: cross it, not a bounce
      current = medium_after(sc, current, m, sh.h, r.direction);
      r = spawn_ray(sh.h, r.direction);
      --bounce;
      continue;
    }
    // Emission found by this ray: all of it, its MIS share, or none (nee: the light sample at
    // the previous hit counted this light already).
    if (const rgb Le = emitted(m, sh.h); Le != rgb(0)) {
      if (!nee || specular || lights.index_of(sh.object) < 0) L += beta * Le;
      else if (mis && media) {  // the ray may have crossed boundaries since `from`: its t is not the distance
        hit_t<T> lh = sh.h;
        lh.t = glm::length(sh.h.p - from);
        L += beta * Le * float(power_heuristic(bsdf_pdf, lights.pdf(sh.object, from, r.direction, lh)));
      } else if (mis) L += beta * Le * float(power_heuristic(bsdf_pdf, lights.pdf(sh.object, from, r.direction, sh.h)));
    }
    if (bounce == opt.max_depth) return L;
    const vec3_t<T> wo = -r.direction;
    if (nee && has_density(m)) {  // the next event: a point on a light (next_event.hpp)
      const auto shadow = [&](const light_sample_t<T>& e) {
        return !media ? rgb(occluded(sc, e.shadow) ? 0.0f : 1.0f)
                      : shadow_transmittance(sc, e.shadow, medium_after(sc, current, m, sh.h, e.wi), g, opt.media, rays);
      };
      if (const auto ne = next_event(lights, sh.h, surface_vertex_t<T>{m, sh.h, wo}, mis, bounce, g, shadow, rays))
        L += ne->estimate(beta);
    }
    g.seek(path_number(bounce, path_slot::bsdf));
    const auto s = scatter(m, r.direction, sh.h, g);
    if (!s) return L;  // absorbed (or a light, which does not reflect)
    beta *= s->weight;  // f cos / pdf: the cosine is counted once, inside the weight
    specular = s->specular;
    bsdf_pdf = s->pdf;
    from = sh.h.p;
    if (media) current = medium_after(sc, current, m, sh.h, s->direction);
    if (!survives_roulette(beta, bounce, opt.rr_depth, g)) return L;
    r = spawn_ray(sh.h, s->direction);
  }
}
// [end]

// A scene, its lights and the options, ready to give the radiance along a camera ray.
template <class T> struct path_tracer_t {
  const scene_t<T>& sc;
  light_set_t<T> lights;
  path_options opt;

  path_tracer_t(const scene_t<T>& scene, const path_options& o);
  rgb operator()(const ray_t<T>& r, rng& g, std::uint64_t& rays) const {
    return path_radiance(sc, lights, r, g, opt, rays);
  }
  // What this scene made the renderer build and which branches of the loop its paths can take
  // (issue 17, "leave out what a scene does not need"), for the summary line.
  std::string choices() const;
};

template <class T>
path_tracer_t<T>::path_tracer_t(const scene_t<T>& scene, const path_options& o)
    : sc(scene), lights(scene, o.lights), opt(o) {
  if (o.max_depth < 0) throw error("the maximum depth must not be negative, got " + std::to_string(o.max_depth));
  if (o.rr_depth < 0) throw error("the Russian roulette depth must not be negative");
  check_media(scene, o.media);
  if (o.method == integrator::naive && !scene.lights.empty())  // lights/light.hpp: at a point
    throw error("integrator naive: the scene has " + std::to_string(scene.lights.size()) +
                " point light(s), which a ray can never hit; use nee or mis");
}

template <class T> std::string path_tracer_t<T>::choices() const {
  std::string out = sc.has_object_bvh() ? "object BVH over " + std::to_string(sc.accel.objects.size()) + " objects"
                                        : "no object BVH (" + std::to_string(sc.bounded_count()) + " objects in a list)";
  if (!sc.meshes.empty()) out += ", " + std::to_string(sc.meshes.size()) + " triangle BVH(s)";
  out += opt.method == integrator::naive ? ", no light sampling" : ", " + std::to_string(lights.size()) + " light(s) sampled";
  std::vector<std::string> kinds;  // in the order the scene first uses them
  for (const material& m : sc.materials)
    if (const std::string k = is_custom(m) ? "custom" : kind_name(m.kind); std::find(kinds.begin(), kinds.end(), k) == kinds.end())
      kinds.push_back(k);
  std::string joined;
  for (const std::string& k : kinds) joined += (joined.empty() ? "" : "+") + k;
  out += ", materials " + (joined.empty() ? std::string("none") : joined);
  out += sc.media.empty() ? ", media branch off" : ", media branch on";
  out += sc.environment ? ", environment on" : ", environment off";
  return out + " (one compiled loop; branches chosen per path)";
}

using path_tracer = path_tracer_t<double>;

// Compiled once at double (compiled.hpp).
ZRAKA_INSTANCE(rgb path_radiance(const scene_t<double>&, const light_set_t<double>&, ray_t<double>,
                                 rng&, const path_options&, std::uint64_t&))
ZRAKA_INSTANCE(struct path_tracer_t<double>)

}  // namespace zraka

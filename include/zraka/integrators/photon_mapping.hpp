#pragma once
// Photon mapping, the camera side (book 6.3; Jensen 1996). A camera path follows mirrors and
// glass (scatter, as the path loop does) to the first surface with a density: the visible point
// x. There the light is split by the kind of path that brought it, each part found by the
// technique that finds it best, and no path counted twice:
//   emission     seen directly or through specular bounces (L S* E);
//   direct       next-event estimation at x through light_set_t::sample, as the path loop's nee
//                (L D E, and L D S+ E);
//   caustics     the caustic map's density estimate at x: photons whose path was L S+ D;
//   indirect     final gathering: one direction from x by the core's scatter(), followed through
//                specular bounces to a surface y with a density, and the global map's estimate
//                of everything y reflects (L (S|D)* D y, then D x).
// Emission found by the gathering ray is skipped (direct light and caustics counted it).
#include <zraka/core/compiled.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/integrators/next_event.hpp>
#include <zraka/integrators/photon_map.hpp>
#include <zraka/integrators/photons.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <cstdint>
#include <string>

namespace zraka {

template <class T> struct visible_point_t {
  bool found = false;
  scene_hit_t<T> sh;
  vec3_t<T> wo{T(0)};
  rgb beta{1};    // camera throughput up to x
  rgb direct{0};  // emission on the way plus next-event estimation at x, times beta
};

// [listing visible-point]
template <class T>
visible_point_t<T> find_visible_point(const scene_t<T>& sc, const light_set_t<T>& lights, ray_t<T> r, rng& g,
                                      int max_depth, std::uint64_t& rays) {
  visible_point_t<T> vp;
  for (int bounce = 0; bounce <= max_depth; ++bounce) {
    ++rays;
    if (!nearest_hit(sc, r, vp.sh)) return vp;  // the background is black (check_photon_scene)
    const material& m = sc.materials[std::size_t(vp.sh.material)];
    vp.direct += vp.beta * emitted(m, vp.sh.h);
    const vec3_t<T> wo = -r.direction;
    if (has_density(m)) {  // the path loop's next event (next_event.hpp), without MIS
      const auto shadow = [&](const light_sample_t<T>& e) { return rgb(occluded(sc, e.shadow) ? 0.0f : 1.0f); };
      // f Le / pdf, divided as this chapter's images were made (estimate() multiplies by 1 / pdf:
      // the same value, rounded differently)
      if (const auto ne = next_event(lights, vp.sh.h, surface_vertex_t<T>{m, vp.sh.h, wo}, false, -1, g, shadow, rays))
        vp.direct += vp.beta * ne->at.f * ne->Le / float(ne->pdf);
      vp.found = true;
      vp.wo = wo;
      return vp;
    }
    const auto s = scatter(m, r.direction, vp.sh.h, g);
    if (!s) return vp;
    vp.beta *= s->weight;
    r = spawn_ray(vp.sh.h, s->direction);
  }
  return vp;
}
// [end]

struct photon_map_options {
  std::uint64_t photons = 200000;  // emitted for both maps (the caustic map keeps its share)
  double radius = 0.05;            // of the density estimate's disc
  int max_depth = 8;               // camera and gathering paths
  photon_options trace;
  std::uint64_t seed = 1;
  int threads = 0;
};

template <class T> class photon_mapper_t {
 public:
  // Traces the photons and builds both maps. Throws zraka::error.
  photon_mapper_t(const scene_t<T>& sc, const photon_map_options& o);

  const light_set_t<T>& lights() const { return lights_; }
  std::size_t global_size() const { return global_.size(); }
  std::size_t caustic_size() const { return caustic_.size(); }

  // The radiance along camera ray r (find_visible_point, the caustic map, final gathering).
  rgb operator()(const ray_t<T>& r, rng& g, std::uint64_t& rays) const;

 private:
  const scene_t<T>& sc_;
  light_set_t<T> lights_;
  photon_map_options opt_;
  photon_grid_t<T> global_, caustic_;
  std::uint64_t emitted_ = 0;
};

// The members below the class: compiled once at double with zraka::compiled (compiled.hpp).
template <class T>
photon_mapper_t<T>::photon_mapper_t(const scene_t<T>& sc, const photon_map_options& o)
    : sc_(sc), lights_(sc), opt_(o) {
  if (!(o.radius > 0) || !std::isfinite(o.radius))
    throw error("photon mapping: --radius must be positive, got " + std::to_string(o.radius));
  check_photon_scene(sc, lights_);
  // [listing two-maps]
  auto pass = trace_photons(sc, lights_, o.photons, o.seed, 0, o.trace, o.threads,
                            [](const photon_t<T>&) { return true; });
  emitted_ = pass.emitted;
  std::vector<photon_t<T>> caustic;
  for (const auto& p : pass.photons)
    if (p.caustic) caustic.push_back(p);
  caustic_.build(std::move(caustic), T(o.radius));
  global_.build(std::move(pass.photons), T(o.radius));  // every stored photon: all y reflects
  // [end]
}

// [listing photon-radiance]
template <class T>
rgb photon_mapper_t<T>::operator()(const ray_t<T>& r, rng& g, std::uint64_t& rays) const {
  const T rad = T(opt_.radius);
  const visible_point_t<T> vp = find_visible_point(sc_, lights_, r, g, opt_.max_depth, rays);
  if (!vp.found) return vp.direct;
  const material& m = sc_.materials[std::size_t(vp.sh.material)];
  rgb L = vp.direct + vp.beta * photon_density(caustic_, emitted_, m, vp.sh.h, vp.wo, rad);
  // Final gathering: one bounce of the path loop's BSDF sampling, then the global map at y.
  const auto s = scatter(m, -vp.wo, vp.sh.h, g);
  if (!s) return L;
  rgb beta = vp.beta * s->weight;
  ray_t<T> gather = spawn_ray(vp.sh.h, s->direction);
  for (int bounce = 0; bounce < opt_.max_depth; ++bounce) {
    scene_hit_t<T> y;
    ++rays;
    if (!nearest_hit(sc_, gather, y)) break;
    const material& my = sc_.materials[std::size_t(y.material)];
    if (has_density(my)) {
      L += beta * photon_density(global_, emitted_, my, y.h, -gather.direction, rad);
      break;
    }
    const auto sy = scatter(my, gather.direction, y.h, g);  // through glass and mirrors
    if (!sy) break;
    beta *= sy->weight;
    gather = spawn_ray(y.h, sy->direction);
  }
  return L;
}
// [end]

ZRAKA_INSTANCE(class photon_mapper_t<double>)  // compiled.hpp

}  // namespace zraka

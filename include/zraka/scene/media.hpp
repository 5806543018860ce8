#pragma once
// A scene's media along paths (book 6.1): which medium a path is in after crossing a surface,
// and how much light a shadow segment lets through. The path loop (path.hpp) asks these only
// when the scene has media, so scenes without them draw exactly the numbers they always did.
//
// Every path starts in scene.global_medium (fog: the camera is in it; -1 clear air). A surface
// whose material names an interior medium is the boundary of a closed shape filled with it:
// leaving the surface into its back side (against the outward normal) enters the interior,
// leaving into its front side returns to the global medium. Surfaces that name no medium do not
// change it (a glass sphere in fog is full of fog unless it names a medium). Shapes with media
// do not nest: the outside of each is the global medium.
#include <zraka/core/compiled.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/media/medium.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <cstdint>
#include <string>

namespace zraka {

// [listing medium-after]
template <class T>
int medium_after(const scene_t<T>& sc, int current, const material& m, const hit_t<T>& h, const vec3_t<T>& w) {
  if (m.interior < 0) return current;
  return glm::dot(w, h.normal) < T(0) ? m.interior : sc.global_medium;
}
// [end]

// [listing shadow-transmittance]
// The light a shadow segment lets through, starting in medium `current`: the transmittance of
// every medium it crosses, across index-matched boundaries (material.hpp: is_index_matched);
// 0 if anything else is in the way (glass refracts: a straight shadow ray cannot pass it).
template <class T>
rgb shadow_transmittance(const scene_t<T>& sc, segment_t<T> s, int current, rng& g, const medium_options& o,
                         std::uint64_t& rays) {
  const vec3_t<T> target = s.ray.at(s.t_max);
  rgb tr(1);
  for (int crossing = 0; crossing < 1024; ++crossing) {
    scene_hit_t<T> sh;
    const bool hit = nearest_hit(sc, s.ray, sh, s.t_max);
    if (current >= 0) tr *= segment_transmittance(sc.media[std::size_t(current)], s.ray, hit ? sh.h.t : s.t_max, g, o);
    if (!hit) return tr;
    if (!is_index_matched(sc.materials[std::size_t(sh.material)]) || tr == rgb(0)) return rgb(0);
    current = medium_after(sc, current, sc.materials[std::size_t(sh.material)], sh.h, s.ray.direction);
    const ray_t<T> next = spawn_ray(sh.h, s.ray.direction);
    s.t_max = glm::dot(target - next.origin, s.ray.direction);
    if (!(s.t_max > T(0))) return tr;
    s.ray = next;
    ++rays;
  }
  return rgb(0);  // a thousand boundaries: give up, darker rather than wrong-bright
}
// [end]

// What the path loop cannot do with these media and options, refused by name.
template <class T> void check_media(const scene_t<T>& sc, const medium_options& o) {
  const int n = static_cast<int>(sc.media.size());
  if (sc.global_medium < -1 || sc.global_medium >= n)
    throw error("media: the global medium " + std::to_string(sc.global_medium) + " does not exist");
  for (std::size_t i = 0; i < sc.materials.size(); ++i)
    if (sc.materials[i].interior < -1 || sc.materials[i].interior >= n)
      throw error("media: " + sc.material_label(int(i)) + " names medium " + std::to_string(sc.materials[i].interior) +
                  ", which does not exist");
  if (o.estimator == media_estimator::march && !(o.step > 0 && std::isfinite(o.step)))
    throw error("media: the march step must be positive and finite, got " + std::to_string(o.step));
  for (const medium& m : sc.media) {
    m.check();
    if (!m.homogeneous() && o.estimator == media_estimator::march &&
        glm::length(m.density->box().hi - m.density->box().lo) / o.step > 1e6)  // a typo must not hang
      throw error("medium '" + m.name + "': a march step of " + std::to_string(o.step) +
                  " takes more than a million steps across its density grid");
    if (!m.homogeneous() && o.estimator == media_estimator::delta && !m.gray())
      throw error("medium '" + m.name + "': delta tracking of a density grid needs the same sigma_t in every "
                  "channel (sigma_a + sigma_s); make it gray or use the march estimator");
  }
}

// Compiled once at double (compiled.hpp).
ZRAKA_INSTANCE(rgb shadow_transmittance(const scene_t<double>&, segment_t<double>, int, rng&,
                                        const medium_options&, std::uint64_t&))
ZRAKA_INSTANCE(void check_media(const scene_t<double>&, const medium_options&))

}  // namespace zraka

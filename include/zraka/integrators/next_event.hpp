#pragma once
// Next-event estimation, written once (book 2.3, 6.1, 6.3): at a vertex of a camera path, pick a
// point on a light (lights.hpp), see what the vertex sends on towards the camera from it, send a
// shadow ray and, with multiple importance sampling, weight the sample against the vertex's own
// sampling by the power heuristic. The path loop (path.hpp) calls it at surfaces and at medium
// events, photon mapping (photon_mapping.hpp) at its visible points. What differs is the vertex
// (a surface's BSDF or a medium's phase function: surface_vertex_t, medium_vertex_t below), the
// shadow ray (a yes/no, or a transmittance through media) and whether MIS applies.
#include <zraka/core/vec.hpp>  // ZRAKA_FORCE_INLINE
#include <zraka/integrators/path_kit.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/media/phase.hpp>
#include <zraka/scene/lights.hpp>

#include <cstdint>
#include <optional>

namespace zraka {

// What the vertex makes of light arriving from wi: f, times the scalar s (kept apart so that the
// product is formed in one order for both kinds of vertex, and the images stay as they were).
template <class T> struct vertex_response_t {
  rgb f{0};
  T s = T(1);
};

// A surface: f |cos theta_i| (brdf_cos) and the density scatter() gives wi (scatter_pdf).
template <class T> struct surface_vertex_t {
  const material& m;
  const hit_t<T>& h;
  vec3_t<T> wo;
  vertex_response_t<T> response(const vec3_t<T>& wi) const { return {brdf_cos(m, h, wo, wi), T(1)}; }
  T pdf(const vec3_t<T>& wi) const { return scatter_pdf(m, h, wo, wi); }
};

// A medium event: the phase function is both the response and its own sampling density. It is
// never zero (|g| < 1), so the shadow ray is always sent.
template <class T> struct medium_vertex_t {
  phase_t<T> phase;
  vec3_t<T> wo;
  vertex_response_t<T> response(const vec3_t<T>& wi) const { return {rgb(1), phase.eval(wo, wi)}; }
  T pdf(const vec3_t<T>& wi) const { return phase.eval(wo, wi); }
};

// One next event that found light: the light arriving and its density (the light sample's Le
// and pdf), the vertex's response, the shadow ray's transmittance and the MIS weight.
template <class T> struct next_event_t {
  rgb Le{0};
  T pdf = T(0);
  vertex_response_t<T> at;
  rgb tr{1};
  T w = T(1);
  // beta tr f Le s w / pdf: the estimate added to the path's radiance.
  rgb estimate(const rgb& beta) const { return beta * tr * at.f * Le * float(at.s * w / pdf); }
};

// Inlined by force (ZRAKA_FORCE_INLINE, vec.hpp): called, it cost the path loop 2% more
// instructions (cachegrind, pathtrace at its defaults); inlined, 0.8%.
// [listing next-event]
// The next event at `at`. The three numbers come from the bounce's fixed slots (path_kit.hpp), or,
// with bounce -1, next in the stream. shadow(light sample) -> rgb is the segment's transmittance
// (one ray counted here; media count their own). Empty when no light arrives.
template <class T, class Vertex, class Shadow>
ZRAKA_FORCE_INLINE std::optional<next_event_t<T>> next_event(const light_set_t<T>& lights, const hit_t<T>& at,
                                                             const Vertex& v, bool mis, int bounce, rng& g,
                                                             Shadow&& shadow, std::uint64_t& rays) {
  if (bounce >= 0) g.seek(path_number(bounce, path_slot::light_choice));
  const T u_select = T(g.uniform());
  if (bounce >= 0) g.seek(path_number(bounce, path_slot::light_point));
  const vec2_t<T> u(g.uniform2());
  const auto e = lights.sample(at, u_select, u);
  if (!e || e->Le == rgb(0)) return std::nullopt;
  next_event_t<T> n{e->Le, e->pdf, v.response(e->wi)};
  if (n.at.f == rgb(0)) return std::nullopt;  // the surface sends nothing on: no shadow ray
  ++rays;
  n.tr = shadow(*e);
  if (n.tr == rgb(0)) return std::nullopt;
  if (mis && !e->delta) n.w = power_heuristic(e->pdf, v.pdf(e->wi));
  return n;
}
// [end]

}  // namespace zraka

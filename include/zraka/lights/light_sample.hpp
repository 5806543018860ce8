#pragma once
// What sampling a light gives (book 2.2, 2.3, 6.2): the light arriving at a shading point
// (light_sample_t, next-event estimation), and light leaving a light (emission_sample_t, for the
// renderers that start paths at the lights: BDPT, photon mapping). Every light kind fills them:
// the light kinds of this folder (light.hpp), the shapes with a glowing material and the
// environment (scene/lights.hpp, which also sets the choice of the light).
#include <zraka/core/hit.hpp>
#include <zraka/core/vec.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/image/image.hpp>  // rgb

#include <optional>

namespace zraka {

template <class T> struct light_sample_t {
  vec3_t<T> point{T(0)};  // on the light
  vec3_t<T> wi{T(0)};     // unit, from the shading point towards it
  T pdf = T(0);           // per steradian (a point light: 1), times the choice of the light if chosen
  rgb Le{0};              // arriving from the light (0 from a one-sided light's back; point: I/d^2)
  bool delta = false;     // a point light: no other technique can find it
  segment_t<T> shadow;    // the light is seen if occluded(scene, shadow) is false
  int light = -1;         // index in the light set
};

// Light leaving a light: a point on it and a direction it leaves in. The position density is
// per unit area (times the choice of the light); the direction density is per steradian. A
// light at a point has a delta position (pdf_position is then the probability of choosing it).
template <class T> struct emission_sample_t {
  vec3_t<T> point{T(0)};
  vec3_t<T> normal{T(0)};     // unit outward normal at point; zero for a light at a point
  vec3_t<T> p_error{T(0)};    // bound on the error of point
  vec3_t<T> direction{T(0)};  // unit, leaving the light
  rgb Le{0};                  // radiance along direction (a light at a point: its intensity I)
  T pdf_position = T(0);      // per unit area, times the choice of the light
  T pdf_direction = T(0);     // per steradian
  bool delta_position = false;  // a light at a point
  int light = -1;
};

// The light at hit h from a light at point p that sends intensity I towards h: one direction,
// a delta whose "density" is reported as 1, Le = I / d^2 (the irradiance facing it, per
// steradian of that delta). None at the light itself or for a non-finite result.
template <class T>
std::optional<light_sample_t<T>> sample_light_at_point(const vec3_t<T>& p, const rgb& I, const hit_t<T>& h) {
  light_sample_t<T> s;
  const vec3_t<T> to = p - h.p;
  s.point = p;
  s.wi = normalize_or_zero(to);
  s.pdf = T(1);
  s.Le = I / float(length2(to));
  s.delta = true;
  s.shadow = spawn_segment(h, s.point);
  if (s.wi == vec3_t<T>(0) || !is_finite(s.Le)) return std::nullopt;
  return s;
}

}  // namespace zraka

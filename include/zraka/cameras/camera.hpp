#pragma once
// A camera that turns image-plane coordinates into primary rays. It looks from `position`
// towards `look_at`, with `up` roughly up and a vertical field of view `vfov_degrees`.
// With aperture > 0 it is a thin lens focused at `focus_distance` (depth of field).
// Image coordinates: s in [0,1] left to right, t in [0,1] top to bottom, as pixels are stored.
//
// The settings are plain members; prepare() computes the lens frame once, and the prepared
// camera's generate() makes rays:  auto cam = settings.prepare(); ray r = cam.generate(s, t);
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/ray.hpp>

#include <string>

namespace zraka {

template <class T> struct camera_t {
  vec3_t<T> position{T(0), T(0), T(0)};
  vec3_t<T> look_at{T(0), T(0), T(-1)};
  vec3_t<T> up{T(0), T(1), T(0)};
  T vfov_degrees = T(40);
  T aspect = T(1);          // width / height
  T aperture = T(0);        // lens diameter; 0 = pinhole
  T focus_distance = T(0);  // 0 = the distance to look_at

  struct prepared {
    vec3_t<T> origin, u, v, corner, horizontal, vertical;
    T lens_radius;

    // s, t: image-plane position; lens_u, lens_v in [0,1): where on the lens (thin lens only;
    // the default (0, 0) is the lens centre).
    ray_t<T> generate(T s, T t, T lens_u = T(0), T lens_v = T(0)) const {
      const vec3_t<T> target = corner + s * horizontal + t * vertical;
      vec3_t<T> o = origin;
      if (lens_radius > T(0)) {  // uniform point on the lens disk (sampling.hpp explains why sqrt)
        const T r = lens_radius * std::sqrt(lens_u);
        const T phi = T(2) * pi<T> * lens_v;
        o += r * std::cos(phi) * u + r * std::sin(phi) * v;
      }
      return {o, target - o};
    }
  };

  // Throws zraka::error for settings that define no camera (instead of making NaN rays).
  prepared prepare() const;
};

template <class T> typename camera_t<T>::prepared camera_t<T>::prepare() const {
  if (!(vfov_degrees > T(0) && vfov_degrees < T(180)))
    throw error("camera: vfov_degrees must be in (0, 180), got " + std::to_string(vfov_degrees));
  if (!(aspect > T(0)) || !std::isfinite(aspect))
    throw error("camera: aspect must be positive, got " + std::to_string(aspect));
  if (!(aperture >= T(0)) || !(focus_distance >= T(0)))
    throw error("camera: aperture and focus_distance must not be negative");
  const vec3_t<T> w = normalize_or_zero(position - look_at);  // the camera looks along -w
  const vec3_t<T> u = normalize_or_zero(glm::cross(up, w));
  if (w == vec3_t<T>(0) || u == vec3_t<T>(0))
    throw error("camera: position equals look_at, or up is parallel to the view direction");
  const vec3_t<T> v = glm::cross(w, u);
  const T focus = focus_distance > T(0) ? focus_distance : glm::length(look_at - position);
  const T half_h = std::tan(vfov_degrees * pi<T> / T(360)) * focus;
  const T half_w = aspect * half_h;
  const vec3_t<T> top_left = position - focus * w - half_w * u + half_h * v;
  return {position, u, v, top_left, T(2) * half_w * u, T(-2) * half_h * v, aperture / T(2)};
}

using camera = camera_t<double>;

ZRAKA_INSTANCE(struct camera_t<double>)  // compiled.hpp

}  // namespace zraka

#pragma once
// The pinhole camera as a "light" of importance (book 6.2), for renderers that connect paths
// to the camera (light tracing, bidirectional path tracing). A camera ray leaves the pinhole
// towards a point uniform on the image plane. Put that plane at distance 1 along the view
// direction, where it has area A; a direction w at angle theta to the view direction meets it
// at distance 1/cos(theta), so the ray's density per steradian is
//     p(w) = d^2 / (A cos theta) = 1 / (A cos^3 theta),
// and the importance We(w) = 1 / (A cos^4 theta) makes We cos theta / p = 1: a camera ray
// carries weight one, and the integral of We over the image (in solid angle, times cos theta)
// is one. Directions that miss the image have We = p = 0. A lens (aperture > 0) is not
// handled: importance() refuses it by name.
#include <zraka/cameras/camera.hpp>
#include <zraka/core/error.hpp>

#include <optional>

namespace zraka {

template <class T> struct camera_importance_t {
  vec3_t<T> origin, forward;     // the pinhole and the unit view direction
  vec3_t<T> corner, horizontal, vertical;  // the image plane as the prepared camera has it
  T focus = T(1);                // distance of that plane
  T area = T(1);                 // A: the image's area on the plane at distance 1

  explicit camera_importance_t(const typename camera_t<T>::prepared& c)
      : origin(c.origin), corner(c.corner), horizontal(c.horizontal), vertical(c.vertical) {
    if (c.lens_radius > T(0))
      throw error("camera importance: a thin lens (aperture > 0) is not supported; use a pinhole");
    const vec3_t<T> centre = corner + horizontal / T(2) + vertical / T(2) - origin;
    focus = glm::length(centre);
    forward = centre / focus;
    area = glm::length(horizontal) * glm::length(vertical) / (focus * focus);
  }

  // [listing camera-importance]
  // Where direction w from the pinhole meets the image: (s, t) in [0,1)^2 as generate() takes
  // them, or none when it misses.
  std::optional<vec2_t<T>> image_position(const vec3_t<T>& w) const {
    const T c = glm::dot(w, forward);
    if (!(c > T(0))) return std::nullopt;
    const vec3_t<T> q = origin + w * (focus / c) - corner;
    const T s = glm::dot(q, horizontal) / length2(horizontal);
    const T t = glm::dot(q, vertical) / length2(vertical);
    if (!(s >= T(0) && s < T(1) && t >= T(0) && t < T(1))) return std::nullopt;
    return vec2_t<T>(s, t);
  }
  // We(w) = 1 / (A cos^4 theta) on the image, 0 off it.
  T importance(const vec3_t<T>& w) const {
    if (!image_position(w)) return T(0);
    const T c = glm::dot(w, forward);
    return T(1) / (area * c * c * c * c);
  }
  // p(w) = 1 / (A cos^3 theta): the density per steradian of a camera ray's direction.
  T pdf_direction(const vec3_t<T>& w) const {
    if (!image_position(w)) return T(0);
    const T c = glm::dot(w, forward);
    return T(1) / (area * c * c * c);
  }
  // The cosine between w and the view direction (the camera's side of the geometry term).
  T cos_theta(const vec3_t<T>& w) const { return glm::dot(w, forward); }
  // [end]
};

}  // namespace zraka

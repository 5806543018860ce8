#pragma once
// A course's light (custom_light.hpp) as a light kind: the one kind whose physics is behind a
// virtual interface. A registered light type (scene_registry.hpp) makes one.
#include <zraka/core/hit.hpp>
#include <zraka/lights/custom_light.hpp>
#include <zraka/lights/light_sample.hpp>

#include <memory>
#include <optional>

namespace zraka::light_kinds {

struct custom {
  static constexpr const char* name = "custom";
  std::shared_ptr<const custom_light> light;  // never null (zraka::light's constructor checks)

  // As a point light's, with the intensity towards the shading point.
  template <class T> std::optional<light_sample_t<T>> sample(const hit_t<T>& h) const {
    const vec3 p = light->position();
    const vec3 towards = normalize_or_zero(vec3(h.p) - p);
    if (towards == vec3(0)) return std::nullopt;
    return sample_light_at_point(vec3_t<T>(p), light->intensity(towards), h);
  }
  double power() const { return light->power(); }
  template <class T> emission_sample_t<T> sample_emission(const vec2_t<T>& u_dir) const {
    emission_sample_t<T> e;
    e.point = vec3_t<T>(light->position());
    const vec3 w = light->sample_direction(vec2(u_dir));
    e.direction = vec3_t<T>(w);
    e.Le = light->intensity(w);
    e.pdf_direction = T(light->pdf_direction(w));
    e.delta_position = true;
    return e;
  }
  template <class T> T pdf_emission_direction(const vec3_t<T>& w) const { return T(light->pdf_direction(vec3(w))); }
  template <class T> rgb intensity_towards(const vec3_t<T>& w) const { return light->intensity(vec3(w)); }
};

}  // namespace zraka::light_kinds

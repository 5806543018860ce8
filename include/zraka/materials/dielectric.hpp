#pragma once
// Glass (book 1.8): reflect with probability R (exact Fresnel), else refract; total internal
// reflection. ior = n_inside / n_outside: 1.5 a glass ball in air, 1/1.5 an air bubble in glass.
// Of ior 1 it is an index-matched boundary (book 6.1, "boundary" in scene files): rays cross it
// unchanged; it marks where a medium (material_common::interior) begins.
#include <zraka/core/hit.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/materials/scatter.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct dielectric {
  static constexpr const char* name = "dielectric";
  static constexpr bool has_density = false;
  static constexpr bool is_specular = true;  // two directions, no density to evaluate
  double ior = 1.5;  // index inside (outside is 1)

  // The weight is 1 either way. The eta^2 change of radiance across the boundary is left out:
  // it cancels for every path that leaves the glass again, which is all of them in the course's
  // scenes. One number, for the choice between reflection and refraction.
  template <class T> std::optional<scatter_t<T>> scatter(const vec3_t<T>& d, const hit_t<T>& h, rng& g) const {
    const vec3_t<T> n = h.facing_normal();
    const T eta = relative_ior(h.front_face, T(ior));
    const T cos_i = -glm::dot(d, n);
    const auto t = refract(d, n, eta);  // none on total internal reflection
    if (t && T(g.uniform()) >= fresnel_dielectric(cos_i, eta)) return scatter_t<T>{*t, rgb(1), T(0), true};
    return scatter_t<T>{reflect(d, n), rgb(1), T(0), true};
  }
  // [listing whitted-glass]
  // Whitted (whitted.hpp): both rays, the reflected one weighted by the exact Fresnel R, the
  // refracted one by 1 - R (none on total internal reflection). About the shading normal,
  // unless a ray would cross the geometric surface: then about the geometric one.
  template <class W> rgb whitted(W& w) const {
    using T = typename W::scalar;
    const T eta = relative_ior(w.h.front_face, T(ior));
    vec3_t<T> n = w.ns;
    auto t = refract(w.d, n, eta);  // none on total internal reflection
    if (!w.outside(reflect(w.d, n)) || (t && w.outside(*t))) {
      n = w.ng;
      t = refract(w.d, n, eta);
    }
    const float R = t ? float(fresnel_dielectric(-glm::dot(w.d, n), eta)) : 1.0f;
    rgb c = w.trace(reflect(w.d, n), rgb(R));
    if (t) c += w.trace(*t, rgb(1.0f - R));
    return c;
  }
  // [end]

  static constexpr int gpu_kind = 2;  // KIND_DIELECTRIC
  template <class Packer> void pack(Packer& p) const { p.record.ior = float(ior); }

  // Light crosses it unchanged (media.hpp lets paths and shadow rays through) unless it glows.
  bool index_matched() const { return ior == 1.0; }

  // {type: dielectric, ior, medium}; the medium is a name in the media section.
  static std::vector<std::string> keys() { return {"ior", "medium"}; }
  template <class Node> static dielectric read(const Node& n, material_common& c) {
    dielectric k;
    if (n.has("ior")) {
      k.ior = n.number("ior");
      if (!(k.ior > 0)) n.fail("ior", "must be positive, got " + n.scalar("ior"));
    }
    if (n.has("medium")) c.interior = n.medium("medium");
    return k;
  }
  // {type: boundary, medium}: a dielectric of ior 1 around a medium, which is required.
  static std::vector<std::string> boundary_keys() { return {"medium"}; }
  template <class Node> static dielectric read_boundary(const Node& n, material_common& c) {
    c.interior = n.medium("medium");
    return dielectric{1.0};
  }
  template <class Writer> void write(Writer& w, const material_common& c) const {
    w.number("ior", ior);
    if (c.interior >= 0) w.medium("medium", c.interior);
  }
};

}  // namespace zraka::material_kinds

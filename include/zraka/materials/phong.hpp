#pragma once
// Phong's material (book 1.9): kd, ks and the shininess p. Whitted's tracer (whitted.hpp) shades
// it with the local model; a path tracer uses the energy-normalised BRDF of the same lobe,
// Lambert kd / pi plus (p+2)/(2 pi) ks (R.V)^p (bxdf.hpp): (V.R)^p itself is not a BRDF.
#include <zraka/core/hit.hpp>
#include <zraka/materials/bxdf.hpp>
#include <zraka/materials/scatter.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct phong {
  static constexpr const char* name = "phong";
  static constexpr bool has_density = true;
  static constexpr bool is_specular = false;
  rgb kd{0.8f}, ks{0.2f};
  double shininess = 32;  // the exponent p

  template <class T> lambert_phong_brdf_t<T> brdf(const hit_t<T>&) const {
    lambert_phong_brdf_t<T> f;
    f.diffuse.rho = vec3_t<T>(kd);
    f.glossy.rho_s = vec3_t<T>(ks);
    f.glossy.s = T(shininess);
    return f;
  }
  // Sampled as the mixture of the two lobes (bxdf.hpp reuses u for the lobe).
  template <class T>
  std::optional<scatter_t<T>> sample(const vec3_t<T>& d, const hit_t<T>& h, const vec2& u, double) const {
    const vec3_t<T> n = h.facing_normal();
    const auto sm = brdf(h).sample(-d, n, vec2_t<T>(u));
    if (!sm) return std::nullopt;  // sampled below the surface: absorbed
    return scatter_t<T>{sm->wi, rgb(sm->weight), sm->pdf, false};
  }
  template <class T> rgb f_cos(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const vec3_t<T> n = h.facing_normal();
    return rgb(brdf(h).eval(wi, wo, n) * std::max(T(0), glm::dot(n, wi)));
  }
  template <class T> T pdf(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    return brdf(h).pdf(wi, wo, h.facing_normal());
  }
  template <class T> local_model_terms local_model(const hit_t<T>&) const { return {kd, ks, shininess}; }
  template <class W> rgb whitted(W& w) const { return w.local(local_model(w.h)); }

  static constexpr int gpu_kind = 4;  // KIND_PHONG: kd and ks travel in the albedo's two colours
  template <class Packer> void pack(Packer& p) const {
    p.record.albedo_a = p.colour(kd);
    p.record.albedo_b = p.colour(ks);
    p.record.shininess = float(shininess);
  }

  static std::vector<std::string> keys() { return {"kd", "ks", "shininess"}; }
  template <class Node> static phong read(const Node& n, material_common&) {
    phong k;
    if (n.has("kd")) k.kd = n.colour("kd");
    if (n.has("ks")) k.ks = n.colour("ks");
    if (n.has("shininess")) {
      k.shininess = n.number("shininess");
      if (!(k.shininess > 0)) n.fail("shininess", "must be positive");
    }
    return k;
  }
  template <class Writer> void write(Writer& w, const material_common&) const {
    w.colour("kd", kd);
    w.colour("ks", ks);
    w.number("shininess", shininess);
  }
};

}  // namespace zraka::material_kinds

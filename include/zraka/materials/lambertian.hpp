#pragma once
// The diffuse surface (book 1.7, 2.3): rho / pi in every direction, sampled cosine-weighted
// (erratum C1), so that f cos / pdf is the albedo exactly. The albedo may be a texture.
// Every material kind is a file of this form; material.hpp lists the kinds, builtin.hpp
// registers them by name (README.md, "Adding a material").
#include <zraka/core/hit.hpp>
#include <zraka/materials/bxdf.hpp>
#include <zraka/materials/scatter.hpp>
#include <zraka/textures/texture.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::material_kinds {

struct lambertian {
  static constexpr const char* name = "lambertian";  // in scene files and messages
  static constexpr bool has_density = true;          // lights are sampled at it (brdf_cos, pdf)
  static constexpr bool is_specular = false;
  texture albedo = texture::solid(rgb(0.8f));

  // The BRDF at a hit as book 1.9's Lambert + Phong pair with no lobe (bxdf.hpp): evaluating
  // it so keeps brdf_cos() and scatter_pdf() the numbers phong's lobe-less twin gives.
  template <class T> lambert_phong_brdf_t<T> brdf(const hit_t<T>& h) const {
    lambert_phong_brdf_t<T> f;
    f.diffuse.rho = vec3_t<T>(evaluate(albedo, h.p, h.facing_normal(), h.uv));
    f.glossy.rho_s = vec3_t<T>(0);
    return f;
  }
  // u: the direction's two numbers (the third, for a lobe, is not used).
  template <class T>
  std::optional<scatter_t<T>> sample(const vec3_t<T>& d, const hit_t<T>& h, const vec2& u, double) const {
    const vec3_t<T> n = h.facing_normal();
    const lambert_brdf_t<T> f{vec3_t<T>(evaluate(albedo, h.p, n, h.uv))};
    const auto sm = f.sample(-d, n, vec2_t<T>(u));
    if (!sm) return std::nullopt;  // grazing: d along the surface, or rounding on the horizon
    return scatter_t<T>{sm->wi, rgb(sm->weight), sm->pdf, false};
  }
  template <class T> rgb f_cos(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    const vec3_t<T> n = h.facing_normal();
    return rgb(brdf(h).eval(wi, wo, n) * std::max(T(0), glm::dot(n, wi)));
  }
  template <class T> T pdf(const hit_t<T>& h, const vec3_t<T>& wo, const vec3_t<T>& wi) const {
    return brdf(h).pdf(wi, wo, h.facing_normal());
  }
  // Whitted (whitted.hpp) shades it with the local model: the albedo as kd, no highlight (the
  // exponent is phong's default; with ks 0 it multiplies nothing).
  template <class T> local_model_terms local_model(const hit_t<T>& h) const {
    return {evaluate(albedo, h.p, h.facing_normal(), h.uv), rgb(0), 32};
  }
  template <class W> rgb whitted(W& w) const { return w.local(local_model(w.h)); }

  // The OpenCL kernel (kernels/pathtrace.cl, KIND_LAMBERTIAN) reads its albedo; Packer is
  // gpu_scene.hpp's, which fills the packed record.
  static constexpr int gpu_kind = 0;
  template <class Packer> void pack(Packer& p) const { p.albedo(albedo); }

  // Scene file: {type: lambertian, albedo: colour or texture} (scenes/README.md). Node is the
  // scene file's scene_node (io/scene_file.hpp), Writer its resolved-scene or export writer.
  static std::vector<std::string> keys() { return {"albedo"}; }
  template <class Node> static lambertian read(const Node& n, material_common&) {
    lambertian k;
    if (n.has("albedo")) k.albedo = n.texture("albedo");
    return k;
  }
  template <class Writer> void write(Writer& w, const material_common&) const { w.texture("albedo", albedo); }
};

}  // namespace zraka::material_kinds

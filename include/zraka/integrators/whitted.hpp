#pragma once
// The Whitted ray tracer (book 2.2; the thesis's Listing 2.2 corrected per erratum B10). A ray
// from the camera finds the *nearest* hit; there the colour is
//   local light   (Phong or Blinn-Phong, one shadow ray per point light and per area light),
// + ks  x  the colour seen in the mirror direction          (phong surfaces, Whitted's k_s),
// + the colour seen in the mirror direction                 (metal; fuzz > 0 samples a direction),
// + R x reflected + (1 - R) x refracted colour              (glass: exact Fresnel R; R = 1 on
//                                                            total internal reflection),
// and each of those colours is the same computation one level deeper: a tree of rays. The
// recursion stops at max_depth (black: nothing more is known there), where a branch's weight
// falls below min_weight (Whitted 1980's adaptive depth), or when a ray leaves the scene
// (the background colour, or the environment map when the scene has one: seen along rays, it
// does not light diffuse surfaces here, which would need an integral over it).
//
// Local light uses the normalised Phong (or Blinn-Phong) lobe of bxdf.hpp, so a Whitted image
// and a path-traced one agree on direct light; with point lights it is exact, with area lights
// each sample takes one random point per light (soft shadows; spp > 1 averages them). Whitted
// tracing has no diffuse inter-reflection (erratum C2): light that bounces off a wall onto
// another wall is left out, which is what `ambient` crudely stands in for.
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/image/image.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/materials/bxdf.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/materials/optics.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/render_it_with.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <cstdint>
#include <optional>
#include <type_traits>
#include <variant>

namespace zraka {

enum class local_model { phong, blinn_phong };

struct whitted_options {
  int max_depth = 8;          // levels of the ray tree below the camera ray
  float min_weight = 1e-3f;   // skip branches that would add less than this fraction
  local_model model = local_model::phong;
};

// The local model's kd, ks and exponent at a hit, for the kinds that have one (a kind's
// local_model(): lambertian and phong); none for the others.
template <class T> std::optional<local_model_terms> local_terms(const material& m, const hit_t<T>& h) {
  return std::visit([&](const auto& k) -> std::optional<local_model_terms> {
    if constexpr (requires { k.local_model(h); }) return k.local_model(h);
    else return std::nullopt;
  }, m.kind);
}

// A call to a callable that lives on the caller's stack (a lambda), without copying it.
template <class R, class... A> class call_ref {
 public:
  template <class F> call_ref(F& f) : obj_(&f), call_([](void* o, A... a) -> R { return (*static_cast<F*>(o))(a...); }) {}
  R operator()(A... a) const { return call_(obj_, a...); }

 private:
  void* obj_;
  R (*call_)(void*, A...);
};

// [listing whitted-vertex]
// What a material kind's whitted() (materials/) is given at a hit: the ray's direction, the hit,
// its geometric and shading normals on the ray's side, and the tracer's three ways to shade:
// the local model with shadow rays (local), a branch of the ray tree (trace), the light the
// surface gives off (emitted). A kind without whitted() is refused by check_whitted_scene.
template <class T> struct whitted_vertex {
  using scalar = T;
  vec3_t<T> d;         // the incoming ray's direction
  const hit_t<T>& h;
  vec3_t<T> ng, ns;    // facing geometric and shading normals
  vec3_t<T> shading_normal;  // the shading normal as the hit has it (not turned to the ray)
  rng& g;
  call_ref<rgb, const vec3_t<T>&, rgb> trace;
  call_ref<rgb, const local_model_terms&> local;
  rgb light;  // emitted(m, h)

  bool outside(const vec3_t<T>& w) const { return glm::dot(w, ng) > T(0); }  // above the surface
  hit_t<T> shading_hit() const {  // the hit with the shading normal (smooth on meshes)
    hit_t<T> hs = h;
    hs.normal = shading_normal;
    return hs;
  }
  rgb emitted() const { return light; }
};
// [end]

// Does Whitted's tracer shade kind K?
template <class K> constexpr bool whitted_shades =
    requires(const K& k, whitted_vertex<double>& w) { k.whitted(w); };

// [listing local-shade]
// f cos(theta_i) for light arriving from wi: Lambert kd/pi plus the normalised specular lobe,
// (p+2)/(2 pi) (R.V)^p for Phong or (p+8)/(8 pi) (N.H)^p for Blinn-Phong, both times N.L.
template <class T>
rgb local_brdf_cos(const material& m, const hit_t<T>& h, const vec3_t<T>& n, const vec3_t<T>& wo,
                   const vec3_t<T>& wi, local_model model) {
  const auto lm = local_terms(m, h);
  if (!lm) return rgb(0);
  const T p = T(lm->shininess);
  const shading_terms_t<T> k = model == local_model::phong ? phong_terms(n, wi, wo, p)
                                                           : blinn_phong_terms(n, wi, wo, p);
  if (!(glm::dot(n, wo) > T(0))) return rgb(0);  // seen from below the shading normal
  const T norm = model == local_model::phong ? (p + T(2)) / (T(2) * pi<T>) : (p + T(8)) / (T(8) * pi<T>);
  return lm->kd * float(k.diffuse / pi<T>) + lm->ks * float(norm * k.specular * k.diffuse);
}
// [end]

// [listing direct-light]
// Light arriving at a diffuse hit straight from the lights (lights.hpp), one shadow ray each:
// a point light of intensity I at distance d gives irradiance I cos / d^2; an area light is
// sampled at one point, its radiance weighted by 1 / pdf.
template <class T>
rgb direct_light(const scene_t<T>& sc, const light_set_t<T>& lights, const scene_hit_t<T>& sh,
                 const vec3_t<T>& wo, rng& g, const whitted_options& opt, std::uint64_t& rays) {
  const material& m = sc.materials[std::size_t(sh.material)];
  const vec3_t<T> n = sh.facing_shading_normal();
  const vec3_t<T> ng = sh.h.facing_normal();
  rgb L(0);
  for (int k = 0; k < int(lights.size()); ++k) {  // every light, not one chosen at random
    if (lights.is_environment(k)) continue;  // the sky is Whitted's background, seen by rays only
    const vec2_t<T> u(g.uniform2());
    const auto ls = lights.sample_one(k, sh.h, u);
    if (!ls || ls->Le == rgb(0) || !(glm::dot(ls->wi, ng) > T(0))) continue;  // behind the surface
    const rgb f = local_brdf_cos(m, sh.h, n, wo, ls->wi, opt.model);
    if (f == rgb(0)) continue;
    ++rays;
    if (!occluded(sc, ls->shadow)) L += f * ls->Le / float(ls->pdf);
  }
  return L;
}
// [end]

// [listing whitted]
// The colour seen along r; depth counts the bounces above it, weight what its colour is
// multiplied by at the camera.
template <class T>
rgb whitted_radiance(const scene_t<T>& sc, const light_set_t<T>& lights, const ray_t<T>& r, rng& g,
                     const whitted_options& opt, std::uint64_t& rays, int depth = 0, float weight = 1.0f) {
  scene_hit_t<T> sh;
  ++rays;
  if (!nearest_hit(sc, r, sh))  // the nearest, not the first in the list
    return sc.environment ? sc.environment->radiance(r.direction) : sc.background;
  const material& m = sc.materials[std::size_t(sh.material)];
  const hit_t<T>& h = sh.h;
  const vec3_t<T> wo = -r.direction;
  // A secondary ray, if the tree may grow and the branch still matters.
  auto trace = [&](const vec3_t<T>& dir, rgb w) {
    const float bw = weight * max_component(w);
    if (depth >= opt.max_depth || !(bw >= opt.min_weight)) return rgb(0);
    return w * whitted_radiance(sc, lights, spawn_ray(h, dir), g, opt, rays, depth + 1, bw);
  };
  // Lambert and Phong: the local model, and for Phong the mirror ray weighted by ks.
  auto local = [&](const local_model_terms& lm) {
    rgb c = emitted(m, h) + direct_light(sc, lights, sh, wo, g, opt, rays) + sc.ambient * lm.kd;
    if (lm.ks != rgb(0)) {
      const vec3_t<T> ng = h.facing_normal(), w = reflect(r.direction, sh.facing_shading_normal());
      c += trace(glm::dot(w, ng) > T(0) ? w : reflect(r.direction, ng), lm.ks);
    }
    return c;
  };
  // Directions bend around the shading normal (smooth on meshes); one that would cross the
  // geometric surface (possible where the two normals differ) falls back to the geometric one.
  whitted_vertex<T> w{r.direction, h, h.facing_normal(), sh.facing_shading_normal(), sh.shading_normal, g, trace, local,
                      emitted(m, h)};
  return std::visit([&](const auto& k) {  // the kind's whitted() (materials/)
    if constexpr (whitted_shades<std::decay_t<decltype(k)>>) return k.whitted(w);
    else return rgb(0);  // refused by check_whitted_scene
  }, m.kind);
}
// [end]

// Whitted's local model knows the built-in materials only: a custom BSDF or a microfacet
// material used by an object is refused by name rather than drawn as something else.
template <class T> void check_whitted_scene(const scene_t<T>& sc) {
  if (!sc.media.empty())
    throw error("whitted: the scene has participating media (" + sc.media_names() +
                "), which the Whitted ray tracer cannot render; " + render_it_with(sc));
  for_each_object(sc, [&](object_ref o) {
    const material& m = sc.material_of(o);
    if (is_custom(m))
      throw error("whitted: " + sc.material_label(sc.material_index(o)) + " is a custom BSDF ('" +
                  m.get<material_kinds::custom>()->bsdf->name() + "'), which the Whitted ray tracer cannot shade; " + render_it_with(sc));
    // A glossy lobe is neither a mirror (one ray) nor a local model (a highlight per light):
    // it needs the integral over directions that path tracing estimates.
    if (is_microfacet(m))
      throw error("whitted: " + sc.material_label(sc.material_index(o)) + " is a " + kind_name(m.kind) +
                  ", a rough microfacet surface, which the Whitted ray tracer cannot shade; " + render_it_with(sc));
    const bool shades = std::visit([](const auto& k) { return whitted_shades<std::decay_t<decltype(k)>>; }, m.kind);
    if (!shades)  // a kind without whitted() (materials/)
      throw error("whitted: " + sc.material_label(sc.material_index(o)) + " is a " + kind_name(m.kind) +
                  ", which the Whitted ray tracer cannot shade; " + render_it_with(sc));
  });
}

// [listing render-whitted]
// The whole image on all cores (render.hpp): spp stratified samples per pixel (one sample: the
// pixel centre), each with its own random stream, so the image is the same for any thread count.
template <class T>
render_stats render_whitted(const scene_t<T>& sc, image& img, const whitted_options& opt,
                            const render_options& ro = {}) {
  if (img.width != sc.settings.width || img.height != sc.settings.height)
    throw error("render_whitted: the image size differs from the scene's settings");
  check_whitted_scene(sc);
  const light_set_t<T> lights(sc);
  const auto cam = sc.prepared_camera();
  return render(img, sc.settings.spp, sc.settings.seed, [&](sample_context& c) {
    const vec2 o = c.spp == 1 ? vec2(0.5) : pixel_sample(pixel_pattern::stratified, c.sample, c.spp, c.random);
    const vec2 lens = sc.camera.aperture > 0 ? c.random.uniform2() : vec2(0);
    const ray_t<T> r = cam.generate(T((c.x + o.x) / img.width), T((c.y + o.y) / img.height), T(lens.x), T(lens.y));
    return whitted_radiance(sc, lights, r, c.random, opt, c.rays);
  }, ro);
}
// [end]

}  // namespace zraka

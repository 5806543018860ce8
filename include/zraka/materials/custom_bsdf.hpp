#pragma once
// A user-defined BSDF (book 2.3, book/assignments/03-material): the extension point that lets
// an instructor or a student add a material without editing material.hpp. Derive from
// custom_bsdf, put it in a material with material::custom(std::make_shared<my_bsdf>(...)),
// and scatter(), brdf_cos() and scatter_pdf() call it, so the path tracer (path.hpp; naive, nee
// and mis) renders it unchanged. Whitted's local model and the OpenCL kernel cannot run it:
// they refuse the scene, naming the material.
//
// A BSDF sees the hit through a bsdf_frame: the point, the surface coordinates uv, and an
// orthonormal shading frame (s, t, n) with n on the side of wo. wo points from the surface
// towards the viewer, wi away from the surface; all unit vectors, world space. A virtual
// function cannot be a template, so the interface is in double; the material functions convert
// from and to the scalar T of the renderer.
#include <zraka/core/onb.hpp>
#include <zraka/core/vec.hpp>

#include <optional>
#include <string>

namespace zraka {

struct bsdf_frame {
  vec3 p{0};             // the hit point
  vec2 uv{0};            // the shape's surface coordinates there (hit_t::uv)
  vec3 s{1, 0, 0}, t{0, 1, 0}, n{0, 0, 1};  // shading frame, n unit on the side of wo
  bool front_face = true;  // the ray came from the outside of the shape

  vec3 to_local(const vec3& w) const { return {glm::dot(w, s), glm::dot(w, t), glm::dot(w, n)}; }
  vec3 to_world(const vec3& v) const { return v.x * s + v.y * t + v.z * n; }
  static bsdf_frame around(const vec3& p, const vec2& uv, const vec3& n, bool front_face) {
    const onb b(n);
    return {p, uv, b.t, b.b, b.n, front_face};
  }
};

// Colours are vec3 (r, g, b) in double here, not rgb: a value the renderer multiplies by a
// cosine is then rounded to float once, as the built-in materials do.
struct custom_sample {
  vec3 wi;      // unit, away from the surface
  vec3 weight;  // f(wo, wi) |cos theta_i| / pdf per channel: what the throughput is multiplied by
  double pdf;   // per steradian, > 0
};

struct custom_bsdf {
  virtual ~custom_bsdf() = default;
  // The name used in messages ("oren_nayar").
  virtual std::string name() const { return "custom"; }
  // f(wo, wi) in 1/sr, per channel.
  virtual vec3 eval(const bsdf_frame& f, const vec3& wo, const vec3& wi) const = 0;
  // A direction wi with density pdf(f, wo, wi), from three uniform numbers in [0,1): u.x and u.y
  // for the direction, u.z to choose a lobe if the BSDF has several. None when the sample is
  // lost (e.g. below the surface): the path is then absorbed.
  virtual std::optional<custom_sample> sample(const bsdf_frame& f, const vec3& wo, const vec3& u) const = 0;
  // The density sample() draws wi with, per steradian (used by multiple importance sampling).
  virtual double pdf(const bsdf_frame& f, const vec3& wo, const vec3& wi) const = 0;
};

}  // namespace zraka

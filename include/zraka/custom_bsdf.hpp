#pragma once
// A user-defined BSDF (book/assignments/03-material): the extension point that lets an
// instructor or a student add a material without editing material.hpp. Derive from
// custom_bsdf, put it in a material with material::custom(std::make_shared<my_bsdf>(...)),
// and scatter(), brdf_cos() and scatter_pdf() call it, so every path tracer that goes through
// them (path.hpp; naive, nee and mis in integrators.hpp) renders it unchanged.
//
// The same conventions as bxdf.hpp: n is the unit normal on the side of wo (facing_normal()),
// wo points from the surface towards the viewer, wi away from the surface; all unit vectors.
// A virtual function cannot be a template, so the interface is in double; the material
// functions convert from and to the scalar T of the renderer.
#include <zraka/vec.hpp>

#include <optional>

namespace zraka {

// Colours are vec3 (r, g, b) in double here, not rgb: a value the renderer multiplies by a
// cosine is then rounded to float once, as the built-in materials do.
struct custom_sample {
  vec3 wi;      // unit, away from the surface
  vec3 weight;  // f(wo, wi) |cos theta_i| / pdf per channel: what the throughput is multiplied by
  double pdf;   // per steradian, > 0
};

struct custom_bsdf {
  virtual ~custom_bsdf() = default;
  // f(wo, wi) in 1/sr, per channel; zero for wi below the surface (a BRDF only reflects).
  virtual vec3 eval(const vec3& wo, const vec3& wi, const vec3& n) const = 0;
  // A direction wi with density pdf(wo, wi, n), from two uniform numbers u in [0,1)^2; none
  // when the sample is lost (e.g. below the surface): the path is then absorbed.
  virtual std::optional<custom_sample> sample(const vec3& wo, const vec3& n, const vec2& u) const = 0;
  // The density sample() draws wi with, per steradian (used by multiple importance sampling).
  virtual double pdf(const vec3& wo, const vec3& wi, const vec3& n) const = 0;
};

}  // namespace zraka

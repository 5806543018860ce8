#pragma once
// A course's own light (book 2.3, book/assignments: a spot light): the extension point that
// lets an instructor or a student add a light kind without editing the library. Derive from
// custom_light, register its type in a scene_registry (add_light, returning
// light(light_kinds::custom{std::make_shared<my_light>(...)})), and every CPU renderer samples
// it through scene/lights.hpp: Whitted, the path tracers, BDPT, photon mapping, Metropolis. The
// OpenCL kernel cannot run C++ code: it refuses the scene, naming the type.
//
// A light that is not a shape sits at a point and is never hit by a ray: it is found only by
// sampling it (a delta in position, as the point light). It sends radiant intensity I(w)
// (W/sr, per channel) along each unit direction w; a point at distance d, facing it, receives
// the irradiance I(w) / d^2. An area light is a shape with a glowing material instead.
// A virtual function cannot be a template: the interface is in double, as custom_bsdf's.
#include <zraka/core/vec.hpp>
#include <zraka/image/image.hpp>  // rgb
#include <zraka/sampling/sampling.hpp>

#include <string>

namespace zraka {

struct custom_light {
  virtual ~custom_light() = default;
  // The type's name in messages ("spot").
  virtual std::string name() const = 0;
  virtual vec3 position() const = 0;
  // Radiant intensity leaving along unit w, per channel: finite and not negative.
  virtual rgb intensity(const vec3& w) const = 0;
  // Emitted flux (the integral of I over the sphere of directions), the mean over the channels:
  // the light set chooses lights in proportion to it.
  virtual double power() const = 0;
  // Emission sampling (BDPT and photon mapping start paths at the lights): a direction leaving
  // the light from two uniform numbers, and its density per steradian, which pdf_direction()
  // must return for the same w. Uniform over the sphere unless overridden: right for any I(w),
  // but a narrow spot then wastes most of its photons.
  virtual vec3 sample_direction(const vec2& u) const { return sample_uniform_sphere(u); }
  virtual double pdf_direction(const vec3&) const { return uniform_sphere_pdf<double>(); }
};

}  // namespace zraka

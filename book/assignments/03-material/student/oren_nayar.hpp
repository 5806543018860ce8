#pragma once
// Assignment 03: the Oren–Nayar rough diffuse BRDF (its "qualitative" form) as a
// zraka::custom_bsdf. Fill in eval, pdf and sample; see README.md.
//
//   f(wo, wi) = rho/pi (A + B max(0, cos(phi_i - phi_o)) sin(alpha) tan(beta))
//   A = 1 - sigma^2 / (2 (sigma^2 + 0.33)),  B = 0.45 sigma^2 / (sigma^2 + 0.09)
//   alpha = max(theta_i, theta_o),  beta = min(theta_i, theta_o)
// sigma is the standard deviation of the facet slopes in radians; sigma = 0 is Lambert.
#include <zraka/core/onb.hpp>
#include <zraka/materials/custom_bsdf.hpp>
#include <zraka/sampling/sampling.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace course {

struct oren_nayar final : zraka::custom_bsdf {
  zraka::vec3 rho{0.5};  // reflectance of the facets (the albedo at sigma = 0)
  double sigma = 0;      // roughness, radians

  oren_nayar(zraka::vec3 rho_, double sigma_) : rho(rho_), sigma(sigma_) {}

  std::string name() const override { return "oren_nayar"; }

  // f(wo, wi) per channel, in 1/sr; zero unless both wo and wi are above the surface.
  // The shading frame f gives the normal n = f.n (on the side of wo).
  zraka::vec3 eval(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const zraka::vec3& n = f.n;
    (void)wo, (void)wi, (void)n;
    return zraka::vec3(0);  // TODO
  }

  // The density sample() draws wi with, per steradian.
  double pdf(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const zraka::vec3& n = f.n;
    (void)wo, (void)wi, (void)n;
    return 0;  // TODO
  }

  // A direction wi, its weight f cos / pdf and its pdf; none when wo is below the surface.
  std::optional<zraka::custom_sample> sample(const zraka::bsdf_frame& f, const zraka::vec3& wo,
                                             const zraka::vec3& u) const override {
    const zraka::vec3& n = f.n;
    (void)wo, (void)u;
    return zraka::custom_sample{n, zraka::vec3(0), 0};  // TODO
  }
};

}  // namespace course

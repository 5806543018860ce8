#pragma once
// Assignment 03, reference solution: the Oren–Nayar rough diffuse BRDF (its "qualitative" form)
// as a zraka::custom_bsdf, sampled like Lambert (cosine-weighted).
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

  // The shading frame f gives the normal n = f.n (on the side of wo).
  zraka::vec3 eval(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const zraka::vec3& n = f.n;
    const double cos_i = glm::dot(wi, n), cos_o = glm::dot(wo, n);
    if (!(cos_i > 0) || !(cos_o > 0)) return zraka::vec3(0);  // a BRDF reflects only
    const double s2 = sigma * sigma;
    const double A = 1 - s2 / (2 * (s2 + 0.33)), B = 0.45 * s2 / (s2 + 0.09);
    // sin(alpha) tan(beta) without angles: alpha is the angle with the smaller cosine, beta the
    // larger, so it is sin_small_cos * sin_large_cos / large_cos, and large_cos >= cos_i > 0.
    const double sin_i = std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
    const double sin_o = std::sqrt(std::max(0.0, 1 - cos_o * cos_o));
    const double sin_a_tan_b = cos_i < cos_o ? sin_i * sin_o / cos_o : sin_o * sin_i / cos_i;
    // cos(phi_i - phi_o) from the tangent parts of wi and wo; zero when either is the normal.
    const zraka::vec3 ti = wi - cos_i * n, to = wo - cos_o * n;
    const double len = std::sqrt(glm::dot(ti, ti) * glm::dot(to, to));
    const double cos_phi = len > 0 ? std::clamp(glm::dot(ti, to) / len, -1.0, 1.0) : 0.0;
    return rho / zraka::pi<double> * (A + B * std::max(0.0, cos_phi) * sin_a_tan_b);
  }

  double pdf(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const zraka::vec3& n = f.n;
    if (!(glm::dot(wo, n) > 0)) return 0;
    return std::max(0.0, glm::dot(wi, n)) / zraka::pi<double>;
  }

  std::optional<zraka::custom_sample> sample(const zraka::bsdf_frame& f, const zraka::vec3& wo,
                                             const zraka::vec3& u) const override {
    const zraka::vec3& n = f.n;
    if (!(glm::dot(wo, n) > 0)) return std::nullopt;
    const zraka::vec3 wi = f.to_world(zraka::sample_cosine_hemisphere(zraka::vec2(u)));
    const double p = pdf(f, wo, wi);
    if (!(p > 0)) return std::nullopt;  // rounding put wi on the horizon
    // f cos / pdf = f cos / (cos / pi) = pi f: the cosine cancels exactly.
    return zraka::custom_sample{wi, zraka::pi<double> * eval(f, wo, wi), p};
  }
};

}  // namespace course

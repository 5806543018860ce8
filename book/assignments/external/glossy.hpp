#pragma once
// A glossy material zraka does not have, as a zraka::custom_bsdf (custom_bsdf.hpp): Lambert plus
// a lobe of half vectors,
//     f = kd / pi + ks D(h) / (4 (wo.h) max(cos_i, cos_o)),   D(h) = (s + 1)/(2 pi) cos^s(theta_h),
// h = (wo + wi)/|wo + wi|. D integrates to 1 over the hemisphere of h, and the max() in the
// denominator (Neumann, Neumann and Szirmay-Kalos 1999) keeps the lobe's albedo at or below ks
// for every wo, so kd + ks <= 1 conserves energy; f is symmetric in wo and wi. At normal incidence
// the albedo is exactly kd + ks A(s), A(s) = 2 (s+1)(1 - c^(s+3))/(s+3) - (1 - c^(s+1)),
// c = 1/sqrt(2) (the lobe's part whose mirror direction stays above the surface).
// Sampling: u.z chooses the lobe (diffuse with probability P_d, from kd and ks); the diffuse lobe
// is cosine-weighted, the glossy one draws h from D (cos theta_h = u^(1/(s+1))) and mirrors wo
// about it, so pdf(wi) = P_d cos_i / pi + (1 - P_d) D(h) / (4 wo.h).
#include <zraka/core/error.hpp>
#include <zraka/materials/custom_bsdf.hpp>
#include <zraka/sampling/sampling.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

namespace mycourse {

class glossy final : public zraka::custom_bsdf {
 public:
  glossy(const zraka::vec3& kd, const zraka::vec3& ks, double exponent) : kd_(kd), ks_(ks), s_(exponent) {
    if (!(s_ >= 0) || !std::isfinite(s_)) throw zraka::error("glossy: the exponent must be finite and >= 0");
    for (int i = 0; i < 3; ++i)
      if (!(kd[i] >= 0 && ks[i] >= 0 && kd[i] + ks[i] <= 1))
        throw zraka::error("glossy: kd and ks must not be negative and kd + ks must not exceed 1 (energy)");
    const double d = std::max({kd.x, kd.y, kd.z}), g = std::max({ks.x, ks.y, ks.z});
    p_diffuse_ = d + g > 0 ? d / (d + g) : 1.0;
  }

  std::string name() const override { return "glossy"; }

  // The albedo at normal incidence, in closed form (see the top of the file).
  zraka::vec3 normal_albedo() const {
    const double c = std::sqrt(0.5);
    const double a = 2 * (s_ + 1) * (1 - std::pow(c, s_ + 3)) / (s_ + 3) - (1 - std::pow(c, s_ + 1));
    return kd_ + ks_ * a;
  }

  zraka::vec3 eval(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const zraka::vec3 o = f.to_local(wo), i = f.to_local(wi);
    if (!(o.z > 0 && i.z > 0)) return zraka::vec3(0);  // a BRDF: both above the surface
    return kd_ / zraka::pi<double> + ks_ * lobe(o, i);
  }

  std::optional<zraka::custom_sample> sample(const zraka::bsdf_frame& f, const zraka::vec3& wo,
                                             const zraka::vec3& u) const override {
    const zraka::vec3 o = f.to_local(wo);
    if (!(o.z > 0)) return std::nullopt;
    zraka::vec3 i;
    if (u.z < p_diffuse_) {
      i = zraka::sample_cosine_hemisphere(zraka::vec2(u.x, u.y));
    } else {
      const double cos_h = std::pow(u.x, 1 / (s_ + 1)), sin_h = std::sqrt(std::max(0.0, 1 - cos_h * cos_h));
      const double phi = 2 * zraka::pi<double> * u.y;
      const zraka::vec3 h(sin_h * std::cos(phi), sin_h * std::sin(phi), cos_h);
      i = 2 * glm::dot(o, h) * h - o;  // wo mirrored about h
    }
    if (!(i.z > 0)) return std::nullopt;  // below the surface: absorbed
    const zraka::vec3 wi = f.to_world(i);
    const double p = pdf_local(o, i);
    if (!(p > 0) || !std::isfinite(p)) return std::nullopt;
    return zraka::custom_sample{wi, (kd_ / zraka::pi<double> + ks_ * lobe(o, i)) * (i.z / p), p};
  }

  double pdf(const zraka::bsdf_frame& f, const zraka::vec3& wo, const zraka::vec3& wi) const override {
    const zraka::vec3 o = f.to_local(wo), i = f.to_local(wi);
    if (!(o.z > 0 && i.z > 0)) return 0;
    return pdf_local(o, i);
  }

 private:
  zraka::vec3 kd_, ks_;
  double s_;
  double p_diffuse_ = 1;

  // D(h) of the half vector of o and i (both above the surface; h is then too).
  double D(const zraka::vec3& h) const { return (s_ + 1) / (2 * zraka::pi<double>) * std::pow(std::max(0.0, h.z), s_); }
  double lobe(const zraka::vec3& o, const zraka::vec3& i) const {
    const zraka::vec3 h = zraka::normalize_or_zero(o + i);
    const double oh = glm::dot(o, h);
    if (!(oh > 0)) return 0;
    return D(h) / (4 * oh * std::max(o.z, i.z));
  }
  double pdf_local(const zraka::vec3& o, const zraka::vec3& i) const {
    const zraka::vec3 h = zraka::normalize_or_zero(o + i);
    const double oh = glm::dot(o, h);
    const double glossy_pdf = oh > 0 ? D(h) / (4 * oh) : 0;
    return p_diffuse_ * i.z / zraka::pi<double> + (1 - p_diffuse_) * glossy_pdf;
  }
};

}  // namespace mycourse

#pragma once
// Sampling (book 1.6, 1.7 and 5.3): turn uniform numbers u in [0,1)^2 (from rng.hpp) into points or
// directions with a known density, and give that density beside each sampler, so that a Monte
// Carlo estimator can divide by it. Directions are sampled in a local frame around +z; onb.hpp
// turns them around a normal:
//
//     zraka::rng g(seed, pixel, sample);
//     const zraka::onb frame(n);
//     const zraka::vec3 wi = frame.to_world(zraka::sample_cosine_hemisphere(g.uniform2()));
//     const double p = zraka::cosine_hemisphere_pdf(frame.to_local(wi));   // = cos(theta)/pi
//
// Densities of directions are per steradian, of points per unit area (or length, in 1D).
// The world-frame distributions at the end (cosine_hemisphere_t, cone_t, mixture_t, ...) share
// one interface, sample(u) -> direction and pdf(direction), so they can be mixed.
#include <zraka/core/onb.hpp>

#include <limits>

namespace zraka {

// The largest T below one: samplers clamp u to it, so that u = 1 (e.g. a double just below one
// rounded to float) cannot produce a direction on the horizon or a point on the far edge.
template <class T> constexpr T one_minus_epsilon = T(1) - std::numeric_limits<T>::epsilon() / 2;

template <class T> T clamp_unit(T u) { return std::clamp(u, T(0), one_minus_epsilon<T>); }

// ---------------------------------------------------------------- 1D: the linear pdf of book 1.6
// p(r) = r/2 on [0,2]; CDF(r) = r^2/4, inverted: r = 2 sqrt(u).
// [listing linear-pdf]
template <class T> T sample_linear(T u) { return T(2) * std::sqrt(clamp_unit(u)); }
template <class T> T linear_pdf(T r) { return (r >= T(0) && r <= T(2)) ? r / T(2) : T(0); }
// [end]

// ---------------------------------------------------------------- the unit disk
// Shirley and Chiu's concentric map: squares around the centre of [-1,1]^2 go to circles, so
// neighbouring u stay neighbours and strata keep their shape (the polar map r = sqrt(u0) would
// squeeze them). Uniform: pdf = 1/pi per unit area.
template <class T> vec2_t<T> sample_disk_concentric(const vec2_t<T>& u) {
  const T a = T(2) * clamp_unit(u.x) - T(1), b = T(2) * clamp_unit(u.y) - T(1);
  if (a == T(0) && b == T(0)) return {T(0), T(0)};
  T r, phi;
  if (std::abs(a) > std::abs(b)) {
    r = a;
    phi = (pi<T> / T(4)) * (b / a);
  } else {
    r = b;
    phi = pi<T> / T(2) - (pi<T> / T(4)) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}
template <class T> T disk_pdf(const vec2_t<T>& p) {
  return glm::dot(p, p) <= T(1) ? T(1) / pi<T> : T(0);
}

// ---------------------------------------------------------------- the unit sphere and ball
// z uniform in (-1,1] gives equal areas (Archimedes); 1 - z^2 = 4u(1-u) avoids cancellation.
template <class T> vec3_t<T> sample_uniform_sphere(const vec2_t<T>& u) {
  const T u0 = clamp_unit(u.x), z = T(1) - T(2) * u0;
  const T s = T(2) * std::sqrt(u0 * (T(1) - u0));
  const T phi = T(2) * pi<T> * clamp_unit(u.y);
  return {s * std::cos(phi), s * std::sin(phi), z};
}
template <class T> T uniform_sphere_pdf() { return T(1) / (T(4) * pi<T>); }

// A point uniform in the unit ball (the "random in unit sphere" of fuzzy_mirror, optics.hpp):
// direction uniform, radius with CDF r^3. pdf = 3/(4 pi) per unit volume.
template <class T> vec3_t<T> sample_unit_ball(const vec3_t<T>& u) {
  return std::cbrt(clamp_unit(u.z)) * sample_uniform_sphere(vec2_t<T>(u.x, u.y));
}
template <class T> T unit_ball_pdf(const vec3_t<T>& p) {
  return length2(p) <= T(1) ? T(3) / (T(4) * pi<T>) : T(0);
}

// ---------------------------------------------------------------- hemispheres around +z
// Uniform: z uniform in (0,1]. pdf = 1/(2 pi) above the horizon.
template <class T> vec3_t<T> sample_uniform_hemisphere(const vec2_t<T>& u) {
  const T u0 = clamp_unit(u.x), z = T(1) - u0;
  const T s = std::sqrt(u0 * (T(2) - u0));  // sqrt(1 - z^2) without cancellation
  const T phi = T(2) * pi<T> * clamp_unit(u.y);
  return {s * std::cos(phi), s * std::sin(phi), z};
}
template <class T> T uniform_hemisphere_pdf(const vec3_t<T>& w) {
  return w.z > T(0) ? T(1) / (T(2) * pi<T>) : T(0);
}

// Cosine-weighted (book 5.3): phi = 2 pi u1, sin(theta) = sqrt(u0), so p = cos(theta)/pi and the
// Lambertian path weight f cos / p is exactly the albedo. z = sqrt(1 - u0) > 0 for u0 < 1.
// [listing cosine-hemisphere]
template <class T> vec3_t<T> sample_cosine_hemisphere(const vec2_t<T>& u) {
  const T u0 = clamp_unit(u.x);
  const T phi = T(2) * pi<T> * clamp_unit(u.y);
  const T s = std::sqrt(u0);
  return {s * std::cos(phi), s * std::sin(phi), std::sqrt(T(1) - u0)};
}
template <class T> T cosine_hemisphere_pdf(const vec3_t<T>& w) {
  return w.z > T(0) ? w.z / pi<T> : T(0);
}
// [end]

// ---------------------------------------------------------------- a cone around +z
// Directions within theta_max of +z, uniform in solid angle: the directions towards a sphere of
// radius r seen from distance d (centre), with sin^2 theta_max = r^2/d^2. Everything is written
// with h = 1 - cos(theta) instead of cos(theta): for a tiny or far sphere cos(theta_max) rounds
// to 1 and 1 - cos would be 0, giving an infinite pdf and a zero-width cone. Here
// 1 - cos = sin^2/(1 + cos) has no cancellation.
// [listing cone]
template <class T> T cone_one_minus_cos(T radius, T distance) {
  if (!(distance > radius)) return T(2);  // inside the sphere: it fills every direction
  const T s = radius / distance;          // r/d before squaring: r^2 could overflow
  const T sin2 = s * s;
  const T h = sin2 / (T(1) + std::sqrt(T(1) - sin2));
  return std::max(h, std::numeric_limits<T>::min());  // a sphere too small for T: keep p finite
}
template <class T> T cone_pdf(T one_minus_cos_max) {
  return T(1) / (T(2) * pi<T> * one_minus_cos_max);
}
template <class T> vec3_t<T> sample_cone(const vec2_t<T>& u, T one_minus_cos_max) {
  const T h = clamp_unit(u.x) * one_minus_cos_max;  // 1 - cos(theta), uniform in [0, h_max)
  const T s = std::sqrt(h * (T(2) - h));              // sin(theta)
  const T phi = T(2) * pi<T> * clamp_unit(u.y);
  return {s * std::cos(phi), s * std::sin(phi), T(1) - h};
}
// [end]
// Whether a local direction lies in the cone, tested on 1 - cos without cancellation too.
template <class T> bool in_cone(const vec3_t<T>& w, T one_minus_cos_max) {
  const T len2 = length2(w);
  if (!(len2 > T(0))) return false;
  const T c = w.z / std::sqrt(len2);
  const T h = c > T(0) ? ((w.x * w.x + w.y * w.y) / len2) / (T(1) + c) : T(1) - c;
  return h <= one_minus_cos_max;
}

// ---------------------------------------------------------------- a Phong lobe around +z
// p(alpha) proportional to cos^s(alpha) over the sphere around the lobe's axis:
// p = (s+1)/(2 pi) cos^s(alpha), CDF in cos: cos^(s+1), so cos(alpha) = u0^(1/(s+1)). For large s
// (10^4) cos(alpha) is within 1e-4 of one: it is computed as exp(log(u0)/(s+1)) and
// 1 - cos(alpha) as -expm1(...), so sin(alpha) keeps its digits. Directions with alpha > 90
// degrees get density 0 (they are never produced).
// [listing phong-lobe]
template <class T> vec3_t<T> sample_phong_lobe(const vec2_t<T>& u, T s) {
  const T e = std::log(T(1) - clamp_unit(u.x)) / (s + T(1));  // log(cos alpha), 1-u0 in (0,1]
  const T c = std::exp(e), h = -std::expm1(e);                // cos(alpha), 1 - cos(alpha)
  const T sin_a = std::sqrt(h * (T(1) + c));
  const T phi = T(2) * pi<T> * clamp_unit(u.y);
  return {sin_a * std::cos(phi), sin_a * std::sin(phi), c};
}
template <class T> T phong_lobe_pdf(T cos_alpha, T s) {
  return cos_alpha > T(0) ? (s + T(1)) / (T(2) * pi<T>) * std::pow(cos_alpha, s) : T(0);
}
// [end]

// ---------------------------------------------------------------- points on shapes (area lights)
// Uniform on a triangle: b0 = 1 - sqrt(u0), b1 = u1 sqrt(u0) (barycentrics of p1 and p2 below).
template <class T> vec2_t<T> sample_triangle_barycentric(const vec2_t<T>& u) {
  const T s = std::sqrt(clamp_unit(u.x));
  const T b1 = clamp_unit(u.y) * s;
  return {b1, s - b1};  // (b1, b2); b0 = 1 - s
}
template <class T>
vec3_t<T> sample_triangle(const vec2_t<T>& u, const vec3_t<T>& p0, const vec3_t<T>& p1,
                          const vec3_t<T>& p2) {
  const vec2_t<T> b = sample_triangle_barycentric(u);
  return p0 + b.x * (p1 - p0) + b.y * (p2 - p0);
}
template <class T> T triangle_area(const vec3_t<T>& p0, const vec3_t<T>& p1, const vec3_t<T>& p2) {
  return glm::length(glm::cross(p1 - p0, p2 - p0)) / T(2);
}
template <class T>
T triangle_pdf(const vec3_t<T>& p0, const vec3_t<T>& p1, const vec3_t<T>& p2) {
  return T(1) / triangle_area(p0, p1, p2);
}

// Uniform on the parallelogram corner + s e1 + t e2, (s,t) in [0,1)^2; pdf = 1/|e1 x e2|.
template <class T>
vec3_t<T> sample_parallelogram(const vec2_t<T>& u, const vec3_t<T>& corner, const vec3_t<T>& e1,
                               const vec3_t<T>& e2) {
  return corner + clamp_unit(u.x) * e1 + clamp_unit(u.y) * e2;
}
template <class T> T parallelogram_pdf(const vec3_t<T>& e1, const vec3_t<T>& e2) {
  return T(1) / glm::length(glm::cross(e1, e2));
}

// A density per unit area on a light, seen from a point at distance d whose direction makes the
// angle theta_l with the light's normal, as a density per steradian: p_A d^2 / |cos theta_l|.
template <class T> T area_to_solid_angle_pdf(T pdf_area, T distance2, T cos_light) {
  const T c = std::abs(cos_light);
  return c > T(0) ? pdf_area * distance2 / c : T(0);
}

// ---------------------------------------------------------------- world-frame distributions
// Each has sample(u) -> unit direction and pdf(direction) per steradian.
template <class T> struct uniform_sphere_t {
  vec3_t<T> sample(const vec2_t<T>& u) const { return sample_uniform_sphere(u); }
  T pdf(const vec3_t<T>&) const { return uniform_sphere_pdf<T>(); }
};

template <class T> struct uniform_hemisphere_t {
  onb_t<T> frame;
  explicit uniform_hemisphere_t(const vec3_t<T>& n) : frame(n) {}
  vec3_t<T> sample(const vec2_t<T>& u) const {
    return frame.to_world(sample_uniform_hemisphere(u));
  }
  T pdf(const vec3_t<T>& w) const { return uniform_hemisphere_pdf(frame.to_local(w)); }
};

template <class T> struct cosine_hemisphere_t {
  onb_t<T> frame;
  explicit cosine_hemisphere_t(const vec3_t<T>& n) : frame(n) {}
  vec3_t<T> sample(const vec2_t<T>& u) const { return frame.to_world(sample_cosine_hemisphere(u)); }
  T pdf(const vec3_t<T>& w) const { return cosine_hemisphere_pdf(frame.to_local(w)); }
};

// The directions from point `from` towards a sphere (a spherical light), uniform in solid angle.
template <class T> struct cone_t {
  onb_t<T> frame;
  T one_minus_cos_max;
  cone_t(const vec3_t<T>& from, const vec3_t<T>& center, T radius)
      : frame(axis(center - from)),
        one_minus_cos_max(cone_one_minus_cos(radius, glm::length(center - from))) {}
  vec3_t<T> sample(const vec2_t<T>& u) const {
    return frame.to_world(sample_cone(u, one_minus_cos_max));
  }
  static vec3_t<T> axis(const vec3_t<T>& d) {  // from the centre: any axis will do
    const vec3_t<T> a = normalize_or_zero(d);
    return length2(a) > T(0) ? a : vec3_t<T>(0, 0, 1);
  }
  T pdf(const vec3_t<T>& w) const {
    return in_cone(frame.to_local(w), one_minus_cos_max) ? cone_pdf(one_minus_cos_max) : T(0);
  }
};

// A Phong lobe of exponent s around a unit axis (the mirror direction, in bxdf.hpp).
template <class T> struct phong_lobe_t {
  onb_t<T> frame;
  T exponent;
  phong_lobe_t(const vec3_t<T>& axis, T s) : frame(axis), exponent(s) {}
  vec3_t<T> sample(const vec2_t<T>& u) const {
    return frame.to_world(sample_phong_lobe(u, exponent));
  }
  T pdf(const vec3_t<T>& w) const {
    return phong_lobe_pdf(std::min(glm::dot(w, frame.n), T(1)), exponent);
  }
};

// p = w p_a + (1 - w) p_b: choose a with probability w, then sample it. The first number is
// reused after rescaling, so u stays two-dimensional. The pdf of the mixture is the mixture of
// the pdfs whichever part produced the direction (the "one-sample" balance heuristic's weight).
// [listing mixture]
template <class A, class B, class T = double> struct mixture_t {
  A a;
  B b;
  T weight_a = T(0.5);  // probability of sampling a, in [0,1]

  vec3_t<T> sample(const vec2_t<T>& u) const {
    const T u0 = clamp_unit(u.x);
    if (u0 < weight_a) return a.sample(vec2_t<T>(u0 / weight_a, u.y));
    return b.sample(vec2_t<T>((u0 - weight_a) / (T(1) - weight_a), u.y));
  }
  T pdf(const vec3_t<T>& w) const { return weight_a * a.pdf(w) + (T(1) - weight_a) * b.pdf(w); }
};
// [end]

using uniform_sphere_dist = uniform_sphere_t<double>;
using uniform_hemisphere_dist = uniform_hemisphere_t<double>;
using cosine_hemisphere_dist = cosine_hemisphere_t<double>;
using cone_dist = cone_t<double>;
using phong_lobe_dist = phong_lobe_t<double>;

}  // namespace zraka

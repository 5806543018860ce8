#pragma once
// The environment light (book 5.3): radiance arriving from infinitely far away, a function of
// direction only. Either a constant colour (a uniform sky) or an equirectangular ("lat-long") map:
// texel (i, j) of a W x H image covers
//     phi   = 2 pi u,  u = (i + [0,1)) / W       around the up axis (+y), from -z towards +x,
//     theta = pi v,    v = (j + [0,1)) / H       down from +y (row 0 is the zenith),
// the direction being w = (sin phi sin theta, cos theta, -cos phi sin theta), then turned by
// `rotate` degrees about +y, right-handed (from +z towards +x: a feature at phi is then seen at
// phi - rotate). This is Mitsuba 3's convention, so that its envmap sees the same sky.
// Radiance between texel centres is bilinear (wrapping in phi, clamped at the poles).
//
// Sampling. A map is importance sampled by a 2D piecewise-constant distribution
// (distribution.hpp) over (u, v), texel (i, j) weighted by the mean of the bilinear radiance
// over the texel (so every direction with L > 0 has p > 0) times sin theta_j (texels near the
// poles cover less solid angle). From d(omega) = sin theta dtheta dphi = 2 pi^2 sin theta du dv,
//     p(omega) = p(u, v) / (2 pi^2 sin theta),
// 0 exactly at the poles (sin theta = 0), which are never produced. A constant sky is sampled
// uniformly over the sphere, p = 1/(4 pi).
#include <zraka/core/error.hpp>
#include <zraka/image/image.hpp>
#include <zraka/sampling/distribution.hpp>
#include <zraka/sampling/sampling.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace zraka {

class environment_map {
 public:
  // A constant sky of radiance L.
  static environment_map constant(const rgb& L, const std::string& name = "color") {
    check_texel(L, name, 0, 0);
    environment_map e;
    e.constant_ = true;
    e.L_ = L;
    e.name_ = name;
    return e;
  }
  // A lat-long map; every texel finite and non-negative (name is the file, for messages).
  static environment_map from_image(const image& img, const std::string& name, float scale = 1.0f,
                                    double rotate_degrees = 0.0) {
    if (img.width <= 0 || img.height <= 0) throw error(name + ": the environment map is empty");
    if (!(scale >= 0) || !std::isfinite(scale)) throw error(name + ": the scale must be finite and >= 0");
    environment_map e;
    e.name_ = name;
    e.img_ = img;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        check_texel(img.at(x, y), name, x, y);
        e.img_.at(x, y) = img.at(x, y) * scale;
      }
    e.set_rotation(rotate_degrees);
    e.build();
    return e;
  }
  static environment_map constant(const rgb& L, float scale, double rotate_degrees) {
    environment_map e = constant(L * scale);
    e.set_rotation(rotate_degrees);
    return e;
  }

  bool is_constant() const { return constant_; }
  const std::string& name() const { return name_; }
  int width() const { return constant_ ? 1 : img_.width; }
  int height() const { return constant_ ? 1 : img_.height; }
  double rotate_degrees() const { return rotate_; }
  // What the OpenCL kernel packs (gpu_scene.hpp) and the Mitsuba export writes: the map's texels,
  // scale applied (row 0 the zenith; empty for a constant sky), its sampling distribution, the
  // rotation's cosine and sine, a constant sky's radiance.
  const image& map() const { return img_; }
  const distribution_2d& distribution() const { return dist_; }
  double cos_rotation() const { return cos_; }
  double sin_rotation() const { return sin_; }
  const rgb& constant_radiance() const { return L_; }

  // [listing environment-lookup]
  // The radiance arriving along -w, i.e. seen looking in direction w (unit).
  template <class T> rgb radiance(const vec3_t<T>& w) const {
    if (constant_) return L_;
    const vec2 uv = to_uv(to_local(vec3(w)));
    // Bilinear between texel centres: wrap around in phi, clamp at the poles.
    const double x = uv.x * img_.width - 0.5, y = uv.y * img_.height - 0.5;
    const double fx = std::floor(x), fy = std::floor(y);
    const float tx = float(x - fx), ty = float(y - fy);
    const int x0 = wrap(int(fx), img_.width), x1 = wrap(int(fx) + 1, img_.width);
    const int y0 = std::clamp(int(fy), 0, img_.height - 1), y1 = std::clamp(int(fy) + 1, 0, img_.height - 1);
    const rgb top = (1 - tx) * img_.at(x0, y0) + tx * img_.at(x1, y0);
    const rgb bottom = (1 - tx) * img_.at(x0, y1) + tx * img_.at(x1, y1);
    return (1 - ty) * top + ty * bottom;
  }
  // [end]

  // [listing environment-sample]
  // A direction w with density pdf per steradian (pdf 0: no direction, e.g. a pole).
  template <class T> vec3_t<T> sample(const vec2_t<T>& u, T& pdf) const {
    if (constant_) {
      pdf = uniform_sphere_pdf<T>();
      return sample_uniform_sphere(u);
    }
    double p_uv = 0;
    const vec2_t<T> uv = dist_.sample(u, p_uv);
    const double theta = pi<double> * double(uv.y), phi = 2 * pi<double> * double(uv.x);
    const double sin_theta = std::sin(theta);
    if (!(sin_theta > 0) || !(p_uv > 0)) {
      pdf = T(0);
      return vec3_t<T>(0);
    }
    pdf = T(p_uv / (2 * pi<double> * pi<double> * sin_theta));
    const vec3 local(std::sin(phi) * sin_theta, std::cos(theta), -std::cos(phi) * sin_theta);
    return vec3_t<T>(to_world(local));
  }
  // The density of sample() for direction w (unit), per steradian.
  template <class T> T pdf(const vec3_t<T>& w) const {
    if (constant_) return uniform_sphere_pdf<T>();
    const vec3 l = to_local(vec3(w));
    const double sin_theta = std::sqrt(l.x * l.x + l.z * l.z);
    if (!(sin_theta > 0)) return T(0);
    const vec2 uv = to_uv(l);
    return T(dist_.pdf(uv.x, uv.y) / (2 * pi<double> * pi<double> * sin_theta));
  }
  // [end]

  // The integral of the radiance (mean over the channels) over the sphere of directions; the
  // light's power is this times pi R^2 for a scene of bounding radius R (the flux through a disk
  // of radius R facing every direction).
  double integral() const {
    if (constant_) return 4 * pi<double> * mean(L_);
    double sum = 0;
    for (int j = 0; j < img_.height; ++j) {
      const double band = (std::cos(pi<double> * j / img_.height) - std::cos(pi<double> * (j + 1) / img_.height)) *
                          2 * pi<double> / img_.width;  // solid angle of one texel of row j
      for (int i = 0; i < img_.width; ++i) sum += mean(img_.at(i, j)) * band;
    }
    return sum;
  }

  // Directions: the map's own frame (before the rotation about +y) and the world's.
  vec3 to_local(const vec3& w) const { return {cos_ * w.x - sin_ * w.z, w.y, sin_ * w.x + cos_ * w.z}; }
  vec3 to_world(const vec3& l) const { return {cos_ * l.x + sin_ * l.z, l.y, -sin_ * l.x + cos_ * l.z}; }
  // (u, v) in [0,1]^2 of a local direction (need not be unit).
  static vec2 to_uv(const vec3& l) {
    double phi = std::atan2(l.x, -l.z);
    if (phi < 0) phi += 2 * pi<double>;
    const double theta = std::atan2(std::sqrt(l.x * l.x + l.z * l.z), l.y);  // acos without its rounding at the poles
    return {std::min(phi / (2 * pi<double>), 1.0), std::min(theta / pi<double>, 1.0)};
  }

 private:
  static double mean(const rgb& c) { return (double(c.x) + double(c.y) + double(c.z)) / 3.0; }
  static int wrap(int i, int n) { return ((i % n) + n) % n; }
  static void check_texel(const rgb& c, const std::string& name, int x, int y) {
    if (!is_finite(c) || c.x < 0 || c.y < 0 || c.z < 0)
      throw error(name + ": pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                  ") of the environment is negative or not finite");
  }
  void set_rotation(double degrees) {
    if (!std::isfinite(degrees)) throw error(name_ + ": the rotation must be finite");
    rotate_ = degrees;
    const double a = degrees * pi<double> / 180;
    cos_ = std::cos(a);
    sin_ = std::sin(a);
  }
  // [listing environment-distribution]
  // Texel weights: the mean of the bilinear radiance over the texel (36/64 of itself, 6/64 of
  // each edge neighbour, 1/64 of each corner one), times sin theta at the row's centre.
  void build() {
    const int W = img_.width, H = img_.height;
    std::vector<double> w(std::size_t(W) * std::size_t(H));
    auto at = [&](int x, int y) { return mean(img_.at(wrap(x, W), std::clamp(y, 0, H - 1))); };
    for (int j = 0; j < H; ++j) {
      const double sin_theta = std::sin(pi<double> * (j + 0.5) / H);
      for (int i = 0; i < W; ++i) {
        const double edges = at(i - 1, j) + at(i + 1, j) + at(i, j - 1) + at(i, j + 1);
        const double corners = at(i - 1, j - 1) + at(i + 1, j - 1) + at(i - 1, j + 1) + at(i + 1, j + 1);
        w[std::size_t(j) * std::size_t(W) + std::size_t(i)] = (36 * at(i, j) + 6 * edges + corners) / 64 * sin_theta;
      }
    }
    dist_ = distribution_2d(w, std::size_t(W), std::size_t(H));
  }
  // [end]

  bool constant_ = false;
  rgb L_{0};
  image img_;
  distribution_2d dist_;
  std::string name_;
  double rotate_ = 0, cos_ = 1, sin_ = 0;
};

}  // namespace zraka

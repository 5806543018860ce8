#pragma once
// Stochastic progressive photon mapping (book 6.3; Hachisuka and Jensen 2009). Photon mapping
// with a fixed radius r is biased by the blur over the disc and its noise is that of the photons
// inside; a fixed photon budget fixes both. SPPM repeats passes: each pass finds a fresh visible
// point per pixel (a new jittered camera ray, photon_mapping.hpp), traces M new photons, and
// gathers the ones within the pixel's current radius r_i. Pixel i keeps N_i (photons counted so
// far), tau_i (their flux times BRDF, scaled with the disc) and r_i; after a pass that found M_i
// photons,
//     N' = N + alpha M,   r' = r sqrt(N' / (N + M)),   tau' = (tau + beta sum f Phi) r'^2 / r^2,
// so only the fraction alpha of new photons is kept in the count, the disc shrinks (bias -> 0)
// and N grows (variance -> 0) together. After k passes of M photons each
//     L_i = (direct light averaged over the passes) + tau_i / (k M pi r_i^2).
// Photons are stored from their first bounce on (bounces >= 1): light straight from the lights
// is next-event estimation's at the visible point, as in the path loop.
//
// Deterministic: pass k's camera ray of pixel p uses rng(seed, p, k), its photons their own
// streams (photons.hpp), and each pixel's update reads the photons in a fixed order.
#include <zraka/cameras/camera.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image.hpp>
#include <zraka/integrators/photon_map.hpp>
#include <zraka/integrators/photon_mapping.hpp>
#include <zraka/integrators/photons.hpp>
#include <zraka/scene/lights.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

namespace zraka {

struct sppm_options {
  std::uint64_t photons_per_pass = 50000;
  double radius = 0.05;       // initial radius r_0 (scene units)
  double alpha = 2.0 / 3.0;   // fraction of new photons kept: in (0, 1)
  int max_depth = 8;          // camera paths (through specular bounces)
  photon_options trace;
  std::uint64_t seed = 1;
  int threads = 0;
};

template <class T> class sppm_t {
 public:
  // The image size is the scene's (settings.width x settings.height), as prepared_camera() uses it.
  sppm_t(const scene_t<T>& sc, const sppm_options& o);

  // One pass: visible points, photons, each pixel's update.
  void run_pass();

  // The image after the passes so far.
  image estimate() const;

  int passes() const { return passes_; }
  std::uint64_t photons_emitted() const { return emitted_; }
  std::uint64_t rays() const { return rays_; }
  const light_set_t<T>& lights() const { return lights_; }
  // The mean radius over the pixels that have found photons (what the bias scales with).
  double mean_radius() const {
    double s = 0;
    for (const auto& p : pixels_) s += p.r;
    return pixels_.empty() ? 0 : s / double(pixels_.size());
  }

 private:
  struct pixel {
    vec3 direct{0};  // sum over passes
    vec3 tau{0};
    double N = 0;
    double r = 0;
  };
  const scene_t<T>& sc_;
  light_set_t<T> lights_;
  sppm_options opt_;
  typename camera_t<T>::prepared cam_;
  int width_, height_;
  std::vector<pixel> pixels_;
  int passes_ = 0;
  std::uint64_t emitted_ = 0, rays_ = 0;
};

// The members below the class: compiled once at double with zraka::compiled (compiled.hpp).
template <class T>
sppm_t<T>::sppm_t(const scene_t<T>& sc, const sppm_options& o)
    : sc_(sc), lights_(sc), opt_(o), cam_(sc.prepared_camera()), width_(sc.settings.width),
      height_(sc.settings.height) {
  if (!(o.radius > 0) || !std::isfinite(o.radius))
    throw error("sppm: --radius must be positive, got " + std::to_string(o.radius));
  if (!(o.alpha > 0 && o.alpha < 1)) throw error("sppm: --alpha must be strictly between 0 and 1");
  if (o.photons_per_pass == 0) throw error("sppm: --photons must be positive, got 0");
  if (o.max_depth < 0) throw error("sppm: the maximum depth must not be negative");
  check_photon_scene(sc, lights_);
  image::check_size(width_, height_);
  pixels_.resize(std::size_t(width_) * std::size_t(height_));
  for (auto& p : pixels_) p.r = o.radius;
}

// [listing sppm-pass]
template <class T> void sppm_t<T>::run_pass() {
  const std::uint32_t k = std::uint32_t(passes_);
  std::vector<visible_point_t<T>> vps(pixels_.size());
  std::vector<std::uint64_t> row_rays(std::size_t(height_), 0);
  parallel_for(std::size_t(height_), opt_.threads, [&](std::size_t y) {  // 1. visible points
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = y * std::size_t(width_) + std::size_t(x);
      rng g(opt_.seed, std::uint32_t(i), k);
      const vec2_t<T> u(g.uniform2());
      const ray_t<T> r = cam_.generate((T(x) + u.x) / T(width_), (T(y) + u.y) / T(height_));
      vps[i] = find_visible_point(sc_, lights_, r, g, opt_.max_depth, row_rays[y]);
    }
  });
  // 2. photons, from their first bounce on, into a grid with cells of the largest radius
  auto photons = trace_photons(sc_, lights_, opt_.photons_per_pass, opt_.seed, k, opt_.trace, opt_.threads,
                               [](const photon_t<T>& p) { return p.bounces >= 1; });
  rays_ += photons.rays;
  emitted_ += photons.emitted;
  T r_max = T(0);
  for (const auto& p : pixels_) r_max = std::max(r_max, T(p.r));
  const photon_grid_t<T> grid(std::move(photons.photons), r_max);
  parallel_for(std::size_t(height_), opt_.threads, [&](std::size_t y) {  // 3. gather, shrink
    for (int x = 0; x < width_; ++x) {
      const std::size_t i = y * std::size_t(width_) + std::size_t(x);
      pixel& px = pixels_[i];
      const visible_point_t<T>& vp = vps[i];
      px.direct += vec3(vp.direct);
      if (!vp.found) continue;
      std::uint64_t M = 0;
      const material& m = sc_.materials[std::size_t(vp.sh.material)];
      const vec3 phi(photon_flux_sum(grid, m, vp.sh.h, vp.wo, T(px.r), &M));
      if (M == 0) continue;
      const double N_new = px.N + opt_.alpha * double(M);
      const double r_new = px.r * std::sqrt(N_new / (px.N + double(M)));
      px.tau = (px.tau + vec3(vp.beta) * phi) * (r_new * r_new) / (px.r * px.r);
      px.N = N_new;
      px.r = r_new;
    }
  });
  for (const auto r : row_rays) rays_ += r;
  ++passes_;
}
// [end]

// [listing sppm-estimate]
template <class T> image sppm_t<T>::estimate() const {
  image img(width_, height_);
  if (passes_ == 0) return img;
  for (std::size_t i = 0; i < pixels_.size(); ++i) {
    const pixel& px = pixels_[i];
    const vec3 indirect = px.tau / (double(emitted_) * pi<double> * px.r * px.r);
    img.pixels[i] = rgb(px.direct / double(passes_) + indirect);
  }
  return img;
}
// [end]

ZRAKA_INSTANCE(class sppm_t<double>)  // compiled.hpp

using sppm = sppm_t<double>;

}  // namespace zraka

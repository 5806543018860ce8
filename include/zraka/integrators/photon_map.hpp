#pragma once
// A photon map (book 6.3): photons stored for the radius query "every photon within r of x",
// and the density estimate made from it.
//
// The structure is a hash grid written here, not a kd-tree library (nanoflann): the queries of
// photon mapping are all radius queries with a radius known when the map is built (the fixed
// radius, or the largest radius of a progressive pass), so cells of that side answer one query
// by visiting at most 2 x 2 x 2 cells, the build is one counting sort (linear, stable, so the
// order of the photons and hence every floating-point sum is fixed), and it adds no dependency.
// A k-nearest query (Jensen's original) would want a kd-tree; progressive photon mapping does not.
//
// Density estimation with the constant disc kernel: reflected radiance at x towards wo is
//     L_r(x, wo) ~ 1/(N pi r^2) sum over photons p within r of  f(x, wi_p, wo) Phi_p
// (N photons emitted, the photons' flux summed over a disc of area pi r^2 around x). The kernel is
// 1/(pi r^2) inside the disc and 0 outside; its bias is the blur of the radiance over the disc.
#include <zraka/core/error.hpp>
#include <zraka/integrators/photons.hpp>
#include <zraka/materials/material.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace zraka {

template <class T> class photon_grid_t {
 public:
  photon_grid_t() = default;
  // Photons kept in their given order within each cell; `cell` >= every radius asked later.
  photon_grid_t(std::vector<photon_t<T>> photons, T cell) { build(std::move(photons), cell); }

  // [listing grid-build]
  void build(std::vector<photon_t<T>> photons, T cell) {
    if (!(cell > T(0)) || !std::isfinite(cell)) throw error("photon map: the cell size must be positive and finite");
    cell_ = cell;
    photons_.clear(), cells_.clear();
    buckets_ = std::max<std::size_t>(1, photons.size());
    start_.assign(buckets_ + 1, 0);
    std::vector<cell_t> keys(photons.size());
    for (std::size_t i = 0; i < photons.size(); ++i) {
      keys[i] = cell_of(photons[i].p);
      ++start_[bucket(keys[i]) + 1];
    }
    for (std::size_t b = 0; b < buckets_; ++b) start_[b + 1] += start_[b];
    std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
    photons_.resize(photons.size());
    cells_.resize(photons.size());
    for (std::size_t i = 0; i < photons.size(); ++i) {  // stable: photon order within a bucket
      const std::uint32_t at = fill[bucket(keys[i])]++;
      photons_[at] = photons[i];
      cells_[at] = keys[i];
    }
  }
  // [end]

  std::size_t size() const { return photons_.size(); }
  T cell() const { return cell_; }

  // [listing grid-query]
  // f(const photon_t&) for every photon within r of x (r <= cell()), in a fixed order.
  template <class F> void for_each_within(const vec3_t<T>& x, T r, F&& f) const {
    if (photons_.empty()) return;
    if (!(r <= cell_)) throw error("photon map: query radius larger than the grid's cell");
    const cell_t lo = cell_of(x - vec3_t<T>(r)), hi = cell_of(x + vec3_t<T>(r));
    const T r2 = r * r;
    for (std::int64_t i = lo.x; i <= hi.x; ++i)
      for (std::int64_t j = lo.y; j <= hi.y; ++j)
        for (std::int64_t k = lo.z; k <= hi.z; ++k) {
          const cell_t c{i, j, k};
          const std::size_t b = bucket(c);
          for (std::uint32_t n = start_[b]; n < start_[b + 1]; ++n) {
            // Another cell may share the bucket: it is visited once, from its own cell.
            if (!(cells_[n] == c)) continue;
            const vec3_t<T> d = photons_[n].p - x;
            if (glm::dot(d, d) <= r2) f(photons_[n]);
          }
        }
  }
  // [end]

 private:
  struct cell_t {
    std::int64_t x = 0, y = 0, z = 0;
    bool operator==(const cell_t& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  cell_t cell_of(const vec3_t<T>& p) const {
    auto c = [&](T v) {  // clamped: a far photon lands in an edge cell, never overflows
      const T q = std::floor(v / cell_);
      return std::int64_t(std::clamp(q, T(-1e15), T(1e15)));
    };
    return {c(p.x), c(p.y), c(p.z)};
  }
  std::size_t bucket(const cell_t& c) const {
    const std::uint64_t h = std::uint64_t(c.x) * 73856093ull ^ std::uint64_t(c.y) * 19349663ull ^
                            std::uint64_t(c.z) * 83492791ull;
    return std::size_t((h ^ (h >> 29)) % buckets_);
  }

  T cell_ = T(1);
  std::size_t buckets_ = 1;
  std::vector<std::uint32_t> start_{0, 0};
  std::vector<photon_t<T>> photons_;
  std::vector<cell_t> cells_;
};

// [listing density]
// sum over photons within r of x of f(x, wi, wo) Phi, for photons that arrived on the side the
// camera sees (a photon on the back of a thin wall must not light its front). Divide by N pi r^2.
template <class T>
rgb photon_flux_sum(const photon_grid_t<T>& map, const material& m, const hit_t<T>& h, const vec3_t<T>& wo, T r,
                    std::uint64_t* found = nullptr) {
  const vec3_t<T> n = h.facing_normal();
  vec3 sum(0);
  std::uint64_t count = 0;
  map.for_each_within(h.p, r, [&](const photon_t<T>& p) {
    const T cos_i = glm::dot(n, p.wi);
    if (!(cos_i > T(0))) return;
    ++count;
    sum += vec3(brdf_cos(m, h, wo, p.wi)) / double(cos_i) * vec3(p.power);  // f = f cos / cos
  });
  if (found) *found = count;
  return rgb(sum);
}

template <class T>
rgb photon_density(const photon_grid_t<T>& map, std::uint64_t emitted, const material& m, const hit_t<T>& h,
                   const vec3_t<T>& wo, T r) {
  return photon_flux_sum(map, m, h, wo, r) / float(double(emitted) * pi<double> * double(r) * double(r));
}
// [end]

}  // namespace zraka

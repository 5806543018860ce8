#pragma once
// Participating media (book 6.1): fog, smoke, milk. Light travelling a distance t through a
// medium is absorbed (coefficient sigma_a, per unit length, per channel) and scattered out of its
// way (sigma_s); the extinction sigma_t = sigma_a + sigma_s. Along a ray of a homogeneous medium
// the fraction that gets through is Beer-Lambert's transmittance
//     T_r(t) = exp(-sigma_t t),
// and in a heterogeneous one T_r = exp(-tau), tau = integral of sigma_t(x(s)) ds the optical
// depth. Here a heterogeneous medium is sigma(x) = d(x) sigma with a density d in [0, 1] given on
// a grid (density_grid: trilinear, 0 outside its box), so every channel shares the integral
// D(t) = integral d ds and tau_c = sigma_t,c D.
//
// A path in a medium samples where it next interacts, the free-flight distance t (pdf
// sigma_t T_r(t)), and either scatters there (a phase function: phase.hpp) or reaches the surface
// at t_max (probability T_r(t_max)). Two estimators, the option media_estimator:
//   delta  unbiased. Homogeneous: t by inversion of one channel's exponential. Heterogeneous:
//          delta tracking (Woodcock): tentative collisions at the rate of a majorant
//          sigma_bar >= sigma_t(x), each real with probability sigma_t(x) / sigma_bar; shadow
//          rays by ratio tracking, T_r = product of (1 - sigma_t(x_i) / sigma_bar) over the
//          tentative collisions. Delta tracking samples one channel's distances, so a
//          heterogeneous medium must have the same sigma_t in every channel (refused otherwise,
//          by name; its albedo may be coloured).
//   march  ray marching with a fixed step (the thesis's "ray marching"): D(t) by the midpoint
//          rule on steps of length `step` from the segment's start, distances and transmittance
//          exact for that piecewise-constant density. Biased where the density changes within a
//          step (the error in tau falls as step^2); exact for a homogeneous medium.
// Chromatic media: one channel c is chosen uniformly (probability 1/3) and its distance sampled;
// the sample is then weighted by the one-sample MIS over the channels (the balance heuristic,
// as pbrt and Mitsuba do): the density of t is the mean over channels of sigma_t,c T_r,c(t),
// the probability of passing the mean of T_r,c(t_max). We choose uniformly rather than by the
// path throughput so that the weights depend on the medium alone.
#include <zraka/core/compiled.hpp>
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/aabb.hpp>
#include <zraka/image/image.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace zraka {

enum class media_estimator { delta, march };

inline constexpr enum_name<media_estimator> media_estimator_names[] = {{media_estimator::delta, "delta"},
                                                                       {media_estimator::march, "march"}};
constexpr std::span<const enum_name<media_estimator>> enum_names(media_estimator) { return media_estimator_names; }  // enum_names.hpp
inline media_estimator parse_media_estimator(std::string_view s) {
  return parse_enum<media_estimator>(s, "media estimator");
}

struct medium_options {
  media_estimator estimator = media_estimator::delta;
  double step = 0.05;  // march: the step length, in scene units
};

// [listing density-grid]
// A density d in [0, 1] on an n x n x n grid of points spanning box, trilinear between them and
// 0 outside the box. max() is the majorant's share: sigma_bar = sigma_t max().
class density_grid {
 public:
  density_grid(const aabb& box, int n, std::vector<float> values) : box_(box), n_(n), v_(std::move(values)) {
    if (n < 2 || v_.size() != std::size_t(n) * std::size_t(n) * std::size_t(n))
      throw error("density grid: needs n >= 2 and n^3 values");
    if (box.empty() || !is_finite(box.lo) || !is_finite(box.hi)) throw error("density grid: the box must be finite and not empty");
    for (const float x : v_)
      if (!(x >= 0 && x <= 1)) throw error("density grid: densities must be in [0, 1]");
    max_ = *std::max_element(v_.begin(), v_.end());
  }
  // A smooth procedural cloud: a few octaves of value noise, squashed into [0, 1]; the same for
  // every seed on every machine (the lattice values come from the counter-based rng).
  static density_grid noise(const aabb& box, int n, double frequency, std::uint64_t seed) {
    constexpr int lattice = 17;
    std::vector<float> lat(std::size_t(lattice * lattice * lattice));
    rng g(seed, 0x6d656469u);
    for (float& x : lat) x = float(g.uniform());
    auto lattice_at = [&](int i, int j, int k) {
      auto w = [](int a) { return ((a % lattice) + lattice) % lattice; };
      return double(lat[std::size_t((w(i) * lattice + w(j)) * lattice + w(k))]);
    };
    auto value_noise = [&](vec3 p) {
      const vec3 f = glm::floor(p), t = p - f;
      const vec3 s = t * t * (3.0 - 2.0 * t);  // smoothstep: continuous slope
      const int i = int(f.x), j = int(f.y), k = int(f.z);
      double out = 0;
      for (int c = 0; c < 8; ++c) {
        const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
        out += (a ? s.x : 1 - s.x) * (b ? s.y : 1 - s.y) * (e ? s.z : 1 - s.z) * lattice_at(i + a, j + b, k + e);
      }
      return out;
    };
    std::vector<float> v(std::size_t(n) * std::size_t(n) * std::size_t(n));
    for (int z = 0; z < n; ++z)
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const vec3 u = vec3(x, y, z) / double(n - 1);
          double sum = 0, amp = 0.5;
          for (int o = 0; o < 3; ++o, amp *= 0.5) sum += amp * value_noise(u * frequency * double(1 << o));
          const double d = std::clamp((sum - 0.35) * 2.5, 0.0, 1.0);  // clear gaps between clouds
          v[std::size_t((z * n + y) * n + x)] = float(d);
        }
    return density_grid(box, n, std::move(v));
  }

  const aabb& box() const { return box_; }
  int resolution() const { return n_; }
  double max() const { return max_; }
  double at(const vec3& p) const {
    const vec3 u = (p - box_.lo) / (box_.hi - box_.lo) * double(n_ - 1);
    if (!(u.x >= 0 && u.y >= 0 && u.z >= 0 && u.x <= n_ - 1 && u.y <= n_ - 1 && u.z <= n_ - 1)) return 0;
    const int i = std::min(int(u.x), n_ - 2), j = std::min(int(u.y), n_ - 2), k = std::min(int(u.z), n_ - 2);
    const vec3 t = u - vec3(i, j, k);
    double out = 0;
    for (int c = 0; c < 8; ++c) {
      const int a = c & 1, b = (c >> 1) & 1, e = (c >> 2) & 1;
      out += (a ? t.x : 1 - t.x) * (b ? t.y : 1 - t.y) * (e ? t.z : 1 - t.z) *
             double(v_[std::size_t(((k + e) * n_ + (j + b)) * n_ + (i + a))]);
    }
    return out;
  }

 private:
  aabb box_;
  int n_;
  std::vector<float> v_;
  double max_ = 0;
};
// [end]

struct medium {
  std::string name;
  rgb sigma_a{0}, sigma_s{0};  // per unit length
  double g = 0;                // Henyey-Greenstein mean cosine; 0 = isotropic
  std::shared_ptr<const density_grid> density;  // null: homogeneous

  rgb sigma_t() const { return sigma_a + sigma_s; }
  bool homogeneous() const { return !density; }
  bool gray() const { const rgb s = sigma_t(); return s.x == s.y && s.y == s.z; }

  // Throws for what no estimator can use, naming the medium and the field.
  void check() const {
    auto coefficient = [&](const rgb& c, const char* field) {
      if (!is_finite(c) || c.x < 0 || c.y < 0 || c.z < 0)
        throw error("medium '" + name + "': " + field + " must be finite and not negative");
    };
    coefficient(sigma_a, "sigma_a");
    coefficient(sigma_s, "sigma_s");
    if (!is_finite(sigma_t())) throw error("medium '" + name + "': sigma_a + sigma_s overflows");
    if (!(g > -1 && g < 1)) throw error("medium '" + name + "': g must be in (-1, 1), got " + std::to_string(g));
  }
};

// [listing beer-lambert]
// exp(-sigma_t t) per channel, in double; 0 t = 0 and 0 inf = 0 (a clear medium, or none).
inline double optical_depth(double sigma, double length) { return sigma == 0 || length == 0 ? 0.0 : sigma * length; }
inline rgb beer_lambert(const rgb& sigma_t, double length) {
  return rgb(float(std::exp(-optical_depth(sigma_t.x, length))), float(std::exp(-optical_depth(sigma_t.y, length))),
             float(std::exp(-optical_depth(sigma_t.z, length))));
}
// [end]

template <class T> struct flight_t {
  bool scattered = false;  // true: a medium event at t; false: the ray reached t_max
  T t = T(0);
  rgb weight{1};           // what the throughput is multiplied by: T_r sigma_s / pdf, or T_r / P
};

namespace detail {

// The segment (t0, t1) of (0, t_max) where the medium can be dense: all of it for a homogeneous
// medium, the density's box for a grid.
template <class T> bool dense_part(const medium& m, const ray_t<T>& r, T t_max, double& t0, double& t1) {
  t0 = 0, t1 = double(t_max);
  if (m.homogeneous()) return true;
  const ray_t<double> rd(vec3(r.origin), vec3(r.direction));
  return intersect(m.density->box(), rd, 0.0, double(t_max), &t0, &t1);
}

// The one-sample MIS weights over channels (balance heuristic, channels chosen uniformly), given
// the optical-depth integral D at the event and the density there.
inline rgb scatter_weight(const medium& m, double D, double d) {
  const rgb st = m.sigma_t(), tr = beer_lambert(st, D);
  const double pdf = d * (double(st.x) * tr.x + double(st.y) * tr.y + double(st.z) * tr.z) / 3.0;
  if (!(pdf > 0)) return rgb(0);
  return rgb(vec3(tr * m.sigma_s) * (d / pdf));
}
inline rgb pass_weight(const medium& m, double D) {
  const rgb tr = beer_lambert(m.sigma_t(), D);
  const double p = (double(tr.x) + double(tr.y) + double(tr.z)) / 3.0;
  if (!(p > 0)) return rgb(0);
  return rgb(vec3(tr) / p);
}
inline double channel(const rgb& c, int i) { return double(i == 0 ? c.x : i == 1 ? c.y : c.z); }

}  // namespace detail

// [listing free-flight]
// Where does a path along r (in medium m, next surface at t_max, maybe infinite) interact?
// Draws two numbers for a homogeneous medium; a grid's trackers draw as many as they need.
template <class T>
flight_t<T> sample_flight(const medium& m, const ray_t<T>& r, T t_max, rng& g, const medium_options& o) {
  flight_t<T> f;
  const int c = std::min(int(g.uniform() * 3.0), 2);  // the channel whose distances we follow
  const double e = -std::log1p(-g.uniform());          // an exponential with mean 1: tau to go
  const double st_c = detail::channel(m.sigma_t(), c);
  double t0, t1;
  if (!detail::dense_part(m, r, t_max, t0, t1)) return f;  // misses the grid's box: clear
  if (m.homogeneous()) {  // tau_c(t) = sigma_t,c t: inverted exactly
    const double t = st_c > 0 ? e / st_c : infinity<double>;
    if (t < double(t_max)) {
      f.scattered = true;
      f.t = T(t);
      f.weight = detail::scatter_weight(m, t, 1.0);
    } else {
      f.weight = detail::pass_weight(m, double(t_max));
    }
    return f;
  }
  const medium_options& opt = o;
  if (opt.estimator == media_estimator::delta) {  // delta tracking, one channel (gray sigma_t)
    const double majorant = st_c * m.density->max();
    if (!(majorant > 0)) return f;
    const vec3 origin(r.origin), dir(r.direction);
    for (double t = t0 + e / majorant;; t -= std::log1p(-g.uniform()) / majorant) {
      if (!(t < t1)) return f;  // passed: weight 1 (T_r / P = 1 for one channel)
      const double d = m.density->at(origin + t * dir);
      if (g.uniform() * m.density->max() < d) {  // a real collision
        f.scattered = true;
        f.t = T(t);
        f.weight = rgb(vec3(m.sigma_s) / vec3(m.sigma_t()));  // the albedo: sigma_s / sigma_t
        return f;
      }
    }
  }
  // march: the midpoint rule on fixed steps from t0, the distance exact for the steps' densities
  const double step = opt.step, target = st_c > 0 ? e / st_c : infinity<double>;  // in units of D
  const vec3 origin(r.origin), dir(r.direction);
  double D = 0;
  for (double a = t0; a < t1; a += step) {
    const double b = std::min(a + step, t1);
    const double d = m.density->at(origin + 0.5 * (a + b) * dir);
    if (d > 0 && D + d * (b - a) >= target) {
      f.scattered = true;
      f.t = T(a + (target - D) / d);
      f.weight = detail::scatter_weight(m, target, d);
      return f;
    }
    D += d * (b - a);
  }
  f.weight = detail::pass_weight(m, D);
  return f;
}
// [end]

// [listing segment-transmittance]
// The transmittance of m along r over (0, t_max): closed form when homogeneous; for a grid
// ratio tracking (delta: unbiased, draws numbers) or the marched quadrature (march: none drawn).
template <class T>
rgb segment_transmittance(const medium& m, const ray_t<T>& r, T t_max, rng& g, const medium_options& o) {
  double t0, t1;
  if (!detail::dense_part(m, r, t_max, t0, t1)) return rgb(1);
  if (m.homogeneous()) return beer_lambert(m.sigma_t(), double(t_max));
  const vec3 origin(r.origin), dir(r.direction);
  if (o.estimator == media_estimator::delta) {
    const double st = double(m.sigma_t().x), majorant = st * m.density->max();
    if (!(majorant > 0)) return rgb(1);
    double tr = 1;
    for (double t = t0 - std::log1p(-g.uniform()) / majorant; t < t1; t -= std::log1p(-g.uniform()) / majorant) {
      tr *= 1 - st * m.density->at(origin + t * dir) / majorant;
      if (tr < 1e-6) {  // Russian roulette on a faint estimate: unbiased, and it ends the walk
        if (g.uniform() >= 0.5) return rgb(0);
        tr *= 2;
      }
    }
    return rgb(float(tr));
  }
  double D = 0;
  for (double a = t0; a < t1; a += o.step) {
    const double b = std::min(a + o.step, t1);
    D += m.density->at(origin + 0.5 * (a + b) * dir) * (b - a);
  }
  return beer_lambert(m.sigma_t(), D);
}
// [end]

// Compiled once at double (compiled.hpp).
ZRAKA_INSTANCE(flight_t<double> sample_flight(const medium&, const ray_t<double>&, double, rng&, const medium_options&))
ZRAKA_INSTANCE(rgb segment_transmittance(const medium&, const ray_t<double>&, double, rng&, const medium_options&))

}  // namespace zraka

#pragma once
// Bidirectional path tracing (book 6.2; Lafortune and Willems 1993, Veach and Guibas 1994 —
// not the 2001 paper the thesis names, erratum E2). Each sample builds two subpaths:
//   a camera subpath z_0 z_1 ... (z_0 the pinhole) and a light subpath y_0 y_1 ... (y_0 a point
//   on a light, lights.hpp's sample_emission), with the core's materials (scatter) and queries;
// and joins them in every way (s, t): the first s light vertices, the first t camera vertices
// and the segment between y_{s-1} and z_{t-1}. s = 0 is the camera path finding a light by
// itself (path tracing without next events); s = 1 is next-event estimation; t = 1 is light
// tracing, which connects a light vertex to the pinhole and adds the result to whatever pixel
// it lands in ("splatting"). Each strategy is an unbiased estimator of the same paths; the
// multiple importance sampling weight w_{s,t} (power or balance heuristic over every strategy
// that could have made the path) combines them, computed from the ratios of the vertices'
// forward and reverse area densities (Veach's thesis, 10.2):
//   p_{i+1} / p_i = p_fwd(x_i) / p_rev(x_i),
// p_fwd the density of x_i when sampled from the light side, p_rev from the camera side.
// Vertices that scatter specularly (glass, mirrors, fuzzy metal: no density) cannot be joined;
// their densities count as 1 in the ratios, which is how the delta factors cancel.
//
// Paths have at most max_depth + 1 segments, as in path.hpp: BDPT and `mis` estimate the same
// image. The strategy (s, t) = (1, 1), a light seen directly by light tracing, is left out: the
// camera path finds those lights (s = 0) with weight 1. Light the samplers cannot start from
// (the background, an infinite glowing plane, a user shape without area sampling) is found
// only by the camera path and counted with weight 1. A thin-lens camera is refused by name
// (camera_importance.hpp).
//
// Determinism: the image is split into fixed bands of rows, parallel_for's items (parallel.hpp);
// each band's pixels use rng(seed, pixel, sample) and splat into the band's own film, and the
// films are summed in band order (in_order), so --seed gives the same bits for any thread count.
#include <zraka/cameras/camera_importance.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/parallel.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/image/image.hpp>
#include <zraka/integrators/path_kit.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <atomic>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace zraka {

enum class mis_heuristic { power, balance };
inline constexpr enum_name<mis_heuristic> mis_heuristic_names[] = {{mis_heuristic::power, "power"},
                                                                   {mis_heuristic::balance, "balance"}};
constexpr std::span<const enum_name<mis_heuristic>> enum_names(mis_heuristic) { return mis_heuristic_names; }  // enum_names.hpp

struct bdpt_options {
  int max_depth = 8;  // bounces, as path_options::max_depth
  int rr_depth = 3;
  mis_heuristic heuristic = mis_heuristic::power;
  light_selection lights = light_selection::power;
  // One strategy alone, unweighted (weight 1), for paths of length s + t - 1 only: the check
  // that every strategy converges to the same image. -1: all strategies, MIS-weighted.
  int only_s = -1, only_t = -1;
  // > 0: also keep the weighted image of every strategy for path lengths 1..strategy_length
  // (the debug grid, as in Veach's thesis).
  int strategy_length = 0;
  int threads = 0;
  int band_rows = 8;  // the fixed bands of determinism
};

// Where strategy (s, t) of path length k = s + t - 1 is kept in the debug images: row k - 1,
// column s, for s = 0..k.
inline int strategy_slot(int s, int t) {
  const int k = s + t - 1;
  return (k - 1) * (k + 2) / 2 + s;
}
inline int strategy_count(int max_length) { return max_length * (max_length + 3) / 2; }

template <class T> struct bdpt_vertex_t {
  enum class kind { camera, light, surface };
  kind type = kind::surface;
  vec3_t<T> p{T(0)}, p_error{T(0)};
  vec3_t<T> n{T(0)};   // unit geometric normal; zero for the pinhole and a point light
  vec3_t<T> wo{T(0)};  // unit, towards the previous vertex
  hit_t<T> h;          // surfaces: the hit, facing the ray that arrived
  int material = -1;
  object_ref object{shape_kind::sphere, -1};
  int light = -1;      // light vertices: the light's index
  bool delta_light = false;  // a point light
  bool delta = false;  // scattered specularly here: cannot be joined
  rgb beta{1};         // throughput of the subpath up to this vertex
  T pdf_fwd = T(0);    // area density of this vertex from its own subpath's side
  T pdf_rev = T(0);    // ... and from the other side
};

// What this tracer cannot render, refused by name; programs call it before any other work.
template <class T> void check_bdpt_scene(const scene_t<T>& sc) {
  // Vertices in media would need the phase function and transmittance in every density ratio.
  if (!sc.media.empty())
    throw error("bdpt: the scene has participating media (" + sc.media_names() +
                "), which this bidirectional tracer does not handle; render it with pathtrace");
  // Light subpaths start on surfaces; an environment would need emission from a disc at infinity.
  if (sc.environment)
    throw error("bdpt: the scene has an environment light ('" + sc.environment->name() +
                "'), which this bidirectional tracer cannot start light subpaths on; render it with pathtrace");
}

template <class T> class bdpt_t {
 public:
  using vertex = bdpt_vertex_t<T>;

  bdpt_t(const scene_t<T>& sc, const bdpt_options& opt)
      : sc_(sc), lights_(sc, opt.lights), cam_(sc.prepared_camera()), eye_(cam_), opt_(opt) {
    check_bdpt_scene(sc);
    if (opt.max_depth < 0) throw error("bdpt: the maximum depth must not be negative, got " + std::to_string(opt.max_depth));
    if (opt.rr_depth < 0) throw error("bdpt: the Russian roulette depth must not be negative");
    if (opt.strategy_length < 0 || opt.strategy_length > opt.max_depth + 1)
      throw error("bdpt: --strategies must be from 0 to max_depth + 1 = " + std::to_string(opt.max_depth + 1));
    if ((opt.only_s >= 0) != (opt.only_t >= 0) || (opt.only_t >= 0 && opt.only_t < 1))
      throw error("bdpt: a single strategy needs s >= 0 and t >= 1");
  }
  const light_set_t<T>& lights() const { return lights_; }
  const camera_importance_t<T>& eye() const { return eye_; }

  // What one sample gives: the pixel's own estimate (strategies with t >= 2) and the splats
  // of light tracing (t = 1).
  struct splat {
    int x, y;
    rgb value;
  };
  struct sample_result {
    rgb L{0};
    std::vector<splat> splats;
    std::vector<std::pair<int, rgb>> by_strategy;  // (slot, weighted value), debug grid
    std::vector<std::pair<int, splat>> splats_by_strategy;  // (path length k, splat) of (k, 1)
    std::uint64_t nonfinite = 0;
    std::uint64_t rays = 0;
  };

  // [listing bdpt-sample]
  // One sample through image position (sx, sy) in [0,1)^2.
  void sample(T sx, T sy, rng& g, sample_result& out) const {
    camera_.clear();
    light_.clear();
    rgb escaped(0);
    camera_subpath(sx, sy, g, escaped, out.rays);
    light_subpath(g, out.rays);
    add(out, 0, int(camera_.size()) + 1, escaped, -1, -1);  // the sky: only the camera finds it
    for (int t = 1; t <= int(camera_.size()); ++t)
      for (int s = 0; s <= int(light_.size()); ++s) {
        const int k = s + t - 1;  // segments
        if (k < 1 || k > opt_.max_depth + 1 || (s == 1 && t == 1)) continue;
        if (opt_.only_s >= 0 && (s != opt_.only_s || t != opt_.only_t)) continue;
        vec2_t<T> raster(0);
        const rgb c = connect(s, t, raster, out.rays);
        if (c == rgb(0)) continue;
        const T w = opt_.only_s >= 0 ? T(1) : mis_weight(s, t);
        const int px = t == 1 ? std::min(int(raster.x * T(sc_.settings.width)), sc_.settings.width - 1) : -1;
        const int py = t == 1 ? std::min(int(raster.y * T(sc_.settings.height)), sc_.settings.height - 1) : -1;
        add(out, s, t, c * float(w), px, py);
      }
  }
  // [end]

 private:
  void add(sample_result& out, int s, int t, const rgb& v, int px, int py) const {
    if (v == rgb(0)) return;
    if (opt_.only_s >= 0 && (s != opt_.only_s || t != opt_.only_t)) return;
    if (!is_finite(v)) {
      ++out.nonfinite;
      return;
    }
    const int k = s + t - 1;
    const bool debug = k >= 1 && k <= opt_.strategy_length;
    if (t == 1) {
      out.splats.push_back({px, py, v});
      if (debug) out.splats_by_strategy.push_back({k, splat{px, py, v}});
    } else {
      out.L += v;
      if (debug) out.by_strategy.push_back({strategy_slot(s, t), v});
    }
  }

  // |cos| at v towards w; 1 at the pinhole and a point light (no surface).
  static T cos_at(const vertex& v, const vec3_t<T>& w) {
    return v.n == vec3_t<T>(0) ? T(1) : std::abs(glm::dot(v.n, w));
  }
  // A density per steradian at `from` as a density per unit area at `to`.
  static T to_area(T pdf_w, const vertex& from, const vertex& to) {
    const vec3_t<T> d = to.p - from.p;
    const T d2 = length2(d);
    if (!(d2 > T(0))) return T(0);
    return pdf_w * cos_at(to, d / std::sqrt(d2)) / d2;
  }
  static bool connectible(const material& m, const vertex& v) {
    return v.type != vertex::kind::surface || (has_density(m) && !v.delta);
  }

  // [listing random-walk]
  // Extends a subpath from its last vertex along r: at each hit a vertex with its throughput
  // beta and forward density, and the reverse density of the vertex before it.
  void random_walk(std::vector<vertex>& path, ray_t<T> r, rgb beta, T pdf_w, int max_vertices, bool camera,
                   rgb& escaped, std::uint64_t& rays, rng& g) const {
    for (int bounce = 0; int(path.size()) < max_vertices; ++bounce) {
      scene_hit_t<T> sh;
      ++rays;
      if (!nearest_hit(sc_, r, sh)) {
        if (camera) escaped = beta * sc_.background;
        return;
      }
      vertex v;
      v.p = sh.h.p;
      v.p_error = sh.h.p_error;
      v.n = sh.h.normal;
      v.wo = -r.direction;
      v.h = sh.h;
      v.material = sh.material;
      v.object = sh.object;
      v.beta = beta;
      v.pdf_fwd = to_area(pdf_w, path.back(), v);
      path.push_back(v);
      if (int(path.size()) == max_vertices) return;
      const material& m = sc_.materials[std::size_t(sh.material)];
      const auto s = scatter(m, r.direction, sh.h, g);
      if (!s) return;
      vertex& cur = path.back();
      vertex& prev = path[path.size() - 2];
      cur.delta = s->specular;
      // The reverse density: the same material sampling wo given the new direction.
      const T pdf_rev_w = s->specular ? T(0) : scatter_pdf(m, sh.h, s->direction, v.wo);
      prev.pdf_rev = to_area(pdf_rev_w, cur, prev);
      pdf_w = s->specular ? T(0) : s->pdf;
      beta *= s->weight;
      if (!survives_roulette(beta, bounce, opt_.rr_depth, g)) return;
      r = spawn_ray(sh.h, s->direction);
    }
  }
  // [end]

  void camera_subpath(T sx, T sy, rng& g, rgb& escaped, std::uint64_t& rays) const {
    vertex z0;
    z0.type = vertex::kind::camera;
    z0.p = eye_.origin;
    z0.pdf_fwd = T(1);
    camera_.push_back(z0);
    const ray_t<T> r = cam_.generate(sx, sy);
    random_walk(camera_, r, rgb(1), eye_.pdf_direction(r.direction), opt_.max_depth + 2, true, escaped, rays, g);
  }

  void light_subpath(rng& g, std::uint64_t& rays) const {
    const T u_select = T(g.uniform());
    const vec2_t<T> u_pos(g.uniform2()), u_dir(g.uniform2());
    const auto e = lights_.sample_emission(u_select, u_pos, u_dir);
    if (!e || e->Le == rgb(0)) return;
    vertex y0;
    y0.type = vertex::kind::light;
    y0.p = e->point;
    y0.p_error = e->p_error;
    y0.n = e->normal;
    y0.light = e->light;
    y0.delta_light = e->delta_position;
    y0.beta = rgb(float(T(1) / e->pdf_position));
    y0.pdf_fwd = e->pdf_position;
    light_.push_back(y0);
    hit_t<T> h;
    h.p = e->point;
    h.p_error = e->p_error;
    h.normal = e->normal;
    const rgb beta = e->Le * float(cos_at(y0, e->direction) / (e->pdf_position * e->pdf_direction));
    rgb unused(0);
    random_walk(light_, spawn_ray(h, e->direction), beta, e->pdf_direction, opt_.max_depth + 1, false, unused, rays, g);
  }

  const material& material_of(const vertex& v) const {
    static const material none = material::emitter(rgb(0));
    return v.material >= 0 ? sc_.materials[std::size_t(v.material)] : none;
  }
  // The radiance light vertex y0 sends along w.
  rgb light_Le(const vertex& y0, const vec3_t<T>& w) const {
    const auto& l = lights_.lights()[std::size_t(y0.light)];
    if (l.point >= 0) return lights_.intensity_towards(y0.light, w);
    return light_set_t<T>::emitted_towards(sc_.material_of(l.object), y0.n, w);
  }
  // Is the segment between a and b free? Both ends move off their surfaces by their rounding.
  bool visible(const vertex& a, const vertex& b, std::uint64_t& rays) const {
    const vec3_t<T> oa = offset_origin(a.p, a.p_error, a.n, b.p - a.p);
    const vec3_t<T> ob = offset_origin(b.p, b.p_error, b.n, a.p - b.p);
    const vec3_t<T> d = ob - oa;
    const T dist = std::sqrt(length2(d));
    if (!(dist > T(0))) return false;
    ++rays;
    return !occluded(sc_, segment_t<T>{ray_t<T>(oa, d), dist * (T(1) - gamma<T>(16))});
  }

  // [listing connect]
  // The unweighted contribution of strategy (s, t); for t = 1 also where on the image it lands.
  rgb connect(int s, int t, vec2_t<T>& raster, std::uint64_t& rays) const {
    const vertex& pt = camera_[std::size_t(t - 1)];
    if (s == 0) {  // the camera path found a light by itself
      if (pt.type != vertex::kind::surface) return rgb(0);
      return pt.beta * emitted(material_of(pt), pt.h);
    }
    const vertex& qs = light_[std::size_t(s - 1)];
    const material& mq = material_of(qs);
    if (!connectible(mq, qs)) return rgb(0);
    if (t == 1) {  // light tracing: join qs to the pinhole
      const vec3_t<T> d = qs.p - eye_.origin;
      const T d2 = length2(d);
      const vec3_t<T> w = d / std::sqrt(d2);
      const auto st = eye_.image_position(w);
      if (!st) return rgb(0);
      raster = *st;
      const rgb f = s == 1 ? light_Le(qs, -w) * float(cos_at(qs, w)) : brdf_cos(mq, qs.h, qs.wo, -w);
      if (f == rgb(0)) return rgb(0);
      const rgb c = qs.beta * f * float(eye_.importance(w) * eye_.cos_theta(w) / d2);
      return c != rgb(0) && visible(qs, pt, rays) ? c : rgb(0);
    }
    const material& mp = material_of(pt);
    if (!connectible(mp, pt)) return rgb(0);
    const vec3_t<T> d = qs.p - pt.p;
    const T d2 = length2(d);
    if (!(d2 > T(0))) return rgb(0);
    const vec3_t<T> w = d / std::sqrt(d2);  // from pt towards qs
    const rgb fz = brdf_cos(mp, pt.h, pt.wo, w);
    if (fz == rgb(0)) return rgb(0);
    const rgb fy = s == 1 ? light_Le(qs, -w) * float(cos_at(qs, w)) : brdf_cos(mq, qs.h, qs.wo, -w);
    const rgb c = pt.beta * fz * fy * qs.beta / float(d2);
    return c != rgb(0) && visible(pt, qs, rays) ? c : rgb(0);
  }
  // [end]

  // [listing mis-weight]
  // w_{s,t} = 1 / sum over the strategies s' of (p_{s'} / p_s)^beta, from the ratios of the
  // forward and reverse densities along the path; the densities at the joined vertices (and
  // the ones before them) change with the join and are worked out here.
  T mis_weight(int s, int t) const {
    if (s + t == 2) return T(1);
    const vertex& pt = camera_[std::size_t(t - 1)];
    const vertex* qs = s > 0 ? &light_[std::size_t(s - 1)] : nullptr;
    int light_of_pt = -1;
    if (s == 0) {
      light_of_pt = lights_.index_of(pt.object);
      if (light_of_pt < 0) return T(1);  // no light sampler can start there
    }
    // Copies of the densities (at most max_depth + 2 vertices a side), kept between calls.
    cf_.resize(std::size_t(t)), cr_.resize(std::size_t(t)), cd_.resize(std::size_t(t));
    lf_.resize(std::size_t(s)), lr_.resize(std::size_t(s)), ld_.resize(std::size_t(s));
    T* cf = cf_.data(); T* cr = cr_.data(); T* lf = lf_.data(); T* lr = lr_.data();
    char* cd = cd_.data(); char* ld = ld_.data();
    for (int i = 0; i < t; ++i) {
      cf[i] = camera_[std::size_t(i)].pdf_fwd, cr[i] = camera_[std::size_t(i)].pdf_rev, cd[i] = camera_[std::size_t(i)].delta;
    }
    for (int i = 0; i < s; ++i) {
      lf[i] = light_[std::size_t(i)].pdf_fwd, lr[i] = light_[std::size_t(i)].pdf_rev, ld[i] = light_[std::size_t(i)].delta;
    }
    // pt, sampled from the light side
    if (s == 0) cr[t - 1] = lights_.pdf_emission_position(light_of_pt);
    else if (s == 1) cr[t - 1] = to_area(lights_.pdf_emission_direction(qs->light, qs->n, normalize_or_zero(pt.p - qs->p)), *qs, pt);
    else cr[t - 1] = to_area(scatter_pdf(material_of(*qs), qs->h, qs->wo, normalize_or_zero(pt.p - qs->p)), *qs, pt);
    // the vertex before pt, sampled from the light side through pt
    if (t >= 3) {
      const vertex& pm = camera_[std::size_t(t - 2)];
      const T pw = s == 0 ? lights_.pdf_emission_direction(light_of_pt, pt.n, pt.wo)
                          : scatter_pdf(material_of(pt), pt.h, normalize_or_zero(qs->p - pt.p), pt.wo);
      cr[t - 2] = to_area(pw, pt, pm);
    }
    if (s >= 1) {
      // qs, sampled from the camera side
      const vec3_t<T> w = normalize_or_zero(qs->p - pt.p);
      lr[s - 1] = t == 1 ? to_area(eye_.pdf_direction(w), pt, *qs)
                         : to_area(scatter_pdf(material_of(pt), pt.h, pt.wo, w), pt, *qs);
      // the vertex before qs, sampled from the camera side through qs
      if (s >= 2)
        lr[s - 2] = to_area(scatter_pdf(material_of(*qs), qs->h, -w, qs->wo), *qs, light_[std::size_t(s - 2)]);
    }
    cd[t - 1] = false;
    if (s > 0) ld[s - 1] = false;
    const auto remap = [](T p) { return p != T(0) ? p : T(1); };
    const auto h = [&](T r) { return opt_.heuristic == mis_heuristic::power ? r * r : r; };
    T sum = T(0), r = T(1);
    for (int i = t - 1; i > 0; --i) {  // more light vertices: s + 1, s + 2, ... (down to t = 1)
      r *= remap(cr[i]) / remap(cf[i]);
      if (!cd[i] && !cd[i - 1]) sum += h(r);
    }
    r = T(1);
    for (int i = s - 1; i >= 0; --i) {  // fewer light vertices: s - 1, ..., 0
      r *= remap(lr[i]) / remap(lf[i]);
      const bool delta_before = i > 0 ? ld[i - 1] : light_[0].delta_light;
      if (!ld[i] && !delta_before) sum += h(r);
    }
    return T(1) / (T(1) + sum);
  }
  // [end]

  const scene_t<T>& sc_;
  light_set_t<T> lights_;
  typename camera_t<T>::prepared cam_;
  camera_importance_t<T> eye_;
  bdpt_options opt_;
  // The subpaths of the sample being made (one bdpt_t per thread: see render_bdpt).
  mutable std::vector<vertex> camera_, light_;
  mutable std::vector<T> cf_, cr_, lf_, lr_;  // mis_weight's copies of the densities
  mutable std::vector<char> cd_, ld_;
};

struct bdpt_render_t {
  image img;
  std::vector<image> strategies;  // strategy_slot(s, t) -> weighted image (debug grid)
  render_stats stats;
};

// [listing render-bdpt]
// The whole image: pixel (x, y)'s samples use rng(seed, pixel, sample) as render() does; each
// band of rows sums its pixels' own estimates, and its light-tracing splats in a film of its
// own; the films are added to the image in band order (a band waits for the ones before it).
// One light subpath per camera sample: a splat is already a per-sample estimate of its pixel.
template <class T> bdpt_render_t render_bdpt(const scene_t<T>& sc, int spp, std::uint64_t seed, const bdpt_options& opt) {
  if (spp < 1) throw error("--spp must be at least 1, got " + std::to_string(spp));
  if (opt.band_rows < 1) throw error("bdpt: band_rows must be at least 1");
  const int W = sc.settings.width, H = sc.settings.height;
  check_render_size(W, H, spp);
  const int threads = resolve_threads(opt.threads);
  const int bands = (H + opt.band_rows - 1) / opt.band_rows;
  const std::size_t N = std::size_t(W) * std::size_t(H);
  const int K = opt.strategy_length, slots = K > 0 ? strategy_count(K) : 0;
  { const bdpt_t<T> probe(sc, opt); }  // refuses bad options before threads start

  std::vector<vec3> own(N, vec3(0));  // each pixel is written by its own band only
  std::vector<std::vector<vec3>> own_s(std::size_t(slots), std::vector<vec3>(N, vec3(0)));
  std::vector<vec3> splats(N, vec3(0));                                   // the bands' films, summed
  std::vector<std::vector<vec3>> splats_s(std::size_t(K), std::vector<vec3>(N, vec3(0)));  // (k, t = 1)
  struct films {
    std::vector<vec3> all;
    std::vector<std::vector<vec3>> by_length;  // (k, t = 1), k = 1..K
  };
  in_order<films> band_films(static_cast<std::size_t>(bands));
  std::vector<std::optional<bdpt_t<T>>> tracers(static_cast<std::size_t>(threads));  // one a thread: it keeps its subpaths
  std::atomic<std::uint64_t> rays{0}, bad{0};
  stopwatch clock;

  parallel_for(std::size_t(bands), threads, [&](std::size_t b, int worker) {
    auto& tracer = tracers[std::size_t(worker)];
    if (!tracer) tracer.emplace(sc, opt);
    typename bdpt_t<T>::sample_result res;
    films film{std::vector<vec3>(N, vec3(0)), std::vector<std::vector<vec3>>(std::size_t(K), std::vector<vec3>(N, vec3(0)))};
    std::uint64_t band_rays = 0, band_bad = 0;
    for (int y = int(b) * opt.band_rows; y < std::min(H, (int(b) + 1) * opt.band_rows); ++y)
      for (int x = 0; x < W; ++x) {
        const std::size_t pixel = std::size_t(y) * std::size_t(W) + std::size_t(x);
        vec3 sum(0);
        for (int s = 0; s < spp; ++s) {
          rng g(seed, std::uint32_t(pixel), std::uint32_t(s));
          const vec2 u = g.uniform2();
          res.L = rgb(0);
          res.splats.clear();
          res.by_strategy.clear();
          res.splats_by_strategy.clear();
          res.nonfinite = res.rays = 0;
          tracer->sample(T((x + u.x) / W), T((y + u.y) / H), g, res);
          sum += vec3(res.L);
          for (const auto& sp : res.splats) film.all[std::size_t(sp.y) * std::size_t(W) + std::size_t(sp.x)] += vec3(sp.value);
          for (const auto& [slot, v] : res.by_strategy) own_s[std::size_t(slot)][pixel] += vec3(v);
          for (const auto& [k, sp] : res.splats_by_strategy)
            film.by_length[std::size_t(k - 1)][std::size_t(sp.y) * std::size_t(W) + std::size_t(sp.x)] += vec3(sp.value);
          band_rays += res.rays;
          band_bad += res.nonfinite;
        }
        own[pixel] = sum;
      }
    rays += band_rays;
    bad += band_bad;
    band_films.put(b, std::move(film), [&](const films& f) {
      for (std::size_t i = 0; i < N; ++i) splats[i] += f.all[i];
      for (int k = 0; k < K; ++k)
        for (std::size_t i = 0; i < N; ++i) splats_s[std::size_t(k)][i] += f.by_length[std::size_t(k)][i];
    });
  });
  if (band_films.merged() != std::size_t(bands))
    throw error("bdpt: internal error, " + std::to_string(std::size_t(bands) - band_films.merged()) + " bands not merged");

  bdpt_render_t out;
  out.img = image(W, H);
  for (std::size_t i = 0; i < N; ++i) out.img.pixels[i] = rgb((own[i] + splats[i]) / double(spp));
  for (int slot = 0; slot < slots; ++slot) {
    image im(W, H);
    for (std::size_t i = 0; i < N; ++i) im.pixels[i] = rgb(own_s[std::size_t(slot)][i] / double(spp));
    out.strategies.push_back(std::move(im));
  }
  for (int k = 1; k <= K; ++k) {  // light tracing's strategies (s, t) = (k, 1)
    image& im = out.strategies[std::size_t(strategy_slot(k, 1))];
    for (std::size_t i = 0; i < N; ++i) im.pixels[i] = rgb(splats_s[std::size_t(k - 1)][i] / double(spp));
  }
  out.stats = {clock.seconds(), threads, std::uint64_t(N) * std::uint64_t(spp), rays.load(), bad.load()};
  return out;
}
// [end]

ZRAKA_INSTANCE(bdpt_render_t render_bdpt(const scene_t<double>&, int, std::uint64_t, const bdpt_options&))  // compiled.hpp

}  // namespace zraka

#pragma once
// Three path tracers for one scene (book 2.3), all estimating the rendering equation
//     L_o(x, wo) = L_e(x, wo) + integral f(x, wi, wo) L_i(x, wi) |cos theta_i| dwi
// with the same mean and different noise:
//   naive  the thesis's algorithm (Listing 2.3, made iterative as in its OpenCL Listing 4.6):
//          follow the scattered ray and add the light it happens to hit. The throughput "mask"
//          is multiplied by f cos / pdf, the cosine counted once (erratum C6).
//   nee    next-event estimation (erratum C4): at every non-specular hit also pick a point on a
//          light and add its light if the shadow segment is free. Emission that the scattered
//          ray then finds on a light that could have been sampled is skipped: it was counted.
//   mis    multiple importance sampling (Veach and Guibas 1995): both the light sample and the
//          BSDF-sampled ray that hits a light are kept, each weighted by the power heuristic
//          w_a = p_a^2 / (p_a^2 + p_b^2) of the two densities for that direction, so that the
//          weights of the two ways to make the same path sum to one.
// All three stop at max_depth bounces and, from rr_depth bounces on, continue with probability
// q = min(1, max throughput) and divide by q (Russian roulette: unbiased, cuts long paths).
//
// The light set is every sphere and quad whose material emits (material.hpp: a light, or any
// glowing surface), and the point lights. Spheres are sampled uniformly in the cone of
// directions they fill (every direction from a point inside or on them, so a glowing room
// works); quads uniformly in area. Emission the samplers cannot produce (the background, a shape
// kind without a sampler: planes, triangles, meshes) is always counted when a ray finds it, so
// no integrator loses it. A point light is the opposite: only a light sample can reach it (a
// ray never hits a point), so `naive` renders scenes lit by point lights black there.
#include <zraka/material.hpp>
#include <zraka/rng.hpp>
#include <zraka/scene.hpp>
#include <zraka/spawn.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace zraka {

enum class integrator { naive, nee, mis };

inline const char* name(integrator i) {
  switch (i) {
    case integrator::naive: return "naive";
    case integrator::nee: return "nee";
    case integrator::mis: return "mis";
  }
  return "?";
}

inline integrator parse_integrator(std::string_view s) {
  for (integrator i : {integrator::naive, integrator::nee, integrator::mis})
    if (s == name(i)) return i;
  throw error("unknown integrator '" + std::string(s) + "' (naive, nee, mis)");
}

struct integrator_options {
  integrator method = integrator::mis;
  int max_depth = 8;  // bounces; 0 = only what the camera ray hits (the thesis's depth 1)
  int rr_depth = 3;   // Russian roulette from this many bounces on
};

// ---------------------------------------------------------------- the light set
template <class T> struct light_set_t {
  std::vector<object_ref> lights;
  std::vector<int> sphere_light, quad_light;  // object -> index in lights, or -1
  std::size_t count = 0;  // area lights and point lights: each is picked with probability 1/count

  explicit light_set_t(const scene_t<T>& sc)
      : sphere_light(sc.spheres.size(), -1), quad_light(sc.quads.size(), -1) {
    for (std::size_t i = 0; i < sc.spheres.size(); ++i)
      if (emits(sc.materials[sc.spheres[i].material])) {
        sphere_light[i] = int(lights.size());
        lights.push_back({shape_kind::sphere, int(i)});
      }
    for (std::size_t i = 0; i < sc.quads.size(); ++i)
      if (emits(sc.materials[sc.quads[i].material])) {
        quad_light[i] = int(lights.size());
        lights.push_back({shape_kind::quad, int(i)});
      }
    count = lights.size() + sc.point_lights.size();
  }
  bool contains(object_ref o) const {
    if (o.index < 0) return false;
    if (o.kind == shape_kind::sphere) return sphere_light[std::size_t(o.index)] >= 0;
    if (o.kind == shape_kind::quad) return quad_light[std::size_t(o.index)] >= 0;
    return false;  // a shape kind without a light sampler
  }
};

template <class T> struct emitter_sample_t {
  vec3_t<T> point;  // on the light
  vec3_t<T> wi;     // unit, from the shading point towards it
  T pdf;            // per steradian, including the 1/n choice of the light (point: just 1/n)
  rgb Le;           // emitted towards the shading point (point light: I / d^2)
  bool delta = false;   // a point light: no other technique can find it (MIS weight 1)
  segment_t<T> shadow;  // test it with occluded(): the light is visible if nothing is in the way
};

// [listing sample-emitter]
// One light chosen uniformly, one point on it, as seen from hit h.
template <class T>
std::optional<emitter_sample_t<T>> sample_emitter(const scene_t<T>& sc, const light_set_t<T>& ls,
                                                  const hit_t<T>& h, rng& g) {
  if (ls.count == 0) return std::nullopt;
  const int n = int(ls.count);
  const int i = std::min(int(g.uniform() * n), n - 1);
  const vec2_t<T> u(g.uniform2());
  emitter_sample_t<T> s{};
  if (i >= int(ls.lights.size())) {  // a point light: one direction, chosen with probability 1/n
    const auto& pl = sc.point_lights[std::size_t(i) - ls.lights.size()];
    const vec3_t<T> to = pl.position - h.p;
    s.point = pl.position;
    s.wi = normalize_or_zero(to);
    s.pdf = T(1) / T(n);
    s.Le = pl.intensity / float(length2(to));
    s.delta = true;
    s.shadow = spawn_segment(h, s.point);
    if (s.wi == vec3_t<T>(0) || !is_finite(s.Le)) return std::nullopt;
    return s;
  }
  const object_ref l = ls.lights[std::size_t(i)];
  hit_t<T> lh;  // the light's surface at the sampled point, to ask it what it emits there
  if (l.kind == shape_kind::sphere) {
    const auto& sp = sc.spheres[std::size_t(l.index)].shape;
    const cone_t<T> cone(h.p, sp.center, sp.radius);  // the whole sphere of directions if inside
    s.wi = cone.sample(u);
    const ray_t<T> r = spawn_ray(h, s.wi);
    if (!intersect(sp, r, T(0), infinity<T>, lh)) return std::nullopt;
    s.point = lh.p;
    // The shadow ray is the ray that found the point, stopped just short of it: the same
    // arithmetic cannot find the sphere again before lh.t (a segment to the rounded point
    // could, on a glowing sphere seen from its own inside).
    s.shadow = {r, lh.t * (T(1) - gamma<T>(16))};
    s.pdf = cone.pdf(s.wi) / T(n);
  } else {
    const auto& q = sc.quads[std::size_t(l.index)].shape;
    s.point = q.point(u.x, u.y);
    const vec3_t<T> to = s.point - h.p;
    s.wi = normalize_or_zero(to);
    lh.normal = q.normal();
    lh.set_face(s.wi);
    s.shadow = spawn_segment(h, s.point);
    s.pdf = area_to_solid_angle_pdf(T(1) / q.area(), length2(to), std::abs(glm::dot(lh.normal, s.wi))) / T(n);
  }
  s.Le = emitted(sc.material_of(l), lh);
  if (!(s.pdf > T(0)) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}
// [end]

// The density with which sample_emitter() picks direction wi from x, given that the ray along
// wi first meets light object o at lh (a BSDF-sampled ray): the same two formulas.
template <class T>
T emitter_pdf(const scene_t<T>& sc, const light_set_t<T>& ls, object_ref o, const vec3_t<T>& x,
              const vec3_t<T>& wi, const hit_t<T>& lh) {
  if (!ls.contains(o)) return T(0);
  const T n = T(ls.count);
  if (o.kind == shape_kind::sphere) {
    const auto& sp = sc.spheres[std::size_t(o.index)].shape;
    return cone_t<T>(x, sp.center, sp.radius).pdf(wi) / n;
  }
  const auto& q = sc.quads[std::size_t(o.index)].shape;
  return area_to_solid_angle_pdf(T(1) / q.area(), lh.t * lh.t, std::abs(glm::dot(q.normal(), wi))) / n;
}

// The power heuristic (exponent 2) for a sample of density a, the other technique's being b.
template <class T> T power_heuristic(T a, T b) {
  if (!(a > T(0))) return T(0);
  if (std::isinf(a)) return T(1);
  const T r = b / a;  // a^2 / (a^2 + b^2) without overflowing a^2
  return T(1) / (T(1) + r * r);
}

// Russian roulette: true if the path goes on (then beta has been divided by q).
inline bool survives_roulette(rgb& beta, int bounce, const integrator_options& opt, rng& g) {
  if (bounce < opt.rr_depth) return true;
  const float q = std::min(1.0f, max_component(beta));
  if (!(g.uniform() < q)) return false;
  beta /= q;
  return true;
}

// [listing naive]
// The thesis's loop: accumulated colour and throughput mask, one ray per bounce.
template <class T>
rgb radiance_naive(const scene_t<T>& sc, ray_t<T> r, rng& g, const integrator_options& opt,
                   std::uint64_t& rays) {
  rgb accum(0), mask(1);
  for (int bounce = 0;; ++bounce) {
    scene_hit_t<T> sh;
    ++rays;
    if (!nearest_hit(sc, r, sh)) return accum + mask * sc.background;
    const material& m = sc.materials[std::size_t(sh.material)];
    accum += mask * emitted(m, sh.h);  // whatever light this ray happened to find
    if (bounce == opt.max_depth) return accum;
    const auto s = scatter(m, r.direction, sh.h, g);
    if (!s) return accum;  // absorbed (or a light, which does not reflect)
    mask *= s->weight;     // f cos / pdf: the cosine is counted once, inside the weight
    if (!survives_roulette(mask, bounce, opt, g)) return accum;
    r = spawn_ray(sh.h, s->direction);
  }
}
// [end]

// [listing nee-mis]
// Next-event estimation, alone (nee) or combined with BSDF sampling by MIS (mis).
template <class T>
rgb radiance_nee_mis(const scene_t<T>& sc, const light_set_t<T>& ls, ray_t<T> r, rng& g,
                     const integrator_options& opt, std::uint64_t& rays) {
  const bool mis = opt.method == integrator::mis;
  rgb L(0), beta(1);
  bool specular = true;     // the last bounce had no density (camera rays count as specular)
  T bsdf_pdf = T(0);        // density of the last scattered direction
  vec3_t<T> from(T(0));     // the point it left from
  for (int bounce = 0;; ++bounce) {
    scene_hit_t<T> sh;
    ++rays;
    if (!nearest_hit(sc, r, sh)) return L + beta * sc.background;  // no sampler knows the sky
    const material& m = sc.materials[std::size_t(sh.material)];
    // Emission found by the scattered ray: its full value, its MIS share, or nothing (nee:
    // the light sample at the previous vertex already counted this light).
    if (const rgb Le = emitted(m, sh.h); Le != rgb(0)) {
      if (specular || !ls.contains(sh.object)) L += beta * Le;
      else if (mis) {
        const T p_light = emitter_pdf(sc, ls, sh.object, from, r.direction, sh.h);
        L += beta * Le * float(power_heuristic(bsdf_pdf, p_light));
      }
    }
    if (bounce == opt.max_depth) return L;
    const vec3_t<T> wo = -r.direction;
    if (!is_specular(m) && m.kind != material_kind::emitter) {  // the next event: a light
      if (const auto e = sample_emitter(sc, ls, sh.h, g); e && e->Le != rgb(0)) {
        const rgb f_cos = brdf_cos(m, sh.h, wo, e->wi);
        if (f_cos != rgb(0)) {
          ++rays;
          if (!occluded(sc, e->shadow)) {
            const T w = mis && !e->delta ? power_heuristic(e->pdf, scatter_pdf(m, sh.h, wo, e->wi)) : T(1);
            L += beta * f_cos * e->Le * float(w / e->pdf);
          }
        }
      }
    }
    const auto s = scatter(m, r.direction, sh.h, g);
    if (!s) return L;
    beta *= s->weight;
    specular = s->specular;
    bsdf_pdf = s->pdf;
    from = sh.h.p;
    if (!survives_roulette(beta, bounce, opt, g)) return L;
    r = spawn_ray(sh.h, s->direction);
  }
}
// [end]

// A scene, its lights and the options, ready to give the radiance along a camera ray.
template <class T> struct path_tracer_t {
  const scene_t<T>& sc;
  light_set_t<T> lights;
  integrator_options opt;

  path_tracer_t(const scene_t<T>& scene, const integrator_options& o) : sc(scene), lights(scene), opt(o) {
    if (o.max_depth < 0) throw error("the maximum depth must not be negative, got " + std::to_string(o.max_depth));
    if (o.rr_depth < 0) throw error("the Russian roulette depth must not be negative");
  }
  rgb operator()(const ray_t<T>& r, rng& g, std::uint64_t& rays) const {
    return opt.method == integrator::naive ? radiance_naive(sc, r, g, opt, rays)
                                           : radiance_nee_mis(sc, lights, r, g, opt, rays);
  }
};

using light_set = light_set_t<double>;
using path_tracer = path_tracer_t<double>;

}  // namespace zraka

#pragma once
// The lights of a scene, written once for every renderer (book 2.2, 2.3, 5.3): which objects
// are lights, how one is chosen, how a point on it is sampled, and the density of that choice.
//
// A light is every object whose material emits (material.hpp: an emitter, or any glowing
// surface; two-sided ones from both faces) and every light of scene.lights, the kinds that are
// not shapes (lights/light.hpp: point lights, a course's own). Each is sampled as seen from a
// shading point x, and the density is per steradian at x:
//   sphere     uniform in the cone of directions that see it; from inside, every direction
//              (each meets the sphere once), so a glowing room works;
//   quad, triangle, user shape with area sampling
//              uniform in area, p_A = 1/A, turned into solid angle: p = p_A d^2 / |cos theta_l|;
//   mesh       a triangle chosen by area, then uniform on it: again p_A = 1/A of the whole mesh;
//   point      one direction: a delta, pdf 1 (times the choice), Le = I / d^2; every kind of
//              lights/light.hpp samples itself so (its file: point.hpp, a course's custom_light).
//   environment the scene's environment map (environment.hpp), sampled by its own distribution
//              over directions; the shadow ray goes to infinity. Its power is estimated as
//              pi R^2 times the integral of its radiance, R the radius of the scene's bounds.
// Emission that cannot be sampled is counted only where a ray finds it ("hit only"): an
// infinite plane (no finite area to pick a point on), a user shape that gives no area sampling,
// and the plain background colour. describe() names them, so the choice is never silent.
//
// Lights are chosen in proportion to their power (emitted flux: mean radiance x area x pi, twice
// that when two-sided; 4 pi I for a point light, any kind of light.hpp its own power()), or
// uniformly (light_selection::uniform, for comparison: bench/pathtrace_bench measures what
// choosing by power buys).
#include <zraka/core/compiled.hpp>
#include <zraka/core/enum_names.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/lights/light.hpp>
#include <zraka/lights/light_sample.hpp>
#include <zraka/sampling/sampling.hpp>
#include <zraka/scene/scene.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace zraka {

enum class light_selection { power, uniform };
inline constexpr enum_name<light_selection> light_selection_names[] = {{light_selection::power, "power"},
                                                                       {light_selection::uniform, "uniform"}};
constexpr std::span<const enum_name<light_selection>> enum_names(light_selection) { return light_selection_names; }  // enum_names.hpp

// ---------------------------------------------------------------- emission sampling (book 6.2)
// Light leaving the lights, for renderers that start paths there (bidirectional path tracing,
// photon mapping): a point on a light chosen by power, and a direction it leaves in
// (emission_sample_t, lights/light_sample.hpp). The position density is per unit area (times the
// choice of the light); the direction density is per steradian, cosine-weighted from the
// emitting face (from either face, each with probability 1/2, when two-sided). A light that is
// not a shape has a delta position (pdf_position is then the probability of choosing it) and
// leaves as its kind samples (a point light: uniformly over the sphere).
template <class T> class light_set_t {
 public:
  struct light {
    object_ref object{shape_kind::sphere, -1};  // an area light; index -1 for a light of scene.lights
    int point = -1;                             // a light that is not a shape: index in scene.lights
    double power = 0;                           // emitted flux (mean over the channels)
    T area = T(0);                              // area lights
    std::uint32_t first = 0, count = 0;         // meshes: their triangles' range in the area table
    bool environment = false;                   // the environment light (scene.environment)
  };

  explicit light_set_t(const scene_t<T>& sc, light_selection sel = light_selection::power);

  std::size_t size() const { return lights_.size(); }
  bool empty() const { return lights_.empty(); }
  const std::vector<light>& lights() const { return lights_; }
  light_selection selection() const { return selection_; }
  // Emitters that are counted only when a ray hits them (see the top of this file).
  const std::vector<std::string>& hit_only() const { return hit_only_; }
  // Meshes: their triangles' areas, summed, count + 1 entries from light.first (the GPU kernel
  // packs them as they are: gpu_scene.hpp).
  const std::vector<double>& triangle_cdf() const { return triangle_cdf_; }

  // The probability of choosing light i.
  T selection_pdf(int i) const { return T(weight(lights_[std::size_t(i)]) / total_); }
  // The light index of an object, or -1 if the object is not a sampled light.
  int index_of(object_ref o) const {
    if (o.index < 0) return -1;
    const auto& v = index_[kind(o.kind)];
    return std::size_t(o.index) < v.size() ? v[std::size_t(o.index)] : -1;
  }

  // [listing sample-light]
  // One light chosen by u_select (by power or uniformly), one point on it by u, seen from hit h
  // (a point with p_error 0 and no normal will do). pdf includes the choice.
  std::optional<light_sample_t<T>> sample(const hit_t<T>& h, T u_select, const vec2_t<T>& u) const {
    if (lights_.empty()) return std::nullopt;
    const double x = double(clamp_unit(u_select)) * total_;
    const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), x);
    const int i = std::min(int(it - cdf_.begin()) - 1, int(lights_.size()) - 1);
    auto s = sample_one(i, h, u);
    if (!s) return s;
    s->pdf *= selection_pdf(i);
    if (!(s->pdf > T(0)) || !std::isfinite(s->pdf)) return std::nullopt;
    return s;
  }
  // [end]

  // A point on light i, seen from hit h; pdf without the choice of the light (Whitted samples
  // every light).
  std::optional<light_sample_t<T>> sample_one(int i, const hit_t<T>& h, const vec2_t<T>& u) const;

  // [listing light-pdf]
  // The density with which sample() produces direction wi from x, given that the ray along wi
  // first meets object o at lh (a BSDF-sampled ray that found a light): 0 if o is not sampled.
  T pdf(object_ref o, const vec3_t<T>& x, const vec3_t<T>& wi, const hit_t<T>& lh) const {
    const int i = index_of(o);
    if (i < 0) return T(0);
    const light& l = lights_[std::size_t(i)];
    if (o.kind == shape_kind::sphere) {
      const sphere_t<T>& sp = sc_.spheres[std::size_t(o.index)].shape;
      return cone_t<T>(x, sp.center, sp.radius).pdf(wi) * selection_pdf(i);
    }
    return area_to_solid_angle_pdf(T(1) / l.area, lh.t * lh.t, glm::dot(lh.normal, wi)) * selection_pdf(i);
  }
  // [end]

  // ---------------------------------------------------------------- the environment light
  // Its index in the light set, or -1 (no environment, or one that is black).
  int environment_index() const { return environment_; }
  bool is_environment(int i) const { return i >= 0 && i == environment_; }
  // The density with which sample() produces direction wi towards the environment (a
  // BSDF-sampled ray that left the scene), the choice of the light included.
  T environment_pdf(const vec3_t<T>& wi) const {
    if (environment_ < 0) return T(0);
    return sc_.environment->pdf(wi) * selection_pdf(environment_);
  }
  // The radius of the scene's bounds (the finite objects; at least 1e-3), for the power estimate.
  T scene_radius() const { return radius_; }

  // "lights: 2 (1 quad, 1 point light), chosen by power; hit only: plane 0"
  std::string describe() const;

  // ------------------------------------------------------------ emission sampling (book 6.2)
  // One light chosen by u_select (as sample() chooses), a point on it by u_pos (uniform in
  // area; a sphere's too), a direction leaving it by u_dir.
  std::optional<emission_sample_t<T>> sample_emission(T u_select, const vec2_t<T>& u_pos,
                                                      const vec2_t<T>& u_dir) const;

  // The density per unit area (times the choice) with which sample_emission() picks a point on
  // light i; for a point light, the probability of choosing it.
  T pdf_emission_position(int i) const {
    const light& l = lights_[std::size_t(i)];
    return l.point >= 0 ? selection_pdf(i) : selection_pdf(i) / l.area;
  }
  // The density per steradian of leaving light i along w from a point with outward normal n.
  T pdf_emission_direction(int i, const vec3_t<T>& n, const vec3_t<T>& w) const {
    const light& l = lights_[std::size_t(i)];
    if (l.point >= 0) return light_pdf_emission_direction(sc_.lights[std::size_t(l.point)], w);
    const T c = glm::dot(n, w);
    if (sc_.material_of(l.object).two_sided) return std::abs(c) / (T(2) * pi<T>);
    return c > T(0) ? c / pi<T> : T(0);
  }
  // The intensity light i, one that is not a shape, sends along w.
  rgb intensity_towards(int i, const vec3_t<T>& w) const {
    return light_intensity_towards(sc_.lights[std::size_t(lights_[std::size_t(i)].point)], w);
  }
  // The radiance a glowing material sends along w from a point with outward normal n.
  static rgb emitted_towards(const material& m, const vec3_t<T>& n, const vec3_t<T>& w) {
    hit_t<T> h;
    h.normal = n;
    h.set_face(-w);  // as seen by a ray arriving along -w
    return emitted(m, h);
  }

 private:
  static std::size_t kind(shape_kind k) { return std::size_t(k); }
  static double mean(const rgb& c) { return (double(c.x) + double(c.y) + double(c.z)) / 3.0; }
  double weight(const light& l) const { return selection_ == light_selection::power ? l.power : 1.0; }

  void add_object(object_ref o);

  // A point uniform in area on light l: a sphere's over its whole surface (emission sampling).
  std::optional<surface_point_t<T>> emission_point(const light& l, const vec2_t<T>& u) const {
    if (l.object.kind != shape_kind::sphere) return sample_surface(l, u);
    const sphere_t<T>& sp = sc_.spheres[std::size_t(l.object.index)].shape;
    const vec3_t<T> n = sample_uniform_sphere(u);
    const vec3_t<T> on = sp.radius * n;
    const vec3_t<T> p = sp.center + on;
    return surface_point_t<T>{p, n, gamma<T>(6) * (abs3(on) + abs3(p))};
  }

  // A point uniform in area on light l (not a sphere, not a point light).
  std::optional<surface_point_t<T>> sample_surface(const light& l, const vec2_t<T>& u) const;
  static std::optional<surface_point_t<T>> on_triangle(const triangle_t<T>& t, const vec2_t<T>& u, T g) {
    const vec2_t<T> b = sample_triangle_barycentric(u);
    const T w = T(1) - b.x - b.y;
    const vec3_t<T> p = w * t.a + b.x * t.b + b.y * t.c;
    return surface_point_t<T>{p, t.normal(), g * (abs3(w * t.a) + abs3(b.x * t.b) + abs3(b.y * t.c))};
  }

  // The environment as one more light (the top of this file).
  void add_environment();
  std::optional<light_sample_t<T>> sample_environment(int i, const hit_t<T>& h, const vec2_t<T>& u) const;

  const scene_t<T>& sc_;
  light_selection selection_;
  std::vector<light> lights_;
  std::vector<double> cdf_;           // selection weights, summed: cdf_[i + 1] - cdf_[i] = weight(i)
  double total_ = 0;
  std::vector<double> triangle_cdf_;  // meshes: their triangles' areas, summed (count + 1 entries each)
  std::array<std::vector<int>, 6> index_;  // per shape kind: object index -> light index, or -1
  std::vector<std::string> hit_only_;
  int environment_ = -1;     // the environment light's index, or -1
  T radius_ = T(1);          // the scene's bounding sphere (for the environment's power)
  vec3_t<T> centre_{T(0)};
};

template <class T>
light_set_t<T>::light_set_t(const scene_t<T>& sc, light_selection sel) : sc_(sc), selection_(sel) {
  index_[kind(shape_kind::sphere)].assign(sc.spheres.size(), -1);
  index_[kind(shape_kind::quad)].assign(sc.quads.size(), -1);
  index_[kind(shape_kind::plane)].assign(sc.planes.size(), -1);
  index_[kind(shape_kind::triangle)].assign(sc.triangles.size(), -1);
  index_[kind(shape_kind::mesh)].assign(sc.meshes.size(), -1);
  index_[kind(shape_kind::user)].assign(sc.user_shapes.size(), -1);
  for_each_object(sc, [&](object_ref o) { add_object(o); });
  for (std::size_t i = 0; i < sc.lights.size(); ++i) {
    light l;
    l.point = int(i);
    l.power = light_power(sc.lights[i]);
    if (!std::isfinite(l.power))
      throw error("lights: " + light_type(sc.lights[i]) + " light " + std::to_string(i) + " has a non-finite intensity");
    if (l.power > 0) lights_.push_back(l);
  }
  add_environment();
  double total = 0;
  cdf_.assign(1, 0.0);
  for (const light& l : lights_) cdf_.push_back(total += weight(l));
  total_ = total;
}

// [listing sample-one-light]
// A point on light i, seen from hit h; pdf without the choice of the light (Whitted samples
// every light).
template <class T>
std::optional<light_sample_t<T>> light_set_t<T>::sample_one(int i, const hit_t<T>& h, const vec2_t<T>& u) const {
  const light& l = lights_[std::size_t(i)];
  if (l.environment) return sample_environment(i, h, u);
  if (l.point >= 0) {  // a kind of lights/light.hpp: one direction, a delta (pdf 1)
    auto s = sample_light(sc_.lights[std::size_t(l.point)], h);
    if (s) s->light = i;
    return s;
  }
  light_sample_t<T> s;
  s.light = i;
  const material& m = sc_.material_of(l.object);
  hit_t<T> lh;  // the light's surface at the sampled point: its side decides what it emits
  if (l.object.kind == shape_kind::sphere) {
    const sphere_t<T>& sp = sc_.spheres[std::size_t(l.object.index)].shape;
    const cone_t<T> cone(h.p, sp.center, sp.radius);  // every direction from inside
    s.wi = cone.sample(u);
    const ray_t<T> r = spawn_ray(h, s.wi);
    if (!intersect(sp, r, T(0), infinity<T>, lh)) return std::nullopt;
    s.point = lh.p;
    // The shadow ray is the ray that found the point, stopped just short of it: the same
    // arithmetic cannot find the sphere again before lh.t (a segment to the rounded point
    // could, on a glowing sphere seen from its own inside).
    s.shadow = {r, lh.t * (T(1) - gamma<T>(16))};
    s.pdf = cone.pdf(s.wi);
  } else {
    const auto sp = sample_surface(l, u);
    if (!sp) return std::nullopt;
    const vec3_t<T> to = sp->p - h.p;
    s.point = sp->p;
    s.wi = normalize_or_zero(to);
    lh.normal = sp->normal;
    lh.set_face(s.wi);
    const T cos_l = std::abs(glm::dot(sp->normal, s.wi));
    s.pdf = area_to_solid_angle_pdf(T(1) / l.area, length2(to), cos_l);
    s.shadow = spawn_segment(h, s.point);
    // Stop short of the light's own surface by its rounding too, measured along the ray:
    // meshes are tested in float, so a float hit on the light itself may come a little early.
    s.shadow.t_max -= glm::dot(abs3(sp->normal), sp->p_error) / std::max(cos_l, T(1e-30));
  }
  s.Le = emitted(m, lh);
  if (!(s.pdf > T(0)) || !std::isfinite(s.pdf) || s.wi == vec3_t<T>(0)) return std::nullopt;
  return s;
}
// [end]

template <class T>
std::string light_set_t<T>::describe() const {
  std::array<int, 6> per_kind{};
  std::vector<std::pair<std::string, int>> others;  // the kinds of scene.lights, in order of appearance
  for (const light& l : lights_)
    if (l.point >= 0) {
      const std::string t = light_type(sc_.lights[std::size_t(l.point)]);
      auto it = std::find_if(others.begin(), others.end(), [&](const auto& o) { return o.first == t; });
      if (it == others.end()) others.emplace_back(t, 1);
      else ++it->second;
    } else if (!l.environment) {
      ++per_kind[kind(l.object.kind)];
    }
  static const char* names[] = {"sphere", "quad", "plane", "triangle", "mesh", "user shape"};
  std::string out = "lights: " + std::to_string(lights_.size());
  std::string parts;
  auto part = [&](int n, const std::string& what) {
    if (n == 0) return;
    parts += (parts.empty() ? "" : ", ") + std::to_string(n) + " " + what + (n == 1 ? "" : "s");
  };
  for (int k = 0; k < 6; ++k) part(per_kind[std::size_t(k)], names[k]);
  for (const auto& [t, n] : others) part(n, t + " light");
  if (environment_ >= 0) part(1, std::string(sc_.environment->is_constant() ? "constant" : "map") + " environment");
  if (!parts.empty()) out += " (" + parts + ")";
  out += selection_ == light_selection::power ? ", chosen by power" : ", chosen uniformly";
  if (!hit_only_.empty()) {
    out += "; hit only:";
    for (std::size_t i = 0; i < hit_only_.size(); ++i) out += (i ? ", " : " ") + hit_only_[i];
  }
  return out;
}

// [listing sample-emission]
// One light chosen by u_select (as sample() chooses), a point on it by u_pos (uniform in
// area; a sphere's too), a direction leaving it by u_dir.
template <class T>
std::optional<emission_sample_t<T>> light_set_t<T>::sample_emission(T u_select, const vec2_t<T>& u_pos,
                                                                    const vec2_t<T>& u_dir) const {
  if (lights_.empty()) return std::nullopt;
  const double x = double(clamp_unit(u_select)) * total_;
  const auto it = std::upper_bound(cdf_.begin() + 1, cdf_.end(), x);
  const int i = std::min(int(it - cdf_.begin()) - 1, int(lights_.size()) - 1);
  const light& l = lights_[std::size_t(i)];
  emission_sample_t<T> e;
  e.light = i;
  if (l.point >= 0) {  // a delta in position, a direction as its kind samples (lights/light.hpp)
    e = sample_light_emission(sc_.lights[std::size_t(l.point)], u_dir);
    e.light = i;
    e.pdf_position = selection_pdf(i);
    return e;
  }
  const auto sp = emission_point(l, u_pos);
  if (!sp) return std::nullopt;
  e.point = sp->p;
  e.normal = sp->normal;
  e.p_error = sp->p_error;
  const material& m = sc_.material_of(l.object);
  // Two-sided: u_dir.x picks the face (and is stretched back to [0,1) on it).
  vec2_t<T> u = u_dir;
  vec3_t<T> n = sp->normal;
  if (m.two_sided) {
    const T ux = clamp_unit(u.x) * T(2);
    if (ux >= T(1)) n = -n;
    u.x = ux >= T(1) ? ux - T(1) : ux;
  }
  e.direction = cosine_hemisphere_t<T>(n).sample(u);
  e.pdf_position = selection_pdf(i) / l.area;
  e.pdf_direction = pdf_emission_direction(i, e.normal, e.direction);
  e.Le = emitted_towards(m, e.normal, e.direction);
  if (!(e.pdf_position > T(0)) || !(e.pdf_direction > T(0)) || !std::isfinite(e.pdf_position)) return std::nullopt;
  return e;
}
// [end]

template <class T>
void light_set_t<T>::add_object(object_ref o) {
  const material& m = sc_.material_of(o);
  if (!emits(m)) return;
  light l;
  l.object = o;
  switch (o.kind) {
    case shape_kind::sphere: {
      const T r = sc_.spheres[std::size_t(o.index)].shape.radius;
      l.area = T(4) * pi<T> * r * r;
      break;
    }
    case shape_kind::quad: l.area = sc_.quads[std::size_t(o.index)].shape.area(); break;
    case shape_kind::triangle: l.area = sc_.triangles[std::size_t(o.index)].shape.area(); break;
    case shape_kind::mesh: {
      const mesh_t<T>& mesh = sc_.meshes[std::size_t(o.index)].shape;
      l.first = std::uint32_t(triangle_cdf_.size());
      l.count = std::uint32_t(mesh.triangle_count());
      double a = 0;
      for (std::size_t k = 0; k < mesh.triangle_count(); ++k) {
        triangle_cdf_.push_back(a);
        a += double(mesh.triangle(k).area());
      }
      triangle_cdf_.push_back(a);
      l.area = T(a);
      break;
    }
    case shape_kind::user: {
      const auto& us = *sc_.user_shapes[std::size_t(o.index)].shape;
      l.area = us.area();
      if (!(l.area > T(0))) {
        hit_only_.push_back("user shape '" + us.name() + "' " + std::to_string(o.index) + " (no area sampling)");
        return;
      }
      break;
    }
    case shape_kind::plane:
      hit_only_.push_back("plane " + std::to_string(o.index) + " (infinite)");
      return;
  }
  if (!(l.area > T(0)) || !std::isfinite(l.area)) return;  // degenerate: never hit either
  l.power = mean(m.radiance) * double(l.area) * pi<double> * (m.two_sided ? 2.0 : 1.0);
  if (!std::isfinite(l.power) || !is_finite(m.radiance) || m.radiance.x < 0 || m.radiance.y < 0 || m.radiance.z < 0)
    throw error("lights: " + sc_.material_label(sc_.material_index(o)) +
                " glows with a negative or non-finite radiance, or on a shape of infinite area");
  index_[kind(o.kind)][std::size_t(o.index)] = int(lights_.size());
  lights_.push_back(l);
}

template <class T>
std::optional<surface_point_t<T>> light_set_t<T>::sample_surface(const light& l, const vec2_t<T>& u) const {
  const auto i = std::size_t(l.object.index);
  switch (l.object.kind) {
    case shape_kind::quad: {
      const auto& q = sc_.quads[i].shape;
      const T a = clamp_unit(u.x), b = clamp_unit(u.y);
      const vec3_t<T> n = i < sc_.accel.quad_planes.size() ? sc_.accel.quad_planes[i].N : q.normal();  // the same bits
      return surface_point_t<T>{q.point(a, b), n,
                                gamma<T>(4) * (abs3(q.corner) + abs3(a * q.u) + abs3(b * q.v))};
    }
    case shape_kind::triangle: return on_triangle(sc_.triangles[i].shape, u, gamma<T>(7));
    case shape_kind::mesh: {
      // The triangle by area: u.x picks it, and is stretched back to [0,1) inside it.
      const double* c = triangle_cdf_.data() + l.first;
      const double x = double(clamp_unit(u.x)) * c[l.count];
      const std::uint32_t k = std::min<std::uint32_t>(
          std::uint32_t(std::upper_bound(c + 1, c + l.count + 1, x) - (c + 1)), l.count - 1);
      const double width = c[k + 1] - c[k];
      const T ux = width > 0 ? clamp_unit(T((x - c[k]) / width)) : T(0);
      const auto& mesh = sc_.meshes[i].shape;
      // The mesh is tested in float: its hits are as uncertain as scene.hpp's mesh hits.
      return on_triangle(mesh.triangle(k), vec2_t<T>(ux, u.y), T(gamma<float>(64)));
    }
    case shape_kind::user: return sc_.user_shapes[i].shape->sample_area(u);
    case shape_kind::sphere:
    case shape_kind::plane: break;
  }
  return std::nullopt;
}

template <class T>
void light_set_t<T>::add_environment() {
  if (!sc_.environment) return;
  aabb_t<T> box;
  for_each_object(sc_, [&](object_ref o) {
    const aabb_t<T> b = object_bounds(sc_, o);
    if (!b.empty() && is_finite(b.lo) && is_finite(b.hi)) box.grow(b);
  });
  radius_ = box.empty() ? T(1) : std::max(T(glm::length(box.hi - box.lo) / T(2)), T(1e-3));
  centre_ = box.empty() ? vec3_t<T>(0) : (box.lo + box.hi) / T(2);
  light l;
  l.environment = true;
  l.power = pi<double> * double(radius_) * double(radius_) * sc_.environment->integral();
  if (!std::isfinite(l.power)) throw error("lights: the environment " + sc_.environment->name() + " has infinite power");
  if (!(l.power > 0)) return;  // black: nothing to sample (rays that leave still see it)
  environment_ = int(lights_.size());
  lights_.push_back(l);
}

// [listing sample-environment]
template <class T>
std::optional<light_sample_t<T>> light_set_t<T>::sample_environment(int i, const hit_t<T>& h,
                                                                    const vec2_t<T>& u) const {
  light_sample_t<T> s;
  s.light = i;
  s.wi = sc_.environment->sample(u, s.pdf);
  if (!(s.pdf > T(0)) || !std::isfinite(s.pdf)) return std::nullopt;
  s.Le = sc_.environment->radiance(s.wi);
  // A point beyond the scene's bounds in that direction (for whoever needs one); the shadow
  // ray itself never ends: anything in the way occludes.
  s.point = h.p + s.wi * (T(2) * radius_ + glm::length(h.p - centre_));
  s.shadow = {spawn_ray(h, s.wi), infinity<T>};
  return s;
}
// [end]

using light_set = light_set_t<double>;

ZRAKA_INSTANCE(class light_set_t<double>)  // compiled.hpp

}  // namespace zraka

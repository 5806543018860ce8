#pragma once
// A scene described in code (book 2.2, 2.3, 4.1): materials, spheres and quads that name their
// material by index, the lights (every object whose material emits), a background colour, the
// camera and the render settings (the thesis's "hyper-parameters", Def 4.1.1). A scene file
// loader fills the same struct.
//
// Geometry queries go through two functions only, nearest_hit() and occluded(). Here they test
// every object (brute force, fine for the few objects of the course's first scenes); a BVH can
// replace their insides later and address objects through the same object_ref and
// intersect_object(), without changing any renderer.
#include <zraka/camera.hpp>
#include <zraka/material.hpp>
#include <zraka/quad.hpp>
#include <zraka/sampling.hpp>
#include <zraka/spawn.hpp>
#include <zraka/sphere.hpp>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace zraka {

// Def 4.1.1's hyper-parameters.
struct render_settings {
  int width = 320, height = 240;
  int spp = 16;          // samples (primary rays) per pixel
  int max_depth = 8;     // bounces before a path stops
  std::uint64_t seed = 1;
};

enum class shape_kind { sphere, quad };
struct object_ref {
  shape_kind kind;
  int index;  // into scene.spheres or scene.quads
};

template <class T> struct scene_t {
  struct sphere_object {
    sphere_t<T> shape;
    int material;
  };
  struct quad_object {
    parallelogram_t<T> shape;
    int material;
  };

  std::vector<material> materials;
  std::vector<sphere_object> spheres;
  std::vector<quad_object> quads;
  std::vector<object_ref> lights;  // kept up to date by add()
  rgb background{0};               // radiance of rays that leave the scene
  camera_t<T> camera;
  render_settings settings;

  int add_material(const material& m) {
    materials.push_back(m);
    return static_cast<int>(materials.size()) - 1;
  }
  object_ref add(const sphere_t<T>& s, int mat) {
    check_material(mat);
    spheres.push_back({s, mat});
    return note_light({shape_kind::sphere, static_cast<int>(spheres.size()) - 1}, mat);
  }
  object_ref add(const parallelogram_t<T>& q, int mat) {
    check_material(mat);
    quads.push_back({q, mat});
    return note_light({shape_kind::quad, static_cast<int>(quads.size()) - 1}, mat);
  }
  const material& material_of(object_ref o) const {
    return materials[o.kind == shape_kind::sphere ? spheres[o.index].material : quads[o.index].material];
  }
  // The camera with the image's aspect ratio, ready to generate rays.
  typename camera_t<T>::prepared prepared_camera() const {
    camera_t<T> c = camera;
    c.aspect = T(settings.width) / T(settings.height);
    return c.prepare();
  }

 private:
  void check_material(int mat) const {
    if (mat < 0 || mat >= static_cast<int>(materials.size()))
      throw error("material index " + std::to_string(mat) + " does not exist");
  }
  object_ref note_light(object_ref o, int mat) {
    if (materials[mat].kind == material_kind::emitter) lights.push_back(o);
    return o;
  }
};

using scene = scene_t<double>;

template <class T> struct scene_hit_t {
  hit_t<T> h;
  int material = -1;
  object_ref object{shape_kind::sphere, -1};
};
using scene_hit = scene_hit_t<double>;

// One object's own intersection test, the building block for brute force and for a BVH.
template <class T>
bool intersect_object(const scene_t<T>& sc, object_ref o, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& h) {
  return o.kind == shape_kind::sphere ? intersect(sc.spheres[o.index].shape, r, t_min, t_max, h)
                                      : intersect(sc.quads[o.index].shape, r, t_min, t_max, h);
}

// [listing nearest-hit]
// The nearest hit along r with t in (0, t_max): each hit found shrinks the interval, so the
// result is the minimum over all objects whatever their order.
template <class T>
bool nearest_hit(const scene_t<T>& sc, const ray_t<T>& r, scene_hit_t<T>& out, T t_max = infinity<T>) {
  bool found = false;
  auto visit = [&](object_ref o, int mat) {
    if (intersect_object(sc, o, r, T(0), t_max, out.h)) {
      found = true;
      t_max = out.h.t;
      out.material = mat;
      out.object = o;
    }
  };
  for (int i = 0; i < static_cast<int>(sc.spheres.size()); ++i) visit({shape_kind::sphere, i}, sc.spheres[i].material);
  for (int i = 0; i < static_cast<int>(sc.quads.size()); ++i) visit({shape_kind::quad, i}, sc.quads[i].material);
  return found;
}
// [end]

// Is anything in the way along a shadow segment (spawn.hpp)?
template <class T> bool occluded(const scene_t<T>& sc, const segment_t<T>& s) {
  for (const auto& o : sc.spheres)
    if (occludes(o.shape, s.ray, T(0), s.t_max)) return true;
  for (const auto& o : sc.quads)
    if (occludes(o.shape, s.ray, T(0), s.t_max)) return true;
  return false;
}

// ---------------------------------------------------------------- lights (next-event estimation)
template <class T> struct light_sample_t {
  vec3_t<T> point;   // on the light
  vec3_t<T> wi;      // unit, from the shading point towards `point`
  T pdf;             // per steradian at the shading point, including the choice of this light
  rgb radiance;      // emitted towards the shading point (0 from a quad light's back)
  object_ref light;
};

// The density (per steradian) with which one light's sampler produces direction wi from x;
// zero if wi misses it. Quads: uniform in area, converted to solid angle. Spheres: uniform in
// the cone of directions that see the sphere (sampling.hpp).
template <class T>
T light_direction_pdf(const scene_t<T>& sc, object_ref l, const vec3_t<T>& x, const vec3_t<T>& wi) {
  if (l.kind == shape_kind::sphere) {
    const auto& s = sc.spheres[l.index].shape;
    return cone_t<T>(x, s.center, s.radius).pdf(wi);
  }
  const auto& q = sc.quads[l.index].shape;
  hit_t<T> h;
  if (!intersect(q, ray_t<T>(x, wi), T(0), infinity<T>, h)) return T(0);
  return area_to_solid_angle_pdf(T(1) / q.area(), h.t * h.t, glm::dot(h.normal, wi));
}

// [listing sample-light]
// Picks one light uniformly and a point on it, seen from the shading point x. The caller tests
// visibility with occluded(sc, spawn_segment(hit, sample.point)).
// u_light picks the light, u the point: both uniform in [0,1) (stratified if the caller likes).
template <class T>
std::optional<light_sample_t<T>> sample_light(const scene_t<T>& sc, const vec3_t<T>& x, T u_light,
                                              const vec2_t<T>& u) {
  if (sc.lights.empty()) return std::nullopt;
  const int n = static_cast<int>(sc.lights.size());
  const object_ref l = sc.lights[std::clamp(static_cast<int>(u_light * T(n)), 0, n - 1)];
  const rgb Le = sc.material_of(l).radiance;
  light_sample_t<T> s{};
  s.light = l;
  if (l.kind == shape_kind::quad) {
    const auto& q = sc.quads[l.index].shape;
    s.point = sample_parallelogram(u, q.corner, q.u, q.v);
    const vec3_t<T> to = s.point - x;
    const T d2 = length2(to);
    s.wi = normalize_or_zero(to);
    const T cos_l = -glm::dot(q.normal(), s.wi);  // > 0: x sees the light's front
    s.pdf = area_to_solid_angle_pdf(T(1) / q.area(), d2, cos_l) / T(n);
    s.radiance = cos_l > T(0) ? Le : rgb(0);
  } else {
    const auto& sp = sc.spheres[l.index].shape;
    const cone_t<T> cone(x, sp.center, sp.radius);
    s.wi = cone.sample(u);
    hit_t<T> h;  // the point where that direction meets the sphere
    if (!intersect(sp, ray_t<T>(x, s.wi), T(0), infinity<T>, h)) return std::nullopt;
    s.point = h.p;
    s.pdf = cone.pdf(s.wi) / T(n);
    s.radiance = h.front_face ? Le : rgb(0);
  }
  if (!(s.pdf > T(0)) || !std::isfinite(s.pdf)) return std::nullopt;
  return s;
}
// [end]

template <class T>
std::optional<light_sample_t<T>> sample_light(const scene_t<T>& sc, const vec3_t<T>& x, rng& g) {
  const T u_light = T(g.uniform());
  return sample_light(sc, x, u_light, vec2_t<T>(g.uniform2()));
}

// The density with which sample_light() produces wi from x, summed over the lights (for MIS).
template <class T> T light_pdf(const scene_t<T>& sc, const vec3_t<T>& x, const vec3_t<T>& wi) {
  if (sc.lights.empty()) return T(0);
  T sum = 0;
  for (object_ref l : sc.lights) sum += light_direction_pdf(sc, l, x, wi);
  return sum / T(sc.lights.size());
}

}  // namespace zraka

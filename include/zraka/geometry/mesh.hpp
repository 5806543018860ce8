#pragma once
// An indexed triangle mesh with a unit normal per vertex (book 1.4): the tessellated teapot,
// later the OBJ models. Triangles are counter-clockwise seen from the side their geometric normal
// points to. Intersection here is brute force (every triangle); the BVH of book 5.2 replaces it.
#include <zraka/geometry/aabb.hpp>
#include <zraka/geometry/triangle.hpp>

#include <array>
#include <cstdint>
#include <vector>

namespace zraka {

template <class T> struct mesh_t {
  std::vector<vec3_t<T>> positions;
  std::vector<vec3_t<T>> normals;  // one unit normal per position
  std::vector<vec2_t<T>> texcoords;  // none, or one (u, v) per position: OBJ vt, a patch's (u, v)
  std::vector<std::array<std::uint32_t, 3>> triangles;

  std::size_t triangle_count() const { return triangles.size(); }
  triangle_t<T> triangle(std::size_t i) const {
    const auto& f = triangles[i];
    return {positions[f[0]], positions[f[1]], positions[f[2]]};
  }
  // The texture coordinates at barycentrics (u, v), interpolated like the point; the barycentrics
  // themselves when the mesh has none.
  vec2_t<T> texcoord(std::size_t i, T u, T v) const {
    if (texcoords.size() != positions.size()) return {u, v};
    const auto& f = triangles[i];
    return (T(1) - u - v) * texcoords[f[0]] + u * texcoords[f[1]] + v * texcoords[f[2]];
  }
  // The shading normal at barycentrics (u, v): the vertex normals interpolated like the point
  // (P = (1-u-v) A + u B + v C) and renormalised. Where they cancel (opposite vertex normals),
  // the triangle's own normal is used, so the result is always unit length.
  vec3_t<T> shading_normal(std::size_t i, T u, T v) const {
    const auto& f = triangles[i];
    const vec3_t<T> n = (T(1) - u - v) * normals[f[0]] + u * normals[f[1]] + v * normals[f[2]];
    const vec3_t<T> s = normalize_or_zero(n);
    return s != vec3_t<T>(0) ? s : triangle(i).normal();
  }
  aabb_t<T> bounds() const {
    aabb_t<T> b;
    for (const auto& p : positions) b.grow(p);
    return b;
  }
  aabb_t<T> bounds(std::size_t first, std::size_t last) const {  // of triangles [first, last)
    aabb_t<T> b;
    for (std::size_t i = first; i < last; ++i)
      for (const std::uint32_t k : triangles[i]) b.grow(positions[k]);
    return b;
  }
};

using mesh = mesh_t<double>;

// What a mesh hit adds to hit_t: the interpolated shading normal (for colour and lighting) and
// the triangle's index. hit_t::normal stays the geometric normal (for spawning rays).
template <class T> struct mesh_shading_t {
  vec3_t<T> normal{T(0)};
  std::size_t triangle = 0;
};

// [listing mesh-intersect]
// The nearest hit among triangles [first, last) with t in (t_min, t_max): every triangle test
// that hits shrinks t_max, so the last hit recorded is the nearest.
template <class T> bool intersect(const mesh_t<T>& m, std::size_t first, std::size_t last,
                                  const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec,
                                  mesh_shading_t<T>& shading) {
  bool found = false;
  for (std::size_t i = first; i < last; ++i)
    if (intersect(m.triangle(i), r, t_min, t_max, rec)) {
      found = true;
      t_max = rec.t;
      shading.triangle = i;
    }
  if (found) shading.normal = m.shading_normal(shading.triangle, rec.uv.x, rec.uv.y);
  return found;
}
// [end]

template <class T> bool intersect(const mesh_t<T>& m, const ray_t<T>& r, T t_min, T t_max,
                                  hit_t<T>& rec, mesh_shading_t<T>& shading) {
  return intersect(m, 0, m.triangle_count(), r, t_min, t_max, rec, shading);
}

template <class T>
bool intersect(const mesh_t<T>& m, const ray_t<T>& r, T t_min, T t_max, hit_t<T>& rec) {
  mesh_shading_t<T> ignored;
  return intersect(m, r, t_min, t_max, rec, ignored);
}

}  // namespace zraka

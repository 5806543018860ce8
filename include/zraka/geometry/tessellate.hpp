#pragma once
// Tessellating Bezier patches into a triangle mesh (book 1.4; the thesis's Listing 4.2, fixed
// per errata B14). Each patch is sampled on a (divs+1) x (divs+1) grid at u = i/divs, v = j/divs;
// every grid cell becomes two triangles, counter-clockwise in (u, v) so that their geometric
// normals point along du x dv, like the patch normal. Each vertex keeps the patch's own normal
// there (not an average of the faces around it), so shading is as smooth as the surface.
//
// Triangles of zero area (along a collapsed row, as at the teapot's lid knob) are kept, so a set
// of P patches always gives P * divs^2 * 2 triangles, and patch k owns the triangles
// [k * 2 divs^2, (k+1) * 2 divs^2) (chapter 1.4 bounds each patch with a box that way).
#include <zraka/core/affine.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/geometry/bezier_patch.hpp>
#include <zraka/geometry/mesh.hpp>

#include <string>
#include <vector>

namespace zraka {

constexpr int max_tessellation_divs = 1024;  // 2M triangles per patch: surely a typo beyond

inline std::size_t triangles_per_patch(int divs) { return std::size_t(2) * divs * divs; }

// [listing tessellate]
template <class T> void tessellate_patch(const bezier_patch_t<T>& patch, int divs,
                                         const affine_t<T>& to_world, mesh_t<T>& out) {
  if (divs < 1 || divs > max_tessellation_divs)
    throw error("tessellation divs " + std::to_string(divs) + " is out of range 1.." +
                std::to_string(max_tessellation_divs));
  const T det = glm::determinant(to_world.linear);
  if (!(det != T(0)) || !std::isfinite(det)) throw error("tessellation: singular transform");
  const bool mirrored = det < T(0);  // a reflection turns the winding: swap two corners back
  const auto base = static_cast<std::uint32_t>(out.positions.size());
  const int n = divs + 1;  // grid points per side
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const T u = T(i) / T(divs), v = T(j) / T(divs);  // exact 0 and 1 on the edges
      out.positions.push_back(to_world.point(evaluate(patch, u, v)));
      out.normals.push_back(to_world.normal(patch_normal(patch, u, v)));
      out.texcoords.push_back({u, v});  // the patch's own parameters: a texture fits each patch
    }
  auto id = [&](int i, int j) { return base + static_cast<std::uint32_t>(j * n + i); };
  for (int j = 0; j < divs; ++j)
    for (int i = 0; i < divs; ++i) {
      const std::uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (!mirrored) {
        out.triangles.push_back({a, b, c});
        out.triangles.push_back({a, c, d});
      } else {
        out.triangles.push_back({a, c, b});
        out.triangles.push_back({a, d, c});
      }
    }
}
// [end]

template <class T> mesh_t<T> tessellate(const std::vector<bezier_patch_t<T>>& patches, int divs,
                                        const affine_t<T>& to_world = {}) {
  mesh_t<T> m;
  const std::size_t grid = std::size_t(divs + 1) * std::size_t(divs + 1);
  if (divs >= 1 && divs <= max_tessellation_divs) {
    // Before the work: the size is known, and a large divs squares into gigabytes.
    check_limit(std::uint64_t(patches.size()) * triangles_per_patch(divs), limits().triangles, "triangles",
                "the triangle count of " + std::to_string(patches.size()) + " patches at divs " + std::to_string(divs));
    m.positions.reserve(patches.size() * grid);
    m.normals.reserve(patches.size() * grid);
    m.triangles.reserve(patches.size() * triangles_per_patch(divs));
  }
  for (const auto& p : patches) tessellate_patch(p, divs, to_world, m);
  return m;
}

ZRAKA_INSTANCE(void tessellate_patch(const bezier_patch_t<double>&, int, const affine_t<double>&, mesh_t<double>&))
ZRAKA_INSTANCE(mesh_t<double> tessellate(const std::vector<bezier_patch_t<double>>&, int, const affine_t<double>&))
ZRAKA_INSTANCE(void tessellate_patch(const bezier_patch_t<float>&, int, const affine_t<float>&, mesh_t<float>&))
ZRAKA_INSTANCE(mesh_t<float> tessellate(const std::vector<bezier_patch_t<float>>&, int, const affine_t<float>&))  // the GPU's (3.2)

}  // namespace zraka

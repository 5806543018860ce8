#pragma once
// Textures: an albedo that varies over a surface (book 1.8's checkered floor, and walls later).
#include <zraka/image.hpp>
#include <zraka/vec.hpp>

#include <cmath>

namespace zraka {

// An albedo that may vary over the surface: a solid colour or a checkerboard. The checker is
// drawn in the two world axes across the surface (the axis nearest the normal is dropped), so
// a floor at y = 0 or a wall at x = 0 does not sit on a cell boundary, where rounding of the
// hit point would flip the cell from pixel to pixel.
struct texture {
  enum class kind { solid, checker } type = kind::solid;
  rgb a{0.8f};          // the colour (solid), or the first checker colour
  rgb b{0.2f};          // the second checker colour
  double cell = 1.0;    // checker cell size in world units

  static texture solid(rgb c) { return {kind::solid, c, c, 1.0}; }
  static texture checker(rgb c0, rgb c1, double cell_size) { return {kind::checker, c0, c1, cell_size}; }
};

// [listing checker]
template <class T> rgb evaluate(const texture& tex, const vec3_t<T>& p, const vec3_t<T>& n) {
  if (tex.type == texture::kind::solid) return tex.a;
  const vec3_t<T> an = glm::abs(n);
  const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  long long sum = 0;
  for (int i = 0; i < 3; ++i)
    if (i != drop) sum += static_cast<long long>(std::floor(double(p[i]) / tex.cell));
  return (sum & 1) ? tex.b : tex.a;
}
// [end]

}  // namespace zraka

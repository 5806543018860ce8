#pragma once
// Textures: an albedo that varies over a surface. A solid colour; a checkerboard in world space
// (book 1.8's floor) or in the hit's surface coordinates uv (Mitsuba's checkerboard); an image,
// looked up by uv; or procedural noise and marble (noise.hpp), functions of the point in space.
#include <zraka/core/compiled.hpp>
#include <zraka/core/vec.hpp>
#include <zraka/image/image.hpp>
#include <zraka/textures/noise.hpp>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

namespace zraka {

// The checker is drawn in the two world axes across the surface (the axis nearest the normal is
// dropped), so a floor at y = 0 or a wall at x = 0 does not sit on a cell boundary, where
// rounding of the hit point would flip the cell from pixel to pixel.
struct texture {
  enum class kind { solid, checker, image, noise } type = kind::solid;
  rgb a{0.8f};          // the colour (solid), the first checker colour, noise's colour at 0
  rgb b{0.2f};          // the second checker colour, noise's colour at 1
  double cell = 1.0;    // checker cell size in world units (in uv units when uv_space)
  bool uv_space = false;  // checker: cells in the surface coordinates uv instead of world space
  // image: linear RGB, row 0 at the top; u runs left to right, v bottom to top, period 1.
  std::shared_ptr<const zraka::image> map;
  bool repeat = true;   // image: wrap (repeat) or clamp to the edge texels outside [0, 1]
  std::string source;   // image: the file as the scene names it (messages, resolved scene)
  bool srgb = true;     // image: the file's values were sRGB-encoded (as read; for the resolved scene)
  // noise: frequency (cycles per world unit), octaves of turbulence, marble veins along z.
  double frequency = 4.0;
  int octaves = 1;
  bool marble = false;

  static texture solid(rgb c) {
    texture t;
    t.a = t.b = c;
    return t;
  }
  static texture checker(rgb c0, rgb c1, double cell_size) {
    texture t;
    t.type = kind::checker;
    t.a = c0, t.b = c1, t.cell = cell_size;
    return t;
  }
  // Cells of `cell_size` in (u, v), even where floor(u / cell) + floor(v / cell) is even.
  static texture checker_uv(rgb c0, rgb c1, double cell_size) {
    texture t = checker(c0, c1, cell_size);
    t.uv_space = true;
    return t;
  }
  static texture image_map(std::shared_ptr<const zraka::image> img, bool repeat_outside, std::string name = "image") {
    texture t;
    t.type = kind::image;
    t.map = std::move(img);
    t.repeat = repeat_outside;
    t.source = std::move(name);
    return t;
  }
  static texture noise(rgb c0, rgb c1, double frequency, int octaves, bool marble) {
    texture t;
    t.type = kind::noise;
    t.a = c0, t.b = c1;
    t.frequency = frequency, t.octaves = octaves, t.marble = marble;
    return t;
  }
};

// What a texture is, for messages: "an image texture ('wood.png')", "a noise texture", ...
inline std::string describe(const texture& t) {
  switch (t.type) {
    case texture::kind::solid: return "a solid colour";
    case texture::kind::checker: return t.uv_space ? "a uv checker texture" : "a checker texture";
    case texture::kind::image: return "an image texture ('" + t.source + "')";
    case texture::kind::noise: return t.marble ? "a marble texture" : "a noise texture";
  }
  return "a texture";
}

// [listing image-texture]
// Bilinear between the four texels around (u, v): texel (i, j)'s centre is at
// u = (i + 1/2) / W, v = 1 - (j + 1/2) / H. Outside [0, 1] the image repeats or its edge
// texels extend (clamp). A NaN or infinite coordinate reads as 0.
inline rgb lookup_bilinear(const image& img, double u, double v, bool repeat) {
  if (!std::isfinite(u)) u = 0;
  if (!std::isfinite(v)) v = 0;
  if (repeat) u -= std::floor(u), v -= std::floor(v);  // into [0, 1): no huge texel index
  else u = std::clamp(u, -1.0, 2.0), v = std::clamp(v, -1.0, 2.0);  // beyond: the same edge texels
  const double x = u * img.width - 0.5, y = (1 - v) * img.height - 0.5;
  const double x0 = std::floor(x), y0 = std::floor(y);
  const float fx = float(x - x0), fy = float(y - y0);
  auto texel = [&](double i, double j) {
    long long xi = (long long)(i), yj = (long long)(j);
    const long long w = img.width, h = img.height;
    if (repeat) xi = ((xi % w) + w) % w, yj = ((yj % h) + h) % h;
    else xi = xi < 0 ? 0 : (xi >= w ? w - 1 : xi), yj = yj < 0 ? 0 : (yj >= h ? h - 1 : yj);
    return img.at(int(xi), int(yj));
  };
  const rgb top = (1 - fx) * texel(x0, y0) + fx * texel(x0 + 1, y0);
  const rgb bottom = (1 - fx) * texel(x0, y0 + 1) + fx * texel(x0 + 1, y0 + 1);
  return (1 - fy) * top + fy * bottom;
}
// [end]

// [listing checker]
template <class T>
rgb evaluate(const texture& tex, const vec3_t<T>& p, const vec3_t<T>& n, const vec2_t<T>& uv) {
  switch (tex.type) {
    case texture::kind::solid: return tex.a;
    case texture::kind::image: return lookup_bilinear(*tex.map, double(uv.x), double(uv.y), tex.repeat);
    case texture::kind::noise: {
      const vec3 q = vec3(p) * tex.frequency;
      // Marble (after Perlin 1985): veins of sin along z, bent by turbulence; otherwise the
      // turbulence itself, or plain noise mapped from [-1, 1] to [0, 1] with one octave.
      const double s = tex.marble ? 0.5 * (1 + std::sin(q.z + 10 * turbulence(q, tex.octaves)))
                       : tex.octaves > 1 ? turbulence(q, tex.octaves)
                                         : 0.5 * (1 + noise(q));
      return float(1 - s) * tex.a + float(s) * tex.b;
    }
    case texture::kind::checker: break;
  }
  if (tex.uv_space) {  // a NaN or infinite coordinate reads as 0, as for images
    const double u = std::isfinite(double(uv.x)) ? double(uv.x) : 0, v = std::isfinite(double(uv.y)) ? double(uv.y) : 0;
    // Each cell index's parity in double (0 or +-1): no integer conversion to overflow, and past
    // 2^53, where every index is even, u's cells do not swallow v's.
    const double odd = std::abs(std::fmod(std::floor(u / tex.cell), 2.0)) + std::abs(std::fmod(std::floor(v / tex.cell), 2.0));
    return odd == 1 ? tex.b : tex.a;
  }
  const vec3_t<T> an = abs3(n);
  const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  long long sum = 0;
  for (int i = 0; i < 3; ++i)
    if (i != drop) sum += static_cast<long long>(std::floor(double(p[i]) / tex.cell));
  return (sum & 1) ? tex.b : tex.a;
}
// [end]

ZRAKA_INSTANCE(rgb evaluate(const texture&, const vec3_t<double>&, const vec3_t<double>&, const vec2_t<double>&))  // compiled.hpp

}  // namespace zraka

#pragma once
// Where inside a pixel the n samples of anti-aliasing go (book 5.1). A pixel is the unit square
// [0,1)^2; position (0.5, 0.5) is its centre. Three patterns for sample k of n:
//  * regular:    the centres of an nx x ny grid of cells (nx ny = n): no randomness, so an edge
//                is still stair-stepped, only in finer steps, and patterns can alias;
//  * uniform:    independent uniform points ("jitter" in the thesis): unbiased, error ~ n^(-1/2);
//  * stratified: one uniform point inside each grid cell ("jittered grid"): unbiased, and for a
//                pixel crossed by an edge the error falls faster, ~ n^(-3/4).
// Every position is a function of (k, n) and the sample's own random stream, so a renderer can
// compute any sample of any pixel independently (deterministic for any number of threads).
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/rng.hpp>

#include <cmath>
#include <string>
#include <string_view>

namespace zraka {

enum class pixel_pattern { regular, uniform, stratified };

inline constexpr enum_name<pixel_pattern> pixel_pattern_names[] = {
    {pixel_pattern::regular, "regular"}, {pixel_pattern::uniform, "uniform"}, {pixel_pattern::stratified, "stratified"}};
constexpr std::span<const enum_name<pixel_pattern>> enum_names(pixel_pattern) { return pixel_pattern_names; }  // enum_names.hpp
inline pixel_pattern parse_pixel_pattern(std::string_view s) { return parse_enum<pixel_pattern>(s, "pixel pattern"); }

// The grid for n samples: nx x ny = n with nx the largest divisor of n not above sqrt(n), so
// square numbers give square grids and a prime n gives 1 x n strips.
struct strata {
  int nx = 1, ny = 1;
};
inline strata strata_for(int n) {
  if (n < 1) throw error("the number of samples per pixel must be at least 1, got " + std::to_string(n));
  int nx = static_cast<int>(std::sqrt(double(n)));
  while (n % nx != 0) --nx;
  return {nx, n / nx};
}

// [listing pixel-sample]
// Sample k (0 <= k < n) of a pixel, in [0,1)^2. `g` is that sample's own stream.
inline vec2 pixel_sample(pixel_pattern pattern, int k, int n, rng& g) {
  if (pattern == pixel_pattern::uniform) return g.uniform2();
  const strata s = strata_for(n);
  const int i = k % s.nx, j = k / s.nx;  // the cell of sample k
  const vec2 in_cell = pattern == pixel_pattern::regular ? vec2(0.5) : g.uniform2();
  return {(i + in_cell.x) / s.nx, (j + in_cell.y) / s.ny};
}
// [end]

}  // namespace zraka

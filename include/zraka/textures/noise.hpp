#pragma once
// Gradient noise (Perlin's improved noise, 2002) and turbulence, for procedural textures
// (texture.hpp): a smooth random function of a 3-D point, the same for every run. Values of
// noise() lie in [-1, 1]; it is 0 at every integer lattice point, where the gradients sit.
#include <zraka/core/vec.hpp>

#include <array>
#include <cmath>
#include <cstdint>

namespace zraka {

namespace detail {
// A permutation of 0..255 from a fixed seed (splitmix64 drives a Fisher-Yates shuffle),
// repeated once so that p[p[x] + y] needs no wrap.
inline const std::array<std::uint8_t, 512>& noise_permutation() {
  static const std::array<std::uint8_t, 512> p = [] {
    std::array<std::uint8_t, 512> q{};
    for (int i = 0; i < 256; ++i) q[std::size_t(i)] = std::uint8_t(i);
    std::uint64_t s = 0x5a52414b41ull;  // "ZRAKA"
    for (int i = 255; i > 0; --i) {
      s += 0x9e3779b97f4a7c15ull;
      std::uint64_t z = s;
      z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
      z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
      z ^= z >> 31;
      const int j = int(z % std::uint64_t(i + 1));
      std::swap(q[std::size_t(i)], q[std::size_t(j)]);
    }
    for (int i = 0; i < 256; ++i) q[std::size_t(256 + i)] = q[std::size_t(i)];
    return q;
  }();
  return p;
}
// Perlin's twelve gradients (the edges of a cube), picked by the low four bits of a hash.
inline double noise_gradient(int hash, double x, double y, double z) {
  const int h = hash & 15;
  const double u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
inline double noise_fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }  // C2 at 0 and 1
}  // namespace detail

// [listing perlin-noise]
inline double noise(const vec3& q) {
  const auto& p = detail::noise_permutation();
  const double fx = std::floor(q.x), fy = std::floor(q.y), fz = std::floor(q.z);
  if (!std::isfinite(fx + fy + fz)) return 0;  // NaN or inf: no lattice cell to be in
  // The lattice cell (wrapped to 256, the permutation's period) and the point inside it.
  const int X = int(std::fmod(fx, 256.0) + 256) & 255, Y = int(std::fmod(fy, 256.0) + 256) & 255,
            Z = int(std::fmod(fz, 256.0) + 256) & 255;
  const double x = q.x - fx, y = q.y - fy, z = q.z - fz;
  const double u = detail::noise_fade(x), v = detail::noise_fade(y), w = detail::noise_fade(z);
  const int A = p[std::size_t(X)] + Y, AA = p[std::size_t(A)] + Z, AB = p[std::size_t(A + 1)] + Z;
  const int B = p[std::size_t(X + 1)] + Y, BA = p[std::size_t(B)] + Z, BB = p[std::size_t(B + 1)] + Z;
  auto g = [&](int h, double dx, double dy, double dz) { return detail::noise_gradient(p[std::size_t(h)], dx, dy, dz); };
  auto lerp = [](double t, double a, double b) { return a + t * (b - a); };
  const double n = lerp(w, lerp(v, lerp(u, g(AA, x, y, z), g(BA, x - 1, y, z)),
                                   lerp(u, g(AB, x, y - 1, z), g(BB, x - 1, y - 1, z))),
                        lerp(v, lerp(u, g(AA + 1, x, y, z - 1), g(BA + 1, x - 1, y, z - 1)),
                                lerp(u, g(AB + 1, x, y - 1, z - 1), g(BB + 1, x - 1, y - 1, z - 1))));
  return n < -1 ? -1 : (n > 1 ? 1 : n);  // the bound is 1 in exact arithmetic; rounding stays inside
}

// Turbulence: |noise| summed over octaves, each twice the frequency and half the weight of the
// one before, divided by the weights' sum, so it lies in [0, 1].
inline double turbulence(const vec3& q, int octaves) {
  double sum = 0, weight = 1, total = 0;
  vec3 x = q;
  for (int i = 0; i < octaves; ++i) {
    sum += weight * std::abs(noise(x));
    total += weight;
    weight *= 0.5;
    x *= 2.0;
  }
  return total > 0 ? sum / total : 0;
}
// [end]

}  // namespace zraka

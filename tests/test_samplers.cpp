#include <zraka/app/chi_square.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/cornell.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <set>
#include <vector>

using namespace zraka;

namespace {

const sampler_kind all_kinds[] = {sampler_kind::independent, sampler_kind::stratified, sampler_kind::halton,
                                  sampler_kind::sobol};
const sampler_kind point_kinds[] = {sampler_kind::stratified, sampler_kind::halton, sampler_kind::sobol};

double fraction(std::uint32_t bits) { return double(bits) * 0x1p-32; }

// Coordinates j and j + 1 of sample i of n, as a path draws them: from the driven stream.
vec2 pair_of(sampler_kind k, std::uint64_t seed, std::uint32_t pixel, std::uint32_t i, std::uint32_t n,
             std::uint32_t j) {
  rng g(seed, pixel, i);
  sample_point p(k, seed, pixel, i, n);
  p.drive(g);
  g.skip_to(2 * j);
  return g.uniform2();
}

// Is every elementary interval of `cells_x` x `cells_y` cells hit exactly once by the points?
bool one_per_cell(const std::vector<vec2>& pts, std::uint32_t cells_x, std::uint32_t cells_y) {
  std::vector<int> count(std::size_t(cells_x) * cells_y, 0);
  for (const vec2& q : pts) {
    if (!(q.x >= 0 && q.x < 1 && q.y >= 0 && q.y < 1)) return false;
    ++count[std::size_t(q.y * cells_y) * cells_x + std::size_t(q.x * cells_x)];
  }
  for (int c : count)
    if (c != 1) return false;
  return true;
}

// The least-squares slope of log(y) against log(x).
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  const double n = double(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double a = std::log(x[i]), b = std::log(y[i]);
    sx += a, sy += b, sxx += a * a, sxy += a * b;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

}  // namespace

TEST_CASE("samplers: names round-trip; an unknown name lists the accepted ones") {
  for (sampler_kind k : all_kinds) CHECK(parse_sampler(name(k)) == k);
  try {
    parse_sampler("random");
    FAIL("no error");
  } catch (const error& e) {
    CHECK(std::string(e.what()) == "unknown sampler 'random' (independent, stratified, halton, sobol)");
  }
}

TEST_CASE("samplers: the Owen scramble keeps shared leading bits shared and is a bijection of each prefix") {
  // Two fractions that agree in their first k bits still agree there after the scramble, with
  // the same key; and the first bit is flipped for about half the keys.
  int flipped = 0;
  for (std::uint32_t key = 0; key < 4096; ++key) {
    const std::uint32_t h = pcg_hash(key);
    for (int k : {1, 4, 13, 31}) {
      const std::uint32_t a = pcg_hash(h + 1), b = (a & ~(0xffffffffu >> k)) | (pcg_hash(h + 2) >> k);
      const std::uint32_t mask = ~(0xffffffffu >> k);
      REQUIRE((owen_scramble(a, h) & mask) == (owen_scramble(b, h) & mask));
    }
    flipped += (owen_scramble(0, h) >> 31) != 0;
  }
  CHECK(flipped > 1800);
  CHECK(flipped < 2300);
  // Owen's scramble flips a bit by a random function of the bits above it: two fractions that
  // differ in their first bit get independent flips of the next ones (about half the keys differ).
  for (int bit = 1; bit < 12; ++bit) {
    int differ = 0;
    for (std::uint32_t key = 0; key < 4096; ++key) {
      const std::uint32_t h = pcg_hash(key ^ 0xabcdefu);
      const std::uint32_t fa = owen_scramble(0, h), fb = owen_scramble(0x80000000u, h) ^ 0x80000000u;
      differ += ((fa ^ fb) >> (31 - bit)) & 1u;
    }
    CHECK_MESSAGE(std::abs(differ - 2048) < 200, "bit " << bit << ": " << differ);
  }
  // A bijection: 2^16 distinct inputs (the top 16 bits) give 2^16 distinct top halves.
  std::set<std::uint32_t> seen;
  for (std::uint32_t i = 0; i < 65536; ++i) seen.insert(owen_scramble(i << 16, 12345u) >> 16);
  CHECK(seen.size() == 65536);
}

TEST_CASE("samplers: Sobol's first two dimensions are a (0,2)-sequence") {
  CHECK(sobol_1(1) == 0x80000000u);
  CHECK(sobol_1(2) == 0xc0000000u);
  CHECK(sobol_1(3) == 0x40000000u);
  for (std::uint32_t k = 0; k <= 10; ++k)
    for (std::uint32_t block : {0u, 3u}) {  // aligned blocks of 2^k points, the first and another
      std::vector<vec2> pts;
      for (std::uint32_t i = block << k; i < (block + 1) << k; ++i) pts.push_back({fraction(sobol_0(i)), fraction(sobol_1(i))});
      for (std::uint32_t a = 0; a <= k; ++a) CHECK(one_per_cell(pts, 1u << a, 1u << (k - a)));
    }
}

TEST_CASE("samplers: every Sobol pair's first 2^k points fill every elementary interval, for any pixel and seed") {
  for (std::uint64_t seed : {1ull, 77ull})
    for (std::uint32_t pixel : {0u, 4095u, 123456u})
      for (std::uint32_t j : {0u, 2u, 10u, 126u})  // the pixel's pair, bounce pairs, the last pair
        for (std::uint32_t k = 0; k <= 9; ++k) {
          std::vector<vec2> pts;
          for (std::uint32_t i = 0; i < (1u << k); ++i) pts.push_back(pair_of(sampler_kind::sobol, seed, pixel, i, 1024, j));
          for (std::uint32_t a = 0; a <= k; ++a)
            CHECK_MESSAGE(one_per_cell(pts, 1u << a, 1u << (k - a)), "pair " << j << ", 2^" << k << " points, " << a);
        }
}

TEST_CASE("samplers: Halton's first b^k points fill the k-digit intervals of each base; bases 2 and 3 together") {
  for (std::uint32_t pixel : {0u, 99u}) {
    for (std::uint32_t j : {0u, 1u, 2u, 5u}) {
      const std::uint32_t b = halton_bases[j];
      for (std::uint32_t cells = b; cells <= 243; cells *= b) {
        std::vector<vec2> pts;
        for (std::uint32_t i = 0; i < cells; ++i) pts.push_back({pair_of(sampler_kind::halton, 5, pixel, i, cells, j).x, 0.5});
        CHECK_MESSAGE(one_per_cell(pts, cells, 1), "coordinate " << j << " base " << b << ", " << cells << " points");
      }
    }
    std::vector<vec2> pts;  // 72 = 8 x 9 points: one in each of the 8 x 9 cells
    for (std::uint32_t i = 0; i < 72; ++i) pts.push_back(pair_of(sampler_kind::halton, 5, pixel, i, 72, 0));
    CHECK(one_per_cell(pts, 8, 9));
  }
  CHECK(halton_bases[0] == 2);
  CHECK(halton_bases[1] == 3);
  CHECK(halton_bases[127] == 719);
}

TEST_CASE("samplers: stratified puts one point in each cell of every pair, each pair in its own order") {
  for (std::uint32_t n : {1u, 7u, 16u, 32u}) {
    const strata s = strata_for(int(n));
    for (std::uint32_t j : {0u, 2u, 40u}) {
      std::vector<vec2> pts;
      for (std::uint32_t i = 0; i < n; ++i) pts.push_back(pair_of(sampler_kind::stratified, 3, 17, i, n, j));
      CHECK(one_per_cell(pts, std::uint32_t(s.nx), std::uint32_t(s.ny)));
    }
  }
  // The pairs' orders differ: over 64 samples, the cell of pair 0 and of pair 1 are not the same
  // function of the index (at most a few agree by chance).
  int same = 0;
  for (std::uint32_t i = 0; i < 64; ++i) {
    const vec2 a = pair_of(sampler_kind::stratified, 3, 17, i, 64, 0), b = pair_of(sampler_kind::stratified, 3, 17, i, 64, 2);
    same += int(a.x * 8) == int(b.x * 8) && int(a.y * 8) == int(b.y * 8);
  }
  CHECK(same < 8);
}

TEST_CASE("samplers: deterministic for a seed; seeds and pixels give other points") {
  for (sampler_kind k : point_kinds) {
    int same_seed = 0, other_seed = 0, other_pixel = 0;
    for (std::uint32_t j = 0; j < 64; ++j) {
      const sample_point a(k, 9, 1234, 5, 16), b(k, 9, 1234, 5, 16), c(k, 10, 1234, 5, 16), d(k, 9, 1235, 5, 16);
      same_seed += a.coordinate(j) == b.coordinate(j);
      other_seed += a.coordinate(j) == c.coordinate(j);
      other_pixel += a.coordinate(j) == d.coordinate(j);
    }
    CHECK(same_seed == 64);
    CHECK(other_seed == 0);
    CHECK(other_pixel == 0);
  }
}

TEST_CASE("samplers: each coordinate, and any two of them, are uniform over many pixels (chi-square)") {
  // One point per pixel (sample 5 of 16) over 8192 pixels: 1-D projections in 32 bins, 2-D
  // projections (a sampler's own pair, and coordinates of different pairs) in 8 x 8 bins.
  const int pixels = 8192;
  const std::pair<std::uint32_t, std::uint32_t> pairs[] = {{0, 1}, {1, 2}, {0, 2}, {4, 5}, {3, 9}, {20, 21}, {100, 127}};
  const double level = bonferroni_level(0.001, 3 * 7 * 2);
  for (sampler_kind k : point_kinds)
    for (const auto& [ja, jb] : pairs) {
      std::vector<double> one(32, 0), two(64, 0);
      for (int p = 0; p < pixels; ++p) {
        const sample_point s(k, 21, std::uint32_t(p), 5, 16);
        const double x = fraction(s.coordinate(ja)), y = fraction(s.coordinate(jb));
        one[std::size_t(x * 32)] += 1;
        two[std::size_t(y * 8) * 8 + std::size_t(x * 8)] += 1;
      }
      const auto r1 = chi_square_test(one, std::vector<double>(32, pixels / 32.0));
      const auto r2 = chi_square_test(two, std::vector<double>(64, pixels / 64.0));
      CHECK_MESSAGE(r1.p_value > level, std::string(name(k)) << " coordinate " << ja << ": p " << r1.p_value);
      CHECK_MESSAGE(r2.p_value > level, std::string(name(k)) << " coordinates " << ja << ", " << jb << ": p " << r2.p_value);
    }
}

TEST_CASE("samplers: padded Sobol decorrelates its pairs; neighbouring pixels are not alike") {
  // Without the per-pair shuffle of the index, coordinates 0 and 2 would be one function of the
  // other (the same van der Corput point, scrambled twice): 256 samples would fill only 16 of
  // the 16 x 16 cells of the (x0, x2) square. Shuffled, they fill about 256 (1 - 1/e) = 162.
  for (std::uint32_t pixel : {0u, 1u, 4000u})
    for (const auto& [ja, jb] : {std::pair<std::uint32_t, std::uint32_t>{0, 2}, {1, 3}, {2, 5}, {4, 40}}) {
      std::set<int> filled;
      for (std::uint32_t i = 0; i < 256; ++i) {
        const sample_point s(sampler_kind::sobol, 4, pixel, i, 256);
        filled.insert(int(fraction(s.coordinate(ja)) * 16) * 16 + int(fraction(s.coordinate(jb)) * 16));
      }
      CHECK_MESSAGE(filled.size() > 120, "pixel " << pixel << " coordinates " << ja << ", " << jb << ": " << filled.size());
    }
  // The correlation of coordinate j between pixel p and p + 1, over 4096 pixels: near 0.
  for (sampler_kind k : point_kinds) {
    double sa = 0, sb = 0, sab = 0, saa = 0, sbb = 0;
    const int n = 4096;
    for (int p = 0; p < n; ++p) {
      const double a = fraction(sample_point(k, 8, std::uint32_t(p), 3, 16).coordinate(6));
      const double b = fraction(sample_point(k, 8, std::uint32_t(p + 1), 3, 16).coordinate(6));
      sa += a, sb += b, sab += a * b, saa += a * a, sbb += b * b;
    }
    const double cov = sab / n - sa / n * sb / n;
    const double r = cov / std::sqrt((saa / n - sa * sa / n / n) * (sbb / n - sb * sb / n / n));
    CHECK_MESSAGE(std::abs(r) < 0.06, std::string(name(k)) << ": r " << r);  // 4 standard errors of 1/sqrt(4096)
  }
}

TEST_CASE("samplers: a smooth integrand's error falls faster than n^-1/2 for halton, sobol and stratified") {
  // exp(-(x^2 + y^2)) over the unit square, estimated with n points of one pixel, RMSE over 256
  // pixels (independent scrambles), n = 16 ... 4096; the slope of log RMSE against log n.
  const double e1 = std::sqrt(std::acos(-1.0)) / 2 * std::erf(1.0), exact = e1 * e1;
  const std::vector<double> ns{16, 64, 256, 1024, 4096};
  for (sampler_kind k : all_kinds)
    for (std::uint32_t j : {0u, 4u}) {
      std::vector<double> err;
      double bias_sum = 0;
      for (double nd : ns) {
        const std::uint32_t n = std::uint32_t(nd);
        double sq = 0, sum_e = 0;
        for (std::uint32_t p = 0; p < 256; ++p) {
          double s = 0;
          for (std::uint32_t i = 0; i < n; ++i) {
            const vec2 q = pair_of(k, 31, p, i, n, j);
            s += std::exp(-(q.x * q.x + q.y * q.y));
          }
          const double e = s / n - exact;
          sq += e * e, sum_e += e;
        }
        err.push_back(std::sqrt(sq / 256));
        if (n == 16) bias_sum = sum_e / 256 / (err.back() / 16);  // mean error in standard errors
      }
      const double slope = loglog_slope(ns, err);
      MESSAGE(std::string(name(k)) << " pair " << j << ": RMSE at 16 " << err.front() << ", at 4096 " << err.back() << ", slope "
                      << slope);
      CHECK(std::abs(bias_sum) < 5);  // unbiased: the mean error is noise
      if (k == sampler_kind::independent) {
        CHECK(slope > -0.6);
        CHECK(slope < -0.4);
      } else {
        CHECK(slope < -0.8);
      }
    }
}

TEST_CASE("samplers: extreme cases - an index near 2^32, numbers past the sampler's, independent leaves the stream") {
  for (sampler_kind k : point_kinds)
    for (std::uint32_t index : {0xfffffffeu, 0xffffffffu}) {
      rng g(3, 7, index), plain(3, 7, index);
      sample_point p(k, 3, 7, index, 0);  // count 0: treated as 1
      p.drive(g);
      for (int d = 0; d < 8; ++d) {
        const double u = g.uniform();
        CHECK(u >= 0);
        CHECK(u < 1);
      }
      // Past the sampler's 2 x 128 numbers the stream is its own hash again, number for number.
      g.skip_to(2 * sample_point::coordinates + 3);
      plain.skip_to(2 * sample_point::coordinates + 3);
      for (int d = 0; d < 16; ++d) CHECK(g.next_u32() == plain.next_u32());
      // Below, the numbers are the sampler's, not the hash's.
      g.skip_to(0), plain.skip_to(0);
      CHECK(g.next_u32() == p.coordinate(0));
    }
  rng g(3, 7, 11), plain(3, 7, 11);
  sample_point p(sampler_kind::independent, 3, 7, 11, 16);
  p.drive(g);
  g.seek(40);  // a plain stream is not moved by seek
  for (int d = 0; d < 32; ++d) CHECK(g.next_u32() == plain.next_u32());
}

TEST_CASE("samplers: seek only moves a driven stream forward, to the path's fixed blocks") {
  rng g(1, 2, 3);
  sample_point p(sampler_kind::sobol, 1, 2, 3, 8);
  p.drive(g);
  g.seek(path_number(0, path_slot::bsdf));
  CHECK(g.dimension() == 2 * (camera_coordinates + 4));
  g.seek(path_number(0, path_slot::light_point));  // behind: stays
  CHECK(g.dimension() == 2 * (camera_coordinates + 4));
  g.seek(path_number(2, path_slot::roulette));
  CHECK(g.dimension() == 2 * (camera_coordinates + 2 * bounce_coordinates + 7));
}

TEST_CASE("samplers: rendering the Cornell box, every sampler's mean agrees with independent's within noise") {
  // Paired per pixel: d = (pixel mean with the sampler) - (pixel mean with independent), 32 x 32
  // pixels, 16 spp. The pixels' d are independent (each pixel has its own scrambles), so their
  // mean must lie within 5 standard errors of zero if the sampler is unbiased.
  const scene sc = cornell_box<double>(cornell_variant::boxes);
  path_options o;
  o.max_depth = 6;
  const path_tracer tracer(sc, o);
  const auto cam = sc.prepared_camera();
  const int W = 32, H = 32, spp = 16;
  render_options ro;
  ro.threads = 2, ro.progress = false;
  auto draw = [&](sampler_kind k) {
    image img(W, H);
    render(img, spp, 5, [&](sample_context& c) {
      sample_point point(k, 5, std::uint32_t(c.y * W + c.x), std::uint32_t(c.sample), std::uint32_t(c.spp));
      point.drive(c.random);
      const vec2 px = c.random.uniform2();
      return tracer(cam.generate((c.x + px.x) / W, (c.y + px.y) / H), c.random, c.rays);
    }, ro);
    return img;
  };
  const image base = draw(sampler_kind::independent);
  for (sampler_kind k : point_kinds) {
    const image img = draw(k);
    double s = 0, s2 = 0;
    const double n = double(W * H);
    for (std::size_t i = 0; i < img.pixels.size(); ++i) {
      const vec3 d = vec3(img.pixels[i]) - vec3(base.pixels[i]);
      const double v = d.x + d.y + d.z;
      s += v, s2 += v * v;
    }
    const double mean = s / n, se = std::sqrt((s2 / n - mean * mean) / n);
    MESSAGE(std::string(name(k)) << ": mean difference " << mean << " +- " << se);
    CHECK(std::abs(mean) < 5 * se);
  }
}

TEST_CASE("samplers: a driven path draws each number once, each at its slot of its bounce's block") {
  // A number source that records which stream numbers a path asks for.
  struct recorder final : number_source {
    std::vector<std::uint32_t> asked;
    std::uint32_t number(std::uint32_t d) override {
      asked.push_back(d);
      return pcg_hash(d * 2654435761u);
    }
  };
  for (cornell_variant v : {cornell_variant::boxes, cornell_variant::glass, cornell_variant::spheres}) {
    const scene sc = cornell_box<double>(v);
    path_options o;
    o.max_depth = 12;
    const path_tracer tracer(sc, o);
    const auto cam = sc.prepared_camera();
    int bounce_blocks = 0;
    for (std::uint32_t s = 0; s < 400; ++s) {
      recorder rec;
      rng g(7, 0, s);
      g.follow(rec, 1u << 20);
      std::uint64_t rays = 0;
      const vec2 px = g.uniform2();
      tracer(cam.generate(px.x, px.y), g, rays);
      std::set<std::uint32_t> seen;
      for (std::uint32_t d : rec.asked) {
        CHECK(seen.insert(d).second);  // never the same number twice
        if (d < 4) continue;           // the pixel's coordinates
        const std::uint32_t c = d / 2;
        REQUIRE(c >= camera_coordinates);
        const std::uint32_t slot = (c - camera_coordinates) % bounce_coordinates;
        CHECK(slot != 1);  // the block's unused coordinate: surfaces never reach it
        if (d % 2 == 0 && slot == std::uint32_t(path_slot::light_point)) ++bounce_blocks;
      }
    }
    CHECK(bounce_blocks > 400);  // the light sample sat at its slot in many bounces
  }
}

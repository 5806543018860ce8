#pragma once
// Checks for instructors' assignment tests (book/assignments/README.md). Each check returns a
// `result` with `ok` and a human-readable `message` that says what was measured, so it works with
// any test framework and a failing test tells the student by how much they are off:
//
//     #include <zraka/app/testing.hpp>
//     namespace zt = zraka::testing;
//     TEST_CASE("my sampler follows its pdf") {
//       zraka::rng g(7);
//       const auto r = zt::directions_follow_pdf(
//           [&] { return my_sample(g.uniform2()); },               // a unit direction, +z up
//           [](const zraka::vec3& w) { return my_pdf(w); },          // per steradian
//           100000, zraka::direction_grid(16, 32));
//       CHECK_MESSAGE(r.ok, r.message);
//     }
//
// The checks, and what each reuses:
//   directions_follow_pdf, samples_follow_density   chi-square goodness of fit (chi_square.hpp)
//   pdf_integral_over_directions                    integral of a pdf over the sphere (same grid)
//   mean_within                                     mean within k standard errors (estimator.hpp)
//   images_match, image_matches_file                RMSE, per-channel mean, max |difference|
//   noise_floor                                     an image tolerance from renders of a few seeds
//   derivative_matches                              central differences, step from the scale
//   normal_matches_surface                          a shape's normal vs the surface its own
//                                                   intersect() traces out around each hit
//   no_self_hits                                    spawn.hpp's rule leaves the surface at every
//                                                   scale: a new ray never re-hits its origin
//   all_of, across_scales                           several results (e.g. one per scale) as one
// Header-only and independent of doctest. All randomness comes from rng.hpp with a fixed seed.
#include <zraka/app/chi_square.hpp>
#include <zraka/core/hit.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/ray.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/spawn.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/sampling/estimator.hpp>

#include <algorithm>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// PNG reading for reference images (stb_image.hpp: stb_image, once, with PNG and HDR).
#include <zraka/image/stb_image.hpp>

namespace zraka::testing {

struct result {
  bool ok = true;
  std::string message;
  explicit operator bool() const { return ok; }
};

// Numbers in messages: 4 significant digits are enough to see how far off a result is.
inline std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// All of several results (e.g. one per scale): ok if each is; the messages are joined.
inline result all_of(const std::vector<result>& parts) {
  result r;
  for (const result& p : parts) {
    r.ok = r.ok && p.ok;
    if (!r.message.empty()) r.message += '\n';
    r.message += p.ok ? "ok: " : "FAILED: ";
    r.message += p.message;
  }
  return r;
}

// One check run at several scales (sizes, distances): ok if it passes at each; each line of the
// message names its scale.
template <class T, class Check> result across_scales(const std::vector<T>& scales, Check&& check) {
  std::vector<result> parts;
  for (const T s : scales) {
    result r = check(s);
    r.message = "scale " + num(double(s)) + ": " + r.message;
    parts.push_back(std::move(r));
  }
  return all_of(parts);
}

// ---------------------------------------------------------------- chi-square (chi_square.hpp)
// A chi-square result judged at significance `level` (the probability of rejecting a correct
// sampler; pass sidak_level(alpha, k) when a test file runs k of these). The message says what is
// wrong first: no samples at all, samples where the pdf is zero, a pdf whose integral is above
// one; then the statistic, and where the samples that are not in the grid went.
inline result judge(const chi_square_result& c, double level, const std::string& what) {
  result r;
  const bool too_much = c.pdf_mass > 1 + 1e-3 + c.quadrature_error;
  r.ok = c.p_value >= level && c.impossible == 0 && !too_much && c.rejected < c.samples;
  std::string why;
  const long in_zero_bins = c.impossible - c.impossible_outside;
  if (c.samples > 0 && c.rejected == c.samples)
    why = "the sampler returned no sample in " + std::to_string(c.samples) +
          " draws (each was none, a zero or a non-finite direction); ";
  else if (too_much)
    why = "the pdf integrates to " + num(c.pdf_mass) + " over the grid, more than 1; ";
  else if (in_zero_bins > 0)
    why = std::to_string(in_zero_bins) + " sample(s) fell in bins where the pdf is zero; ";
  else if (c.impossible_outside > 0)
    why = std::to_string(c.impossible_outside) +
          " draw(s) rejected or outside the grid, although the pdf puts all its mass in the grid; ";
  r.message = what + ": " + why + "X^2 = " + num(c.statistic) + " with " + std::to_string(c.dof) +
              " dof, p = " + num(c.p_value) + " (reject below " + num(level) + "); pdf mass in the grid " +
              num(c.pdf_mass) + " (quadrature error " + num(c.quadrature_error) + ")";
  if (c.rejected > 0 || c.outside > 0)
    r.message += "; of " + std::to_string(c.samples) + " draws " + std::to_string(c.rejected) +
                 " rejected and " + std::to_string(c.outside) + " outside the grid, where the pdf expects " +
                 num(std::max(0.0, 1 - c.pdf_mass) * double(c.samples));
  if (c.unresolved_bins > 0)
    r.message += "; " + std::to_string(c.unresolved_bins) +
                 " bin(s) not integrated to tolerance (a finer grid or a larger sub helps)";
  return r;
}

// sample() returns a unit direction in the local frame (+z up) or an optional of one; pdf(w)
// is per steradian. See chi_square_directions for the grid and the rejected-sample bin; each
// bin's pdf is integrated adaptively from sub x sub points (chi_square.hpp,
// expected_counts_adaptive), so narrow lobes (GGX from alpha = 0.001) need no special grid.
template <class Sample, class Pdf>
result directions_follow_pdf(Sample&& sample, Pdf&& pdf, long n, const grid2& g,
                             double level = 1e-3, int sub = 8) {
  return judge(chi_square_directions(sample, pdf, n, g, sub), level, "directions vs pdf");
}

// The same for a 2D sampler returning std::optional<vec2> against a density on the grid.
template <class Sample, class Density>
result samples_follow_density(Sample&& sample, Density&& density, long n, const grid2& g,
                              double level = 1e-3, int sub = 8) {
  return judge(chi_square_2d(sample, density, n, g, sub), level, "samples vs density");
}

// The integral of pdf(w) over the directions of the grid (the whole sphere by default), by the
// midpoint rule of expected_counts; a pdf must give 1. Resolve a narrow lobe with a fine n_cos.
template <class Pdf>
double pdf_integral_over_directions(Pdf&& pdf, int n_cos, int n_phi, double cos_min = -1) {
  const std::vector<double> e = expected_counts(
      direction_grid(n_cos, n_phi, cos_min),
      [&](double c, double phi) { return double(pdf(direction_from_coords(c, phi))); }, 1.0);
  double sum = 0;
  for (double x : e) sum += x;
  return sum;
}

// ---------------------------------------------------------------- means (estimator.hpp)
// |mean - expected| <= k standard errors. With k = 4 a correct estimator fails about once in
// 16,000 runs, and a fixed seed makes it pass or fail the same way every time. A zero standard
// error (every sample equal) demands the mean to within a few roundings.
template <class T> result mean_within(const estimator_t<T>& e, double expected, double k = 4) {
  result r;
  const double mean = double(e.mean()), se = double(e.standard_error());
  const double diff = mean - expected;
  if (e.count() < 2 || !std::isfinite(mean) || !std::isfinite(se)) {
    r.ok = false;
    r.message = "mean " + num(mean) + " over " + std::to_string(e.count()) +
                " samples has no finite standard error (NaN/inf samples, or fewer than 2)";
    return r;
  }
  if (se == 0) {
    r.ok = std::abs(diff) <= 4 * std::numeric_limits<T>::epsilon() * std::abs(expected);
  } else {
    r.ok = std::abs(diff) <= k * se;
  }
  r.message = "mean " + num(mean) + " vs expected " + num(expected) + ": off by " +
              num(se > 0 ? diff / se : (diff == 0 ? 0.0 : infinity<double>)) +
              " standard errors (se " + num(se) + ", n " + std::to_string(e.count()) +
              ", allowed " + num(k) + ")";
  return r;
}

// The same for n draws of sample() (a number per call).
template <class Sample>
  requires std::invocable<Sample&>
result mean_within(Sample&& sample, long n, double expected, double k = 4) {
  estimator e;
  for (long i = 0; i < n; ++i) e.add(double(sample()));
  return mean_within(e, expected, k);
}

// ---------------------------------------------------------------- images
struct image_tolerance {
  double rmse = 0.01;           // root mean square of all channel differences
  double channel_mean = 0.005;  // |mean of a channel - reference's mean|: catches a global shift
  double max_abs = infinity<double>;  // the largest single channel difference
};

struct image_difference {
  double rmse = 0, channel_mean = 0, max_abs = 0;
  int worst_x = 0, worst_y = 0;
};

inline image_difference compare_images(const image& a, const image& b) {
  image_difference d;
  if (a.pixels.empty()) return d;
  double sq = 0;
  double sum_a[3] = {0, 0, 0}, sum_b[3] = {0, 0, 0};
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const double pa = a.at(x, y)[c], pb = b.at(x, y)[c], diff = std::abs(pa - pb);
        sq += diff * diff;
        sum_a[c] += pa;
        sum_b[c] += pb;
        if (diff > d.max_abs) d = {d.rmse, d.channel_mean, diff, x, y};
      }
  const double n = double(a.pixels.size());
  d.rmse = std::sqrt(sq / (3 * n));
  for (int c = 0; c < 3; ++c) d.channel_mean = std::max(d.channel_mean, std::abs(sum_a[c] - sum_b[c]) / n);
  return d;
}

// Two images of the same size and space (both linear, or both display values in [0,1]).
inline result images_match(const image& got, const image& reference, const image_tolerance& tol,
                           const std::string& space = "linear") {
  result r;
  if (got.width != reference.width || got.height != reference.height) {
    r.ok = false;
    r.message = "image is " + std::to_string(got.width) + "x" + std::to_string(got.height) +
                ", reference is " + std::to_string(reference.width) + "x" +
                std::to_string(reference.height);
    return r;
  }
  if (const std::size_t bad = got.count_nonfinite()) {
    r.ok = false;
    r.message = std::to_string(bad) + " NaN/inf pixel(s) in the image";
    return r;
  }
  const image_difference d = compare_images(got, reference);
  r.ok = d.rmse <= tol.rmse && d.channel_mean <= tol.channel_mean && d.max_abs <= tol.max_abs;
  r.message = "vs reference (" + space + "): RMSE " + num(d.rmse) + " (allowed " + num(tol.rmse) +
              "), worst channel mean shift " + num(d.channel_mean) + " (allowed " +
              num(tol.channel_mean) + "), max |difference| " + num(d.max_abs) + " at (" +
              std::to_string(d.worst_x) + "," + std::to_string(d.worst_y) + ") (allowed " +
              num(tol.max_abs) + ")";
  return r;
}

namespace detail {
// Checks a PNG's chunk structure before stb_image sees it, so that memory stays in proportion to
// the file: stb_image trusts a chunk's declared length (an 80-byte file asked it for 1.7 GB, found
// by fuzz/fuzz_png.cpp) and allocates the image its header declares before inflating. Every
// chunk must lie inside the file, and the declared image must fit what the compressed data can
// hold (deflate expands at most about 1032:1).
inline void check_png_structure(const std::string& bytes, const std::string& name) {
  static const char signature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.size() < 8 || bytes.compare(0, 8, signature, 8) != 0) throw error("cannot read PNG " + name + ": not a PNG file");
  auto u32 = [&](std::size_t at) {
    std::uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(bytes[at + std::size_t(i)]);
    return v;
  };
  std::size_t at = 8;
  double idat = 0, raw = -1;
  for (bool end = false; !end;) {
    // stb_image reads a chunk header from a partial one too (zeros past the end): none may be cut.
    if (bytes.size() - at < 12) throw error("cannot read PNG " + name + ": the file ends inside a chunk (truncated)");
    const std::uint32_t len = u32(at);
    const std::string type = bytes.substr(at + 4, 4);
    if (len > bytes.size() - at - 12)
      throw error("cannot read PNG " + name + ": chunk " + type + " runs past the end of the file");
    if (type == "IHDR" && len >= 13) {
      const double w = u32(at + 8), h = u32(at + 12);
      const int depth = static_cast<unsigned char>(bytes[at + 16]), colour = static_cast<unsigned char>(bytes[at + 17]);
      const int channels = colour == 2 ? 3 : colour == 4 ? 2 : colour == 6 ? 4 : 1;
      raw = h * (1 + std::ceil(w * channels * depth / 8.0));
      try {
        image::check_size(static_cast<long long>(w), static_cast<long long>(h));
      } catch (const error& e) {
        throw error("cannot read PNG " + name + ": " + e.what());
      }
    }
    // An empty IDAT is legal but useless, and stb_image 2.27 then calls memcpy(NULL, ..., 0),
    // undefined behaviour (UBSan stops there): refuse it.
    if (type == "IDAT" && len == 0) throw error("cannot read PNG " + name + ": an empty IDAT chunk");
    if (type == "IDAT") idat += len;
    at += 12 + std::size_t(len);
    end = type == "IEND";
  }
  if (raw < 0) throw error("cannot read PNG " + name + ": no IHDR chunk");
  if (raw > 1032 * idat + 1024)
    throw error("cannot read PNG " + name + ": the image data is too short for the declared size");
}
}  // namespace detail

// A PNG as display values in [0,1] (8-bit sRGB / 255).
// Only a regular file within limits().file_bytes, and the size in its header is checked against
// the image limits before anything is decoded (a small PNG can claim gigapixels).
inline image read_png_display(const std::filesystem::path& path) {
  const std::string bytes = read_input_file(path);
  detail::check_png_structure(bytes, path.string());
  const auto* in = reinterpret_cast<const stbi_uc*>(bytes.data());
  const int len = bytes.size() > std::size_t(std::numeric_limits<int>::max()) ? 0 : int(bytes.size());
  // stb_image does not give a reason for every failure (fuzz_png found a NULL one)
  auto why = [] { const char* w = stbi_failure_reason(); return std::string(w ? w : "corrupt PNG"); };
  int w = 0, h = 0, channels = 0;
  if (!stbi_info_from_memory(in, len, &w, &h, &channels)) throw error("cannot read PNG " + path.string() + ": " + why());
  try {
    image::check_size(w, h);
  } catch (const error& e) {
    throw error(path.string() + ": " + e.what());
  }
  unsigned char* data = stbi_load_from_memory(in, len, &w, &h, &channels, 3);
  if (!data) throw error("cannot read PNG " + path.string() + ": " + why());
  image img;
  try {
    img = image(w, h);
  } catch (...) {
    stbi_image_free(data);
    throw;
  }
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    img.pixels[i] = rgb(data[3 * i], data[3 * i + 1], data[3 * i + 2]) / 255.0f;
  stbi_image_free(data);
  return img;
}

// The image as the PNG writer would store it, as display values in [0,1].
inline image to_display(const image& linear) {
  image out = linear;
  for (rgb& p : out.pixels)
    for (int c = 0; c < 3; ++c) p[c] = float(to_byte(p[c])) / 255.0f;
  return out;
}

// Compares against a reference file: a .pfm or .exr is compared in linear values; a .png in the 8-bit
// display values the PNG writer produces (so an identical render differs by exactly 0).
inline result image_matches_file(const image& got, const std::filesystem::path& reference,
                                 const image_tolerance& tol) {
  result r;
  try {
    const std::string ext = reference.extension().string();
    if (ext == ".pfm" || ext == ".exr") r = images_match(got, read_float_image(reference), tol, "linear");
    else if (ext == ".png") r = images_match(to_display(got), read_png_display(reference), tol, "8-bit display values");
    else throw error("reference " + reference.string() + " is neither .pfm, .exr nor .png");
  } catch (const std::exception& e) {
    return {false, e.what()};
  }
  r.message = reference.filename().string() + " " + r.message;
  return r;
}

// The noise floor of a Monte Carlo render, so that an instructor sets an image tolerance with one
// call: render(seed) makes the image for a seed (the solution at the spp the test will use); it
// is called for `seeds` seeds (2..64), and every image after the first is compared with the first
// (two independent renders differ by sqrt(2) times the per-render noise, as a student's render
// differs from a reference of the same spp). The tolerance is `margin` times the largest
// difference seen in each measure (RMSE, channel mean shift, max |difference|): a correct
// student's image then passes images_match, a wrong one fails once its error is above the noise.
//   const auto floor = zt::noise_floor([&](std::uint64_t s) { return render_solution(s); });
//   CHECK_MESSAGE(zt::images_match(render_student(99), render_solution(1), floor.tolerance).ok, ...);
struct noise_floor_result {
  image_tolerance tolerance;  // margin x floor
  image_difference floor;     // the largest difference between renders of different seeds
  int seeds = 0;
  std::string message;
};
template <class Render>
noise_floor_result noise_floor(Render&& render, int seeds = 4, double margin = 2.0, std::uint64_t first_seed = 1) {
  if (seeds < 2 || seeds > 64) throw error("noise_floor: seeds must be in 2..64, got " + std::to_string(seeds));
  if (!(margin >= 1) || !std::isfinite(margin)) throw error("noise_floor: margin must be finite and >= 1, got " + num(margin));
  const image first = render(first_seed);
  noise_floor_result r;
  r.seeds = seeds;
  for (int i = 1; i < seeds; ++i) {
    const image other = render(first_seed + std::uint64_t(i));
    if (other.width != first.width || other.height != first.height)
      throw error("noise_floor: the renders differ in size between seeds");
    if (first.count_nonfinite() || other.count_nonfinite()) throw error("noise_floor: a render has NaN/inf pixels");
    const image_difference d = compare_images(other, first);
    r.floor.rmse = std::max(r.floor.rmse, d.rmse);
    r.floor.channel_mean = std::max(r.floor.channel_mean, d.channel_mean);
    if (d.max_abs > r.floor.max_abs) r.floor.max_abs = d.max_abs, r.floor.worst_x = d.worst_x, r.floor.worst_y = d.worst_y;
  }
  r.tolerance = {margin * r.floor.rmse, margin * r.floor.channel_mean, margin * r.floor.max_abs};
  r.message = "noise floor over " + std::to_string(seeds) + " seeds: RMSE " + num(r.floor.rmse) +
              ", channel mean shift " + num(r.floor.channel_mean) + ", max |difference| " + num(r.floor.max_abs) +
              "; tolerance " + num(margin) + "x that";
  return r;
}

// ---------------------------------------------------------------- finite differences
namespace detail {
template <class V> double norm_of(const V& v) {
  if constexpr (std::is_arithmetic_v<V>) return std::abs(double(v));
  else return double(glm::length(v));
}
}  // namespace detail

// Checks df(x) against the central difference (f(x+h) - f(x-h)) / 2h at each x. f maps a
// scalar to a scalar or to a vector (a curve). The step h = cbrt(eps) max(1, |x|) balances the
// truncation error (~h^2 f''') against the rounding error (~eps |f| / h). A difference below
// that rounding floor is not counted against the derivative. The step follows |x|, so a function
// that turns faster than that (sin at x = 1e4 in float) needs points of order one, or rescaling.
template <class T, class F, class DF>
result derivative_matches(F&& f, DF&& df, const std::vector<T>& xs, double relative_tolerance) {
  result r;
  double worst = 0;
  T worst_x = 0;
  for (const T x : xs) {
    const T h = std::cbrt(std::numeric_limits<T>::epsilon()) * std::max(T(1), std::abs(x));
    const T xp = x + h, xm = x - h;  // the step actually taken, after rounding
    const auto fp = f(xp), fm = f(xm);
    const auto fd = (fp - fm) / (xp - xm);
    const auto an = df(x);
    const double floor = 8 * std::numeric_limits<T>::epsilon() *
                         std::max(detail::norm_of(fp), detail::norm_of(fm)) / double(xp - xm);
    const double err = std::max(0.0, detail::norm_of(fd - an) - floor) /
                       std::max(detail::norm_of(an), floor > 0 ? floor : 1e-300);
    if (!(err <= worst)) { worst = std::isnan(err) ? infinity<double> : err; worst_x = x; }
  }
  r.ok = worst <= relative_tolerance;
  r.message = "derivative vs central differences: worst relative error " + num(worst) + " at x = " +
              num(double(worst_x)) + " over " + std::to_string(xs.size()) + " points (allowed " +
              num(relative_tolerance) + ")";
  return r;
}

// The reported normal against the surface around each hit, traced by the shape's own intersect:
// four rays from the same origin aimed at the hit point moved by +-h along two tangents give
// four surface points, and the cross product of their central differences is the normal of the
// surface they lie on. Reports the worst angle (sign ignored: orientation is a separate check).
// h = cbrt(eps) * length_scale, where length_scale is the shape's size (its radius): smaller
// than any curvature of the shape, large against the hit points' rounding. A sample whose four
// neighbours do not all hit, or hit with a normal more than 30 degrees off the centre's (across
// an edge, e.g. a cylinder's rim), is skipped and counted; at most half may be skipped.
template <class T, class Intersect, class Aim>
result normal_matches_surface(Intersect&& intersect, Aim&& aim, int samples, T length_scale,
                              double max_angle_degrees, std::uint64_t seed = 1) {
  result r;
  rng g(seed);
  double worst = 0;
  int used = 0, skipped = 0, missed = 0;
  const T h = std::cbrt(std::numeric_limits<T>::epsilon()) * length_scale;
  for (int s = 0; s < samples; ++s) {
    const ray_t<T> ray = aim(g);
    hit_t<T> c;
    if (!intersect(ray, T(0), infinity<T>, c)) { ++missed; continue; }
    // Two tangents of the surface at c.p, from the reported normal.
    const vec3_t<T> n = c.normal;
    const vec3_t<T> helper = std::abs(n.x) < T(0.6) ? vec3_t<T>(1, 0, 0) : vec3_t<T>(0, 1, 0);
    const vec3_t<T> t1 = glm::normalize(glm::cross(n, helper)), t2 = glm::cross(n, t1);
    vec3_t<T> q[4];
    bool good = true;
    const vec3_t<T> offsets[4] = {h * t1, -h * t1, h * t2, -h * t2};
    for (int k = 0; k < 4 && good; ++k) {
      hit_t<T> nb;
      const ray_t<T> rk(ray.origin, c.p + offsets[k] - ray.origin);
      good = intersect(rk, T(0), infinity<T>, nb) &&
             std::abs(glm::dot(nb.normal, n)) > T(0.866);  // within 30 degrees
      q[k] = nb.p;
    }
    if (!good) { ++skipped; continue; }
    const vec3 fd = normalize_or_zero(glm::cross(vec3(q[0] - q[1]), vec3(q[2] - q[3])));
    const double cosine = std::abs(glm::dot(fd, normalize_or_zero(vec3(n))));
    double angle = std::acos(std::min(1.0, cosine)) * 180 / pi<double>;
    if (length2(fd) == 0 || std::abs(glm::length(vec3(n)) - 1) > 1e-3) angle = 180;  // not unit
    worst = std::max(worst, std::isnan(angle) ? 180.0 : angle);
    ++used;
  }
  r.ok = worst <= max_angle_degrees && used > 0 && skipped <= used;
  if (used == 0) r.message = "no usable hits: ";
  r.message += "normal vs finite-difference surface: worst angle " + num(worst) + " deg (allowed " +
              num(max_angle_degrees) + ") over " + std::to_string(used) + " hits; " +
              std::to_string(skipped) + " skipped at edges, " + std::to_string(missed) +
              " aimed rays missed";
  return r;
}

// ---------------------------------------------------------------- reintersection (spawn.hpp)
// For a new shape: aim(g) returns a ray that should hit it; from each hit, rays spawned by
// spawn_ray in random directions (both sides of the surface) are traced on (0, inf). A re-hit
// is a hit within 4 |p_error| + 16 ulp(|p|) of the hit point, the distance spawn_ray moved it:
// the surface found itself again (acne). (A legitimate second hit that close, e.g. on the other
// face at an edge, is rare enough for random points to be ignored.) It
// must never happen. Run it once per scale (a shape of size 1e-4 .. 1e4, near and far from the
// origin), e.g. with across_scales. At least half the aimed rays must hit, or the check says so.
template <class T, class Intersect, class Aim>
result no_self_hits(Intersect&& intersect, Aim&& aim, int hit_points, int rays_per_point = 4,
                    std::uint64_t seed = 1) {
  result r;
  rng g(seed);
  long hits = 0, spawned = 0, rehits = 0;
  double worst_distance = 0;  // of the closest re-hit, relative to |p|
  for (int i = 0; i < hit_points; ++i) {
    const ray_t<T> ray = aim(g);
    hit_t<T> h;
    if (!intersect(ray, T(0), infinity<T>, h)) continue;
    ++hits;
    const T scale = std::max({std::abs(h.p.x), std::abs(h.p.y), std::abs(h.p.z),
                              std::numeric_limits<T>::min()});
    const T radius = T(4) * glm::length(h.p_error) + T(16) * std::numeric_limits<T>::epsilon() * scale;
    for (int k = 0; k < rays_per_point; ++k) {
      const vec2 u = g.uniform2();
      const T z = T(1 - 2 * u.x), phi = T(2 * pi<double> * u.y);
      const T s = std::sqrt(std::max(T(0), (T(1) - z) * (T(1) + z)));
      const vec3_t<T> w(s * std::cos(phi), s * std::sin(phi), z);
      ++spawned;
      hit_t<T> again;
      if (intersect(spawn_ray(h, w), T(0), infinity<T>, again) &&
          glm::length(again.p - h.p) <= radius) {
        ++rehits;
        worst_distance = std::max(worst_distance, double(glm::length(again.p - h.p) / scale));
      }
    }
  }
  r.ok = rehits == 0 && hits * 2 >= hit_points;
  r.message = std::to_string(rehits) + " re-hit(s) of the surface by " + std::to_string(spawned) +
              " spawned rays from " + std::to_string(hits) + " hit points (of " +
              std::to_string(hit_points) + " aimed rays)";
  if (hits * 2 < hit_points) r.message += "; too few aimed rays hit: does intersect() find hits? (else check aim())";
  return r;
}

}  // namespace zraka::testing

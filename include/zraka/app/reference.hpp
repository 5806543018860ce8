#pragma once
// The reference the chapters of part 6 measure their error against: a long render of the path
// tracer with MIS (chapter 2.3), made in two halves with seeds of their own. The halves' difference
// measures the reference's own noise, E|A - B|^2 = 4 MSE((A + B) / 2), which is taken out of every
// error reported against it. The halves are kept as PFM files and read back by the next run with
// the same scene file (its bytes' hash is in the name), size, depth and sample count.
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

// Compiled once into zraka::compiled where zraka was built with yaml-cpp (ZRAKA_COMPILED_SCENE_FILE:
// the scene argument needs the scene reader), in a unit of its own (src/reference.cpp); header-only,
// inline. They take the resource root as an argument (compiled.hpp); the wrappers pass the program's.
#if defined(ZRAKA_COMPILED_SCENE_FILE)
#define ZRAKA_REFERENCE_FN
#else
#define ZRAKA_REFERENCE_FN inline
#endif
#if !defined(ZRAKA_COMPILED_SCENE_FILE) || defined(ZRAKA_COMPILING_REFERENCE)
#define ZRAKA_REFERENCE_DEFINITIONS 1
#else
#define ZRAKA_REFERENCE_DEFINITIONS 0
#endif

namespace zraka {

// [listing mis-render]
// The path tracer of chapter 2.3, its camera rays jittered over the pixel.
ZRAKA_REFERENCE_FN image render_mis(const scene& sc, int spp, std::uint64_t seed, const path_options& po,
                                    const render_options& ro, render_stats& st)
#if ZRAKA_REFERENCE_DEFINITIONS
{
  const path_tracer pt(sc, po);
  const auto cam = sc.prepared_camera();
  const int W = sc.settings.width, H = sc.settings.height;
  image img(W, H);
  st = render(img, spp, seed, [&](sample_context& c) {
    const vec2 u = c.random.uniform2();
    return pt(cam.generate((c.x + u.x) / W, (c.y + u.y) / H), c.random, c.rays);
  }, ro);
  return img;
}
#else
    ;
#endif
// [end]

namespace detail {
// 8 hex digits of the FNV-1a hash of a --scene argument's file ("c++" for a scene built in C++).
ZRAKA_REFERENCE_FN std::string scene_file_hash_in(const std::string& arg, const std::filesystem::path& root)
#if ZRAKA_REFERENCE_DEFINITIONS
{
  const std::filesystem::path file = scene_argument_file(arg, root);
  if (file.empty()) return "c++";
  const std::filesystem::path p = resource_path_in(file.string(), root);
  std::uint32_t h = 2166136261u;
  for (const char c : read_input_file(p)) h = (h ^ std::uint8_t(c)) * 16777619u;
  char buf[16];
  std::snprintf(buf, sizeof buf, "%08x", h);
  return buf;
}
#else
    ;
#endif
}  // namespace detail

inline std::string scene_file_hash(const std::string& arg) { return detail::scene_file_hash_in(arg, resource_root()); }

struct mis_reference {
  image img;                 // (A + B) / 2
  image half[2];             // A and B, for the noise of another error measure (bench/time_to_error)
  double mse_noise = 0;      // its own MSE, |A - B|^2 / 4
  double relmse_noise = 0;   // its own relMSE, likewise
  bool cached = false;       // both halves were read back
  std::string files;         // "<stem>-{a,b}.pfm"

  // "reference: mis, 512 spp in two halves, cached in <files>; its own RMSE ..., relMSE ..."
  std::string describe(int spp) const {
    char buf[160];
    std::snprintf(buf, sizeof buf, "; its own RMSE %.5f, relMSE %.5f (subtracted below)", std::sqrt(mse_noise), relmse_noise);
    return "reference: mis, " + std::to_string(spp) + " spp in two halves, " + (cached ? "read from " : "cached in ") +
           files + buf;
  }

  // An image's RMSE and relMSE against the truth, estimated: the reference's own noise taken out
  // of the squared error (for relMSE approximately, since its weights use the reference).
  std::vector<double> errors_of(const image& x) const {
    const double e = rmse(x, img);
    return {std::sqrt(std::max(0.0, e * e - mse_noise)), std::max(0.0, relmse(x, img) - relmse_noise)};
  }
};

// file_of("-a") names a half's file; the halves use seeds seed + 1000 and seed + 1001.
ZRAKA_REFERENCE_FN mis_reference make_mis_reference(const scene& sc, int spp, std::uint64_t seed, const path_options& po,
                                                    const render_options& ro,
                                                    const std::function<std::string(const std::string&)>& file_of,
                                                    std::uint64_t& nonfinite)
#if ZRAKA_REFERENCE_DEFINITIONS
{
  if (spp < 2 || spp > 65536 || spp % 2) throw error("--ref-spp must be even, in 2..65536, got " + std::to_string(spp));
  const int W = sc.settings.width, H = sc.settings.height;
  image half[2];
  mis_reference ref;
  ref.cached = true;
  for (int i = 0; i < 2; ++i) {
    const std::string name = file_of(i ? "-b" : "-a");
    std::error_code ec;
    if (std::filesystem::exists(name, ec)) {
      half[i] = read_pfm(name);
      check_same_size(image(W, H), half[i]);
      continue;
    }
    ref.cached = false;
    render_stats rs;
    const std::uint64_t s = seed + 1000 + std::uint64_t(i);
    half[i] = render_mis(sc, spp / 2, s, po, ro, rs);
    nonfinite += rs.nonfinite;
    write_image(half[i], name);
    std::printf("reference half %c: mis, %d spp, seed %llu, %.2f s, %llu NaN/inf samples\n", i ? 'b' : 'a', spp / 2,
                static_cast<unsigned long long>(s), rs.seconds, static_cast<unsigned long long>(rs.nonfinite));
  }
  ref.img = image(W, H);
  for (std::size_t i = 0; i < ref.img.pixels.size(); ++i) ref.img.pixels[i] = (half[0].pixels[i] + half[1].pixels[i]) * 0.5f;
  const double d = rmse(half[0], half[1]);
  ref.mse_noise = d * d / 4;
  ref.relmse_noise = relmse(half[0], half[1]) / 4;
  ref.half[0] = std::move(half[0]), ref.half[1] = std::move(half[1]);
  ref.files = file_of("-{a,b}");
  return ref;
}
#else
    ;
#endif

namespace detail {
// The stem of a reference's files for a --scene argument and the settings it depends on.
ZRAKA_REFERENCE_FN std::string reference_tag_in(const std::string& scene_arg, int W, int H, int depth, int spp,
                                                const std::filesystem::path& root)
#if ZRAKA_REFERENCE_DEFINITIONS
{
  return "-reference-" + std::filesystem::path(scene_arg).stem().string() + "-" + scene_file_hash_in(scene_arg, root) +
         "-" + std::to_string(W) + "x" + std::to_string(H) + "-d" + std::to_string(depth) + "-" + std::to_string(spp) +
         "spp";
}
#else
    ;
#endif

ZRAKA_REFERENCE_FN mis_reference program_reference_in(const program_options& cli, const scene& sc, int spp,
                                                      const path_options& po, const render_options& ro,
                                                      std::uint64_t& nonfinite, const std::filesystem::path& root)
#if ZRAKA_REFERENCE_DEFINITIONS
{
  const std::string tag = reference_tag_in(cli.scene, sc.settings.width, sc.settings.height, po.max_depth, spp, root);
  mis_reference ref = make_mis_reference(
      sc, spp, cli.seed, po, ro, [&](const std::string& half) { return cli.sibling(tag + half, ".pfm"); }, nonfinite);
  std::printf("%s\n", ref.describe(spp).c_str());
  return ref;
}
#else
    ;
#endif
}  // namespace detail

inline std::string reference_tag(const std::string& scene_arg, int W, int H, int depth, int spp) {
  return detail::reference_tag_in(scene_arg, W, H, depth, spp, resource_root());
}

// A chapter program's reference: its files next to --out (cli.sibling), named after --scene
// and the settings; its description printed.
inline mis_reference program_reference(const program_options& cli, const scene& sc, int spp, const path_options& po,
                                       const render_options& ro, std::uint64_t& nonfinite) {
  return detail::program_reference_in(cli, sc, spp, po, ro, nonfinite, resource_root());
}

}  // namespace zraka

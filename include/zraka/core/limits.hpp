#pragma once
// Limits on every size that an input file or a command line controls, so that no small input can
// make a program run away with memory or time (issue 18). Each is checked before the work it
// bounds starts, and its error says how to raise it: every program takes `--limit NAME=VALUE`
// (cli.hpp adds it to every command line). The limits belong to the person who runs the program,
// not to the file: a scene cannot raise its own limits.
//
// The defaults keep the peak memory of any input under 1 MB below 1 GiB (tests/hostile/ checks
// it under an address-space limit) and allow everything in scenes/ many times over.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <thread>

namespace zraka {

struct input_limits {
  std::uint64_t file_bytes = std::uint64_t(64) << 20;  // one scene, mesh, patch or image file read
  std::uint64_t yaml_nodes = 1'000'000;                // YAML nodes of a scene, aliases expanded
  std::uint64_t triangles = 4'000'000;                 // in a whole scene (meshes, tessellated patches)
  std::uint64_t vertices = 4'000'000;                  // positions, normals, texture coordinates of one file
  std::uint64_t patches = 100'000;                     // Bezier patches of one .bpt file
  std::uint64_t pixels = std::uint64_t(1) << 24;       // one image: 16.7 M pixels (4096 x 4096), 200 MB of floats
  std::uint64_t samples = std::uint64_t(1) << 32;      // pixels x samples per pixel of one render
  std::uint64_t threads_per_core = 8;                  // --threads at most this many per hardware thread
};

// Not a limit but a range: coordinates, radii and distances (after transforms) beyond this size
// are refused like NaN, since their squares (ray-sphere tests, normalisation) would overflow
// float, and a camera or a triangle there renders as NaN. 1e18 squared is 1e36 < 3.4e38.
constexpr double max_coordinate = 1e18;

// The limits in force for this process: the defaults unless `--limit` changed them.
inline input_limits& limits() {
  static input_limits current;
  return current;
}

// "(raise with --limit NAME=N)": the one wording every limit error ends with.
ZRAKA_COMPILED_FN std::string raise_hint(std::string_view name);

// Throws "WHAT is N, more than the limit of M (raise with --limit NAME=N)" when value > limit.
ZRAKA_COMPILED_FN void check_limit(std::uint64_t value, std::uint64_t limit, std::string_view name, const std::string& what);

// Sets one limit from "NAME=VALUE" (the argument of --limit).
inline void set_limit(input_limits& l, std::string_view assignment) {
  const auto eq = assignment.find('=');
  const std::string_view name = assignment.substr(0, eq);
  std::uint64_t* field = name == "file_bytes"         ? &l.file_bytes
                         : name == "yaml_nodes"       ? &l.yaml_nodes
                         : name == "triangles"        ? &l.triangles
                         : name == "vertices"         ? &l.vertices
                         : name == "patches"          ? &l.patches
                         : name == "pixels"           ? &l.pixels
                         : name == "samples"          ? &l.samples
                         : name == "threads_per_core" ? &l.threads_per_core
                                                      : nullptr;
  if (!field)
    throw error("--limit: unknown limit '" + std::string(name) +
                "' (file_bytes, yaml_nodes, triangles, vertices, patches, pixels, samples, threads_per_core)");
  if (eq == std::string_view::npos) throw error("--limit: expected NAME=VALUE, got '" + std::string(assignment) + "'");
  const std::string_view value = assignment.substr(eq + 1);
  std::uint64_t x = 0;
  const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), x);
  if (ec != std::errc() || end != value.data() + value.size() || x == 0)
    throw error("--limit " + std::string(name) + ": expected a positive integer, got '" + std::string(value) + "'");
  *field = x;
}

// The work of one render: pixels and pixels x spp within the limits.
ZRAKA_COMPILED_FN void check_render_size(long long width, long long height, long long spp);

// Threads a program may start: threads_per_core for each hardware thread.
inline long long max_threads() {
  const unsigned cores = std::thread::hardware_concurrency();
  return (long long)(cores ? cores : 1) * (long long)std::min<std::uint64_t>(limits().threads_per_core, 1u << 20);
}

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN std::string raise_hint(std::string_view name) {
  return "(raise with --limit " + std::string(name) + "=N)";
}

ZRAKA_COMPILED_FN void check_limit(std::uint64_t value, std::uint64_t limit, std::string_view name, const std::string& what) {
  if (value > limit)
    throw error(what + " is " + std::to_string(value) + ", more than the limit of " + std::to_string(limit) + " " +
                raise_hint(name));
}

ZRAKA_COMPILED_FN void check_render_size(long long width, long long height, long long spp) {
  const auto pixels = std::uint64_t(width) * std::uint64_t(height);
  check_limit(pixels, limits().pixels, "pixels", "the image size " + std::to_string(width) + "x" + std::to_string(height) + " in pixels");
  const std::uint64_t s = spp > 0 ? std::uint64_t(spp) : 0;
  if (s != 0 && pixels > limits().samples / s)  // pixels * s would exceed the limit (no overflow)
    throw error(std::to_string(width) + "x" + std::to_string(height) + " pixels at " + std::to_string(spp) +
                " spp are more samples than the limit of " + std::to_string(limits().samples) + " " +
                raise_hint("samples"));
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

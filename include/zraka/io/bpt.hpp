#pragma once
// Loading Bezier patch sets in the .bpt text format (book 1.4; thesis Listing 4.1's teapot data):
//   line 1:        P V                  the patch count and the vertex count
//   next P lines:  16 vertex indices    one-based, row by row: entry 4*row + col (bezier_patch.hpp)
//   next V lines:  x y z                the control points; index 1 is the first
// Blank lines are skipped. Every error names the file and the line: a silently misread patch
// table shows up much later as a torn teapot.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/geometry/bezier_patch.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace zraka {

template <class T> struct patch_set_t {
  std::vector<vec3_t<T>> vertices;                     // the control points
  std::vector<std::array<std::uint32_t, 16>> patches;  // zero-based indices into vertices

  bezier_patch_t<T> patch(std::size_t k) const {
    bezier_patch_t<T> p;
    for (int i = 0; i < 16; ++i) p.P[i] = vertices[patches[k][i]];
    return p;
  }
  std::vector<bezier_patch_t<T>> all_patches() const {
    std::vector<bezier_patch_t<T>> out;
    for (std::size_t k = 0; k < patches.size(); ++k) out.push_back(patch(k));
    return out;
  }
};

using patch_set = patch_set_t<double>;

namespace detail {
class bpt_reader {
 public:
  bpt_reader(std::istream& in, std::string name) : in_(in), name_(std::move(name)) {}

  // The whitespace-separated fields of the next non-blank line; false at the end of the file.
  bool next(std::vector<std::string>& fields) {
    std::string line;
    while (std::getline(in_, line)) {
      ++line_no_;
      std::istringstream s(line);
      fields.clear();
      for (std::string f; s >> f;) fields.push_back(f);
      if (!fields.empty()) return true;
    }
    return false;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw error(name_ + ":" + std::to_string(line_no_) + ": " + what);
  }
  [[noreturn]] void fail_at_end(const std::string& what) const {
    throw error(name_ + ": file ends early: " + what);
  }
  long long integer(const std::string& f) const {
    long long x = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
    if (ec != std::errc() || end != f.data() + f.size()) fail("'" + f + "' is not an integer");
    return x;
  }
  double number(const std::string& f) const {
    double x = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), x);
    if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(x))
      fail("'" + f + "' is not a finite number");
    return x;
  }

 private:
  std::istream& in_;
  std::string name_;
  int line_no_ = 0;
};
}  // namespace detail

// Reads a patch set from a stream; `name` is used in error messages.
template <class T = double> patch_set_t<T> parse_bpt(std::istream& in, const std::string& name) {
  detail::bpt_reader rd(in, name);
  std::vector<std::string> f;
  if (!rd.next(f)) rd.fail_at_end("no header line 'P V' (patch and vertex counts)");
  if (f.size() != 2)
    rd.fail("the header must be 'P V' (two counts), found " + std::to_string(f.size()) +
            " field(s)");
  const long long P = rd.integer(f[0]), V = rd.integer(f[1]);
  // Checked before anything is read or reserved: the header alone must not ask for gigabytes.
  const auto max_p = static_cast<long long>(std::min<std::uint64_t>(limits().patches, 1ULL << 40));
  const auto max_v = static_cast<long long>(std::min<std::uint64_t>(limits().vertices, 1ULL << 40));
  if (P < 1 || P > max_p)
    rd.fail("patch count " + f[0] + " is out of range 1.." + std::to_string(max_p) + " " + raise_hint("patches"));
  if (V < 1 || V > max_v)
    rd.fail("vertex count " + f[1] + " is out of range 1.." + std::to_string(max_v) + " " + raise_hint("vertices"));

  patch_set_t<T> set;
  for (long long k = 0; k < P; ++k) {
    if (!rd.next(f))
      rd.fail_at_end("read " + std::to_string(k) + " of " + std::to_string(P) + " patch lines");
    if (f.size() != 16)
      rd.fail("patch " + std::to_string(k + 1) + " needs 16 indices, found " +
              std::to_string(f.size()));
    std::array<std::uint32_t, 16> idx{};
    for (int i = 0; i < 16; ++i) {
      const long long x = rd.integer(f[i]);
      if (x < 1 || x > V) rd.fail("index " + f[i] + " is out of range 1.." + std::to_string(V));
      idx[i] = static_cast<std::uint32_t>(x - 1);  // one-based in the file
    }
    set.patches.push_back(idx);
  }
  for (long long k = 0; k < V; ++k) {
    if (!rd.next(f))
      rd.fail_at_end("read " + std::to_string(k) + " of " + std::to_string(V) + " vertex lines");
    if (f.size() != 3)
      rd.fail("vertex " + std::to_string(k + 1) + " needs 3 coordinates, found " +
              std::to_string(f.size()));
    const vec3_t<T> x(T(rd.number(f[0])), T(rd.number(f[1])), T(rd.number(f[2])));
    if (!is_finite(x)) rd.fail("vertex " + std::to_string(k + 1) + " overflows this precision");
    for (int i = 0; i < 3; ++i)
      if (std::abs(double(x[i])) > max_coordinate)
        rd.fail("vertex " + std::to_string(k + 1) + ": " + f[i] + " is beyond +-1e18 (its square would overflow)");
    set.vertices.push_back(x);
  }
  if (rd.next(f)) rd.fail("unexpected data after the last vertex: '" + f[0] + "'");
  return set;
}

template <class T = double> patch_set_t<T> load_bpt(const std::filesystem::path& path) {
  std::istringstream in(read_input_file(path));  // a regular file within limits().file_bytes
  return parse_bpt<T>(in, path.string());
}

ZRAKA_INSTANCE(patch_set_t<double> parse_bpt<double>(std::istream&, const std::string&))  // compiled.hpp
ZRAKA_INSTANCE(patch_set_t<double> load_bpt<double>(const std::filesystem::path&))
ZRAKA_INSTANCE(patch_set_t<float> parse_bpt<float>(std::istream&, const std::string&))  // the GPU's (3.2)
ZRAKA_INSTANCE(patch_set_t<float> load_bpt<float>(const std::filesystem::path&))

}  // namespace zraka

#pragma once
// OBJ (Wavefront) meshes to zraka::mesh (book 4.1), thesis Def 4.1.3 done fully (erratum C9):
// v, vn, vt; faces f v, v/vt, v//vn, v/vt/vn; negative indices count back from the last vertex
// defined so far; polygons are fanned into triangles. vn are per-vertex normals referenced by
// the faces; a vertex used with two different normals becomes two mesh vertices. Normals are kept
// only if every face corner has one (otherwise the mesh is shaded flat); so are texture
// coordinates (vt u [v [w]]: mesh.texcoords, for image textures; otherwise uv are barycentric).
//
//   const zraka::mesh m = zraka::load_obj("scenes/meshes/cube.obj");
//
// Strict, like the scene files: every number must be a finite number within max_coordinate,
// every index must name an element defined before it, and anything else is an error
// "FILE:LINE:COLUMN: what". Names (o, g), smoothing groups (s) and materials (usemtl, mtllib)
// are skipped: a scene gives the material. The counts are bounded by limits() (limits.hpp).
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/limits.hpp>
#include <zraka/geometry/mesh.hpp>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

namespace zraka {

// Reads OBJ text; `name` is used in error messages.
ZRAKA_COMPILED_FN mesh parse_obj(std::string_view text, const std::string& name);

// Reads an OBJ file (a regular file within limits().file_bytes, see input_file.hpp).
ZRAKA_COMPILED_FN mesh load_obj(const std::filesystem::path& path);

// The reader is compiled once into zraka::compiled (compiled.hpp): a program's unit then parses
// none of it (~0.6 CPU-s for every scene-loading chapter).
#if ZRAKA_COMPILED_DEFINITIONS
namespace detail {

class obj_reader {
 public:
  explicit obj_reader(std::string name) : name_(std::move(name)) {}

  mesh read(std::string_view text) {
    std::size_t pos = 0;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      ++line_no_;
      line_ = text.substr(pos, end - pos);
      statement();
      pos = end + 1;
    }
    if (corners_.empty()) throw error(name_ + ": no faces");
    return build();
  }

 private:
  struct corner {
    std::uint32_t position;
    std::int64_t normal;  // -1: none
    std::int64_t texcoord = -1;  // -1: none
  };
  std::string name_;
  int line_no_ = 0;
  std::string_view line_;
  std::size_t col_ = 0;       // where the next token starts its search (0-based)
  std::size_t tok_col_ = 0;   // column of the last token (0-based)
  std::vector<vec3> positions_, normals_;
  std::vector<vec2> texcoords_;
  std::vector<corner> corners_;  // three per triangle
  bool all_normals_ = true, all_texcoords_ = true;

  [[noreturn]] void fail(const std::string& what) const {
    throw error(name_ + ":" + std::to_string(line_no_) + ":" + std::to_string(tok_col_ + 1) + ": " + what);
  }
  static bool space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }
  // The next whitespace-separated token of the line ("" at its end, or at a '#' comment).
  std::string_view token() {
    while (col_ < line_.size() && space(line_[col_])) ++col_;
    if (col_ < line_.size() && line_[col_] == '#') col_ = line_.size();
    const std::size_t start = col_;
    while (col_ < line_.size() && !space(line_[col_])) ++col_;
    tok_col_ = start;
    return line_.substr(start, col_ - start);
  }

  double number(std::string_view t, const char* what) {
    if (t.empty()) fail(std::string("expected ") + what + ", the line ends");
    std::string_view digits = t;
    if (digits.front() == '+') digits.remove_prefix(1);  // from_chars takes '-' but not '+'
    double x = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
    if (ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(x))
      fail(std::string(what) + ": '" + std::string(t) + "' is not a finite number");
    if (std::abs(x) > max_coordinate)
      fail(std::string(what) + ": " + std::string(t) + " is beyond +-1e18 (its square would overflow)");
    return x;
  }
  vec3 three_numbers(const char* what) {
    vec3 v;
    for (int i = 0; i < 3; ++i) v[i] = number(token(), what);
    return v;
  }
  void no_more(const char* statement, int allowed_extra = 0) {
    for (int i = 0;; ++i) {
      const std::string_view t = token();
      if (t.empty()) return;
      if (i >= allowed_extra) fail(std::string("unexpected '") + std::string(t) + "' after the " + statement);
      (void)number(t, statement);
    }
  }
  void count(std::uint64_t n, const char* what) {
    if (n >= limits().vertices)
      fail(std::string("more ") + what + " than the limit of " + std::to_string(limits().vertices) + " " +
           raise_hint("vertices"));
  }

  void statement() {
    col_ = 0;
    const std::string_view key = token();
    if (key.empty()) return;  // a blank line or a comment
    if (key == "v") {
      count(positions_.size(), "vertices");
      positions_.push_back(three_numbers("vertex coordinate"));
      no_more("vertex", 3);  // an optional w, or a colour r g b as some exporters write
    } else if (key == "vn") {
      count(normals_.size(), "normals");
      normals_.push_back(three_numbers("normal coordinate"));
      no_more("normal");
    } else if (key == "vt") {
      count(texcoords_.size(), "texture coordinates");
      const double u = number(token(), "texture coordinate");
      const std::string_view tv = token();  // v is optional (1-D textures), and so is w
      texcoords_.push_back({u, tv.empty() ? 0.0 : number(tv, "texture coordinate")});
      if (!tv.empty()) no_more("texture coordinate", 1);
    } else if (key == "f") {
      face();
    } else if (key == "o" || key == "g" || key == "s" || key == "usemtl" || key == "mtllib") {
      // names, smoothing groups and materials: nothing to build
    } else if (key == "l" || key == "p") {
      // (appended piece by piece: GCC 12's -Wrestrict misfires on "literal" + std::string at -O3)
      std::string msg = "'";
      msg.append(key).append("' (a line or a point) has no surface; only faces (f) are rendered");
      fail(msg);
    } else {
      std::string msg = "unknown statement '";
      msg.append(key).append("' (expected v, vn, vt, f, o, g, s, usemtl or mtllib)");
      fail(msg);
    }
  }

  // One index of a face corner: 1-based, or negative counting back from the last one so far.
  std::int64_t index(std::string_view t, std::size_t defined, const char* what) {
    long long x = 0;
    const auto [end, ec] = std::from_chars(t.data(), t.data() + t.size(), x);
    const std::string s(t);
    if (ec == std::errc::result_out_of_range) fail(std::string(what) + " index " + s + " overflows");
    if (ec != std::errc() || end != t.data() + t.size())
      fail(std::string(what) + " index '" + s + "' is not an integer");
    if (x == 0) fail(std::string(what) + " index 0: OBJ indices start at 1 (or count back from -1)");
    const long long n = static_cast<long long>(defined);
    if (x > n)
      fail("refers to " + std::string(what) + " " + s + ", but only " + std::to_string(n) + " are defined before it");
    if (x < -n)
      fail("refers to " + std::string(what) + " " + s + " (counting back), but only " + std::to_string(n) +
           " are defined before it");
    return x > 0 ? x - 1 : n + x;
  }

  void face() {
    const std::size_t first_corner = corners_.size();
    std::size_t n = 0;
    corner c0{}, prev{};
    for (std::string_view t = token(); !t.empty(); t = token(), ++n) {
      const std::size_t token_col = tok_col_;
      const std::size_t s1 = t.find('/');
      const std::string_view v = t.substr(0, s1);
      corner c{std::uint32_t(index(v, positions_.size(), "vertex")), -1};
      if (s1 != std::string_view::npos) {
        const std::string_view rest = t.substr(s1 + 1);
        const std::size_t s2 = rest.find('/');
        const std::string_view vt = rest.substr(0, s2);
        if (!vt.empty()) c.texcoord = index(vt, texcoords_.size(), "texture coordinate");
        if (s2 != std::string_view::npos) {
          const std::string_view vn = rest.substr(s2 + 1);
          if (vn.empty() || vn.find('/') != std::string_view::npos)
            fail("a face corner is v, v/vt, v//vn or v/vt/vn, got '" + std::string(t) + "'");
          c.normal = index(vn, normals_.size(), "normal");
        } else if (vt.empty()) {
          fail("a face corner is v, v/vt, v//vn or v/vt/vn, got '" + std::string(t) + "'");
        }
      }
      tok_col_ = token_col;
      all_normals_ = all_normals_ && c.normal >= 0;
      all_texcoords_ = all_texcoords_ && c.texcoord >= 0;
      if (n == 0) c0 = c;
      if (n >= 2) {  // fan: (first, previous, this)
        if (corners_.size() / 3 >= limits().triangles)
          fail("more triangles than the limit of " + std::to_string(limits().triangles) + " " +
               raise_hint("triangles"));
        corners_.push_back(c0);
        corners_.push_back(prev);
        corners_.push_back(c);
      }
      prev = c;
    }
    if (n < 3) {
      corners_.resize(first_corner);
      tok_col_ = 0;
      fail("a face needs at least 3 corners, got " + std::to_string(n));
    }
  }

  // [listing obj-vertex]
  // A mesh vertex is a (position, normal, texture coordinate) triple: the OBJ's separate index
  // lists become one. Normals (and texture coordinates) are kept only if every corner has one.
  mesh build() const {
    mesh m;
    std::map<std::tuple<std::uint32_t, std::int64_t, std::int64_t>, std::uint32_t> vertex_of;
    auto vertex = [&](const corner& c) {
      const std::int64_t n = all_normals_ ? c.normal : -1, uv = all_texcoords_ ? c.texcoord : -1;
      const auto [it, is_new] = vertex_of.try_emplace({c.position, n, uv}, std::uint32_t(m.positions.size()));
      if (is_new) {
        m.positions.push_back(positions_[c.position]);
        if (n >= 0) m.normals.push_back(normalize_or_zero(normals_[std::size_t(n)]));
        if (uv >= 0) m.texcoords.push_back(texcoords_[std::size_t(uv)]);
      }
      return it->second;
    };
    // [end]
    m.triangles.reserve(corners_.size() / 3);
    for (std::size_t i = 0; i < corners_.size(); i += 3)
      m.triangles.push_back({vertex(corners_[i]), vertex(corners_[i + 1]), vertex(corners_[i + 2])});
    return m;
  }
};

}  // namespace detail

ZRAKA_COMPILED_FN mesh parse_obj(std::string_view text, const std::string& name) {
  return detail::obj_reader(name).read(text);
}

ZRAKA_COMPILED_FN mesh load_obj(const std::filesystem::path& path) {
  return parse_obj(read_input_file(path), path.string());
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

// The .bpt patch loader: the teapot's facts (data README) and an error for each kind of bad file.
#include <zraka/core/resources.hpp>
#include <zraka/geometry/aabb.hpp>
#include <zraka/io/bpt.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <set>
#include <sstream>

using namespace zraka;

namespace {
// The error message parse_bpt gives for `text`, or "" when it parses.
std::string parse_error(const std::string& text) {
  std::istringstream in(text);
  try {
    (void)parse_bpt(in, "bad.bpt");
  } catch (const error& e) {
    return e.what();
  }
  return "";
}
bool has(const std::string& s, const std::string& part) {
  return s.find(part) != std::string::npos;
}

// A valid file: one patch using all 16 of 16 vertices.
std::string one_patch(const std::string& header = "1 16", const std::string& indices = "",
                      int vertex_lines = 16, const std::string& last_vertex = "") {
  std::string s = header + "\n";
  if (indices.empty()) {
    for (int i = 1; i <= 16; ++i) s += std::to_string(i) + (i < 16 ? " " : "\n");
  } else {
    s += indices + "\n";
  }
  for (int k = 0; k < vertex_lines; ++k)
    s += (k == 15 && !last_vertex.empty())
             ? last_vertex + "\n"
             : std::to_string(k % 4) + " " + std::to_string(k / 4) + " 0\n";
  return s;
}
}  // namespace

TEST_CASE_TEMPLATE("the teapot: counts, index range, unused vertices", T, float, double) {
  const auto set = load_bpt<T>(resource_path("scenes/teapot.bpt"));
  CHECK(set.patches.size() == 32);
  CHECK(set.vertices.size() == 306);
  std::set<std::uint32_t> used;
  for (const auto& p : set.patches)
    for (const auto i : p) {
      CHECK(i < 306);  // every one-based index was in 1..306
      used.insert(i + 1);
    }
  std::vector<std::uint32_t> unused;
  for (std::uint32_t i = 1; i <= 306; ++i)
    if (!used.count(i)) unused.push_back(i);
  CHECK(unused == std::vector<std::uint32_t>{205, 206, 216, 223});
  // Patches 21-24 start with vertex 204 four times, 29-32 with 270 (the collapsed rows).
  for (int k = 21; k <= 32; ++k) {
    if (k > 24 && k < 29) continue;
    for (int i = 0; i < 4; ++i) CHECK(set.patches[k - 1][i] + 1 == (k <= 24 ? 204u : 270u));
  }
  // Control points as in the file (2.53125 kept exact; first line of vertices 1.4 0.0 2.4).
  CHECK(set.vertices[0] == vec3_t<T>(T(1.4), T(0), T(2.4)));
  // The control net's box: x from -3 (handle) to 3.525 (spout), y +-2, z from 0 to 3.15.
  aabb_t<T> box;
  for (const auto& p : set.vertices) box.grow(p);
  CHECK(box.lo == vec3_t<T>(T(-3.0), T(-2), T(0)));
  CHECK(box.hi == vec3_t<T>(T(3.525), T(2), T(3.15)));
  CHECK(std::any_of(set.vertices.begin(), set.vertices.end(),
                    [](const vec3_t<T>& p) { return p.z == T(2.53125); }));
}

TEST_CASE("a missing file names the file") {
  try {
    (void)load_bpt("no/such/teapot.bpt");
    FAIL("no error");
  } catch (const error& e) {
    CHECK(has(e.what(), "no/such/teapot.bpt: cannot open: No such file or directory"));
  }
}

TEST_CASE("a valid small file parses") {
  CHECK(parse_error(one_patch()) == "");
  CHECK(parse_error("\n\n" + one_patch() + "\n\n") == "");  // blank lines are skipped
  std::istringstream in(one_patch());
  const auto set = parse_bpt(in, "x");
  CHECK(set.patch(0).P[5] == vec3(1, 1, 0));
}

TEST_CASE("bad counts in the header") {
  CHECK(has(parse_error(""), "bad.bpt: file ends early: no header"));
  CHECK(has(parse_error("32\n"), "bad.bpt:1: the header must be 'P V'"));
  CHECK(has(parse_error("0 16\n"), "bad.bpt:1: patch count 0 is out of range"));
  CHECK(has(parse_error("1 -3\n"), "bad.bpt:1: vertex count -3 is out of range"));
  CHECK(has(parse_error("99999999999 16\n"), "bad.bpt:1: patch count 99999999999 is out of range"));
  CHECK(has(parse_error("x 16\n"), "bad.bpt:1: 'x' is not an integer"));
  CHECK(has(parse_error("1.5 16\n"), "bad.bpt:1: '1.5' is not an integer"));
}

TEST_CASE("indices: count, range, not numbers") {
  CHECK(
      has(parse_error(one_patch("1 16", "1 2 3")), "bad.bpt:2: patch 1 needs 16 indices, found 3"));
  CHECK(has(parse_error(one_patch("1 16", "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 17")),
            "bad.bpt:2: index 17 is out of range 1..16"));
  CHECK(has(parse_error(one_patch("1 16", "0 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16")),
            "bad.bpt:2: index 0 is out of range 1..16"));
  CHECK(has(parse_error(one_patch("1 16", "1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 1x")),
            "bad.bpt:2: '1x' is not an integer"));
}

TEST_CASE("vertices: count, not numbers, not finite") {
  CHECK(has(parse_error(one_patch("1 16", "", 16, "1 2")),
            "bad.bpt:18: vertex 16 needs 3 coordinates"));
  CHECK(has(parse_error(one_patch("1 16", "", 16, "1 two 3")),
            "bad.bpt:18: 'two' is not a finite number"));
  CHECK(has(parse_error(one_patch("1 16", "", 16, "1 nan 3")),
            "bad.bpt:18: 'nan' is not a finite number"));
  CHECK(has(parse_error(one_patch("1 16", "", 16, "1 1e999 3")), "'1e999' is not a finite number"));
  // Finite in double but not in float.
  std::istringstream in(one_patch("1 16", "", 16, "1 1e300 3"));
  try {
    (void)parse_bpt<float>(in, "f.bpt");
    FAIL("no error");
  } catch (const error& e) {
    CHECK(has(e.what(), "f.bpt:18: vertex 16 overflows this precision"));
  }
}

TEST_CASE("truncated files and trailing data") {
  CHECK(has(parse_error("2 16\n1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16\n"),
            "bad.bpt: file ends early: read 1 of 2 patch lines"));
  CHECK(has(parse_error(one_patch("1 16", "", 10)),
            "bad.bpt: file ends early: read 10 of 16 vertex lines"));
  CHECK(has(parse_error(one_patch() + "1 2 3\n"),
            "bad.bpt:19: unexpected data after the last vertex"));
}

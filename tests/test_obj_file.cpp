// Tests for obj_file.hpp: the OBJ forms (erratum C9), every malformed file in tests/scenes/bad/obj
// gives the error its first line expects (file:line:column), the limits, and degenerate but
// finite geometry stays legal.
#include <zraka/core/resources.hpp>
#include <zraka/io/obj_file.hpp>

#include <doctest/doctest.h>

#include "expected_errors.hpp"

#include <algorithm>
#include <fstream>
#include <functional>

using namespace zraka;
namespace fs = std::filesystem;
using zraka_test::error_of;

namespace {
const std::string vertices = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0.5 1.5 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.5 1\n"
                             "vn 0 0 1\nvn 0 0 2\n";
}  // namespace

TEST_CASE("OBJ faces f v, v/vt, v//vn, v/vt/vn, negative indices and polygons (C9)") {
  struct variant {
    const char* name;
    const char* face;
    std::size_t triangles;
    bool normals;
  };
  const variant variants[] = {
      {"v", "f 1 2 3\nf 1 3 4\n", 2, false},
      {"v-vt", "f 1/1 2/2 3/3 4/4\n", 2, false},                         // a quad, fanned
      {"v-vn", "f 1//1 2//1 3//2 5//1 4//2\n", 3, true},                 // a pentagon
      {"v-vt-vn", "f 1/1/1 2/2/1 3/3/1\n", 1, true},
      {"negative", "f -5 -4 -3\nf -5/-5/-2 -3/-3/-1 -2/-2/-2\n", 2, false},  // relative to the end
  };
  for (const variant& v : variants) {
    INFO(v.name);
    // negative: without vn on every corner the mesh is shaded flat (no normals kept).
    const mesh m = parse_obj(vertices + v.face, v.name);
    CHECK(m.triangle_count() == v.triangles);
    CHECK((m.normals.size() == m.positions.size()) == v.normals);
    for (std::size_t i = 0; i < m.triangle_count(); ++i) CHECK(m.triangle(i).normal() == vec3(0, 0, 1));
    for (const vec3& n : m.normals) CHECK(n == vec3(0, 0, 1));  // vn 0 0 2 normalised
  }
  // -5 is the first of five vertices: the negative-index triangle is (0,0,0), (1,0,0), (1,1,0).
  const mesh neg = parse_obj(vertices + "f -5 -4 -3\n", "neg");
  CHECK(neg.triangle(0).a == vec3(0, 0, 0));
  CHECK(neg.triangle(0).c == vec3(1, 1, 0));
  // Names, groups, smoothing and materials are skipped; '+' signs, CRLF and a w are read.
  const mesh misc = parse_obj("mtllib a.mtl\no thing\ng part\ns 1\nusemtl red\r\nv +1 0 0 1\r\nv 0 1 0\nv 0 0 1\n"
                              "# a comment\nf 1 2 3 # a trailing comment\r\n", "misc");
  CHECK(misc.triangle_count() == 1);
  CHECK(misc.positions[0] == vec3(1, 0, 0));
  // The cube in scenes/meshes: six squares, twelve triangles, every face normal pointing out.
  const mesh cube = load_obj(resource_root() / "scenes/meshes/cube.obj");
  REQUIRE(cube.triangle_count() == 12);
  for (std::size_t i = 0; i < 12; ++i) {
    const triangle t = cube.triangle(i);
    CHECK(glm::dot(t.normal(), (t.a + t.b + t.c) / 3.0) > 0);
  }
  CHECK(load_obj(resource_root() / "scenes/meshes/icosphere.obj").triangle_count() == 320);
}

TEST_CASE("OBJ: degenerate but finite geometry stays legal") {
  // A triangle on one point, one on a line, a zero normal, coordinates at +-1e18.
  const mesh m = parse_obj("v 0 0 0\nv 1e18 -1e18 0\nvn 0 0 0\nf 1//1 1//1 1//1\nf 1//1 2//1 2//1\n", "degenerate");
  CHECK(m.triangle_count() == 2);
  CHECK(m.normals[0] == vec3(0));
}

TEST_CASE("OBJ: each malformed file in tests/scenes/bad/obj gives the error its first line expects") {
  zraka_test::check_expected_errors(resource_root() / "tests" / "scenes" / "bad" / "obj", ".obj", "# expect: ", "", 20, true,
                                    [](const fs::path& f) { (void)load_obj(f); });
}

TEST_CASE("OBJ: the counts are bounded by limits(), at the line that exceeds them") {
  const input_limits saved = limits();
  set_limit(limits(), "vertices=2");
  CHECK(error_of([] { parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n", "m.obj"); }) ==
        "m.obj:3:1: more vertices than the limit of 2 (raise with --limit vertices=N)");
  CHECK(error_of([] { parse_obj("v 0 0 0\nvn 0 0 1\nvn 0 0 1\nvn 0 0 1\n", "m.obj"); }) ==
        "m.obj:4:1: more normals than the limit of 2 (raise with --limit vertices=N)");
  limits() = saved;
  set_limit(limits(), "triangles=1");
  CHECK(error_of([] { parse_obj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "m.obj"); }) ==
        "m.obj:5:9: more triangles than the limit of 1 (raise with --limit triangles=N)");
  limits() = saved;
}

TEST_CASE("OBJ: only regular files are read, and only up to limits().file_bytes") {
  CHECK(error_of([] { load_obj("/dev/zero"); }) == "/dev/zero: is a character device; only regular files are read");
  const fs::path dir = resource_root() / "scenes" / "meshes";
  CHECK(error_of([&] { load_obj(dir); }) == dir.string() + ": is a directory; only regular files are read");
  CHECK(error_of([] { load_obj("/no/such/file.obj"); }) == "/no/such/file.obj: cannot open: No such file or directory");
  const input_limits saved = limits();
  set_limit(limits(), "file_bytes=100");
  const std::string cube = (dir / "cube.obj").string();
  CHECK(error_of([&] { load_obj(cube); }).find(cube + ": the file size ") == 0);
  CHECK(error_of([&] { load_obj(cube); }).find("bytes is more than the limit of 100 (raise with --limit file_bytes=N)") !=
        std::string::npos);
  limits() = saved;
}

// links: assimp yaml-cpp
// Tests for mesh_file.hpp: the same sphere read from OBJ, PLY, glTF and GLB gives the same
// triangles; glTF's texture orientation (the texel reached at a known point); every malformed
// file in tests/scenes/bad/mesh gives its expected error; the limits; `material: from-file`.
#include <zraka/core/resources.hpp>
#include <zraka/io/mesh_file.hpp>
#include <zraka/io/scene_file.hpp>

#include "expected_errors.hpp"

#include <doctest/doctest.h>

#include <fstream>
#include <functional>
#include <sstream>

using namespace zraka;
namespace fs = std::filesystem;
using zraka_test::error_of;

namespace {
fs::path meshes() { return resource_root() / "scenes" / "meshes"; }
std::string text_of(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}
// quad.gltf's text to be changed and written into `dir` (made here), its texture found from there.
std::string quad_gltf_text(const fs::path& dir) {
  fs::create_directories(dir);
  std::string t = text_of(meshes() / "quad.gltf");
  t.replace(t.find("../uv-grid.png"), 14, (resource_root() / "scenes" / "uv-grid.png").string());
  return t;
}
// The texel that a ray straight down -z onto the unit quad at (x, y) reaches.
rgb texel_at(const mesh& m, const texture& t, double x, double y) {
  hit rec;
  mesh_shading_t<double> sh;
  REQUIRE(intersect(m, ray{vec3(x, y, 1), vec3(0, 0, -1)}, 1e-9, 10.0, rec, sh));
  const vec2 uv = m.texcoord(sh.triangle, rec.uv.x, rec.uv.y);
  return evaluate(t, rec.p, rec.normal, uv);
}
}  // namespace

TEST_CASE("mesh files: one sphere as OBJ, PLY, glTF and GLB gives the same triangles") {
  const mesh obj = read_mesh_file(meshes() / "sphere.obj");
  REQUIRE(obj.triangle_count() == 528);
  for (const char* f : {"sphere.ply", "sphere.gltf", "sphere.glb"}) {
    INFO(f);
    const mesh m = read_mesh_file(meshes() / f);
    REQUIRE(m.triangle_count() == obj.triangle_count());
    REQUIRE(m.normals.size() == m.positions.size());
    REQUIRE(m.texcoords.size() == m.positions.size());
    double worst = 0;
    for (std::size_t i = 0; i < m.triangle_count(); ++i)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = m.triangles[i][std::size_t(k)], b = obj.triangles[i][std::size_t(k)];
        // float in the binary files, 9 significant digits in the OBJ: the same floats
        worst = std::max({worst, glm::length(m.positions[a] - obj.positions[b]),
                          glm::length(m.normals[a] - obj.normals[b]), glm::length(m.texcoords[a] - obj.texcoords[b])});
      }
    CHECK(worst < 1e-6);
  }
  // The glTF ones carry the uv grid as their base colour; PLY has no material.
  CHECK(load_mesh_file(meshes() / "sphere.gltf").base_colour->type == texture::kind::image);
  CHECK(load_mesh_file(meshes() / "sphere.glb").base_colour->type == texture::kind::image);
  const mesh_file_contents ply = load_mesh_file(meshes() / "sphere.ply");
  CHECK(!ply.base_colour);
  CHECK(ply.base_colour_problem == "a PLY file has no material");
}

TEST_CASE("mesh files: glTF's v counts from the image's top, and reaches the same texel as OBJ's") {
  // quad.gltf stores uv (0, 1) at the origin, where quad.obj stores (0, 0): both mean the
  // image's bottom-left corner, where uv-grid.png has its white mark.
  const mesh_file_contents g = load_mesh_file(meshes() / "quad.gltf");
  REQUIRE(g.base_colour);
  const mesh obj = read_mesh_file(meshes() / "quad.obj");
  CHECK(g.geometry.texcoords[0] == vec2(0, 0));
  for (const auto& [x, y] : {std::pair{0.06, 0.06}, {0.94, 0.94}, {0.5, 0.3}, {0.2, 0.8}}) {
    INFO(x << ", " << y);
    const rgb a = texel_at(g.geometry, *g.base_colour, x, y), b = texel_at(obj, *g.base_colour, x, y);
    CHECK(glm::length(glm::vec3(a - b)) < 1e-6f);
  }
  const rgb mark = texel_at(g.geometry, *g.base_colour, 0.06, 0.06);
  CHECK(std::min({mark.r, mark.g, mark.b}) > 0.9f);  // white
  const rgb top_right = texel_at(g.geometry, *g.base_colour, 0.94, 0.94);
  CHECK(top_right.r > 0.5f);  // red grows with u, green with v
  CHECK(top_right.g > 0.5f);
  const rgb bottom_right = texel_at(g.geometry, *g.base_colour, 0.94, 0.06);
  CHECK(bottom_right.r > 0.5f);
  CHECK(bottom_right.g < top_right.g);
}

TEST_CASE("mesh files: each malformed file in tests/scenes/bad/mesh gives its expected error") {
  const fs::path dir = resource_root() / "tests" / "scenes" / "bad" / "mesh";
  std::ifstream in(dir / "expect.txt");
  REQUIRE(in);
  int n = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t colon = line.find(": ");
    const fs::path f = dir / line.substr(0, colon);
    const std::string words = line.substr(colon + 2), got = error_of([&] { load_mesh_file(f); });
    INFO(f.filename().string() << "\ngot: " << got << "\nexpected the words: " << words);
    CHECK(got.rfind(f.string() + ":", 0) == 0);  // names the file
    CHECK(got.find(words) != std::string::npos);
    ++n;
  }
  CHECK(n >= 20);
}

TEST_CASE("mesh files: limits, types, and only regular files (the .bin too)") {
  const input_limits saved = limits();
  set_limit(limits(), "vertices=100");
  CHECK(error_of([] { load_mesh_file(meshes() / "sphere.ply"); })
            .find("325 vertices, more than the limit of 100 (raise with --limit vertices=N)") != std::string::npos);
  CHECK(error_of([] { load_mesh_file(meshes() / "sphere.glb"); })
            .find("more than the limit of 100 vertices (raise with --limit vertices=N)") != std::string::npos);
  limits() = saved;
  set_limit(limits(), "file_bytes=4000");  // sphere.gltf is ~1.6 kB, its sphere.bin ~17 kB
  const std::string bin_error = error_of([] { load_mesh_file(meshes() / "sphere.gltf"); });
  CHECK(bin_error.find("sphere.bin: the file size 16736 bytes is more than the limit of 4000") != std::string::npos);
  limits() = saved;
  CHECK(error_of([] { load_mesh_file("/dev/zero.ply"); }) == "/dev/zero.ply: cannot open: No such file or directory");
  CHECK(error_of([] { load_mesh_file("/dev/zero"); }) == "/dev/zero: is a character device; only regular files are read");
  CHECK(error_of([] { load_mesh_file(meshes()); }) == meshes().string() + ": is a directory; only regular files are read");
}

TEST_CASE("mesh files: a glTF material that is more than a base colour is refused by name") {
  const fs::path dir = fs::temp_directory_path() / "zraka-test-mesh-file";
  std::string t = quad_gltf_text(dir);
  t.replace(t.find("\"metallicFactor\": 0"), 19, "\"metallicFactor\": 1");
  std::ofstream(dir / "metal.gltf") << t;
  const mesh_file_contents c = load_mesh_file(dir / "metal.gltf");
  CHECK(!c.base_colour);
  CHECK(c.base_colour_problem ==
        "the material 'uv-grid' has metallicFactor 1.000000 (a metal), which zraka does not map (only the base colour)");
  fs::remove_all(dir);
}

TEST_CASE("mesh files: a glTF node's transform moves points, turns normals and keeps the winding") {
  const fs::path dir = fs::temp_directory_path() / "zraka-test-mesh-node";
  std::string t = quad_gltf_text(dir);
  // A mirror in x (scale -1), then a quarter turn about y (quaternion x y z w), then a move.
  const std::size_t at = t.find("\"mesh\": 0");
  REQUIRE(at != std::string::npos);
  t.insert(at, "\"scale\": [-1, 1, 1], \"rotation\": [0, 0.70710678, 0, 0.70710678], \"translation\": [1, 2, 3], ");
  std::ofstream(dir / "moved.gltf") << t;
  const mesh m = read_mesh_file(dir / "moved.gltf");
  const mesh q = read_mesh_file(meshes() / "quad.obj");
  REQUIRE(m.triangle_count() == q.triangle_count());
  for (std::size_t i = 0; i < q.positions.size(); ++i) {
    const vec3 p = q.positions[i], mirrored(-p.x, p.y, p.z);
    const vec3 turned(mirrored.z, mirrored.y, -mirrored.x);  // +90 degrees about y
    CHECK(glm::length(m.positions[i] - (turned + vec3(1, 2, 3))) < 1e-6);
    CHECK(glm::length(m.normals[i] - vec3(1, 0, 0)) < 1e-6);  // (0, 0, 1) mirrored stays, turned to +x
  }
  for (std::size_t i = 0; i < m.triangle_count(); ++i)  // the winding follows the mirror
    CHECK(glm::dot(m.triangle(i).normal(), m.normals[m.triangles[i][0]]) > 0);
  fs::remove_all(dir);
}

TEST_CASE("scene files: meshes by extension, and material: from-file") {
  const loaded_scene g = load_scene_file(resource_root() / "scenes" / "gltf-model.yaml");
  bool textured = false;
  for (const material& m : g.sc.materials) textured = textured || (m.get<material_kinds::lambertian>() && m.get<material_kinds::lambertian>()->albedo.type == texture::kind::image);
  CHECK(textured);
  CHECK(g.resolved.find("material: from-file") != std::string::npos);
  (void)load_scene_file(resource_root() / "scenes" / "ply-mesh.yaml");
  const std::string head = "camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\nobjects:\n  - {type: mesh, file: ";
  const fs::path dir = resource_root() / "scenes";
  CHECK(error_of([&] { parse_scene(head + "meshes/sphere.ply, material: from-file}\n", "s.yaml", dir); }) ==
        "s.yaml:3:53: objects[0].material: from-file: meshes/sphere.ply: a PLY file has no material");
  CHECK(error_of([&] { parse_scene(head + "meshes/nothing.gltf}\n", "s.yaml", dir); })
            .find("objects[0].file") != std::string::npos);
  CHECK(error_of([&] { parse_scene("materials: {from-file: {albedo: 0.5}}\n" + head + "meshes/sphere.ply}\n", "s.yaml", dir); })
            .find("materials.from-file: the name is reserved") != std::string::npos);
  CHECK(error_of([&] {
          parse_scene("camera: {position: [0, 0, 5], look_at: [0, 0, 0]}\nobjects:\n  - {type: sphere, material: from-file}\n",
                      "s.yaml", dir);
        }).find("only a mesh takes its material from its file") != std::string::npos);
}

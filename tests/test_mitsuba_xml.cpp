// links: yaml-cpp pugixml
// Mitsuba 3 XML scenes (mitsuba_xml.hpp): every malformed or out-of-subset file in
// tests/scenes/bad/xml gives its expected error (file, line, element, attribute); the Cornell box
// of scenes/mitsuba/ is the Cornell box of scenes/cornell.yaml, quad for quad; the sensor's
// conventions (fov_axis, lookat and matrix, max_depth); a mesh's to_world through zraka's
// scale-rotate-translate, half turns included; defaults and $name; limits and deep nesting.
#include <zraka/io/mitsuba_xml.hpp>
#include <zraka/io/scene_argument.hpp>

#include "expected_errors.hpp"

#include <doctest/doctest.h>

#include <fstream>

using namespace zraka;
using zraka_test::error_of;
namespace fs = std::filesystem;

namespace {

// A scene around `body`: a sensor, a path integrator and what the test adds.
std::string scene_xml(const std::string& body, const std::string& sensor_extra = "", int w = 64, int h = 32,
                      int depth = 5) {
  return "<scene version=\"3.0.0\">\n<integrator type=\"path\"><integer name=\"max_depth\" value=\"" +
         std::to_string(depth) + "\"/></integrator>\n<sensor type=\"perspective\">" +
         (sensor_extra.empty() ? "<float name=\"fov\" value=\"40\"/>" : sensor_extra) +
         "<film type=\"hdrfilm\"><integer name=\"width\" value=\"" + std::to_string(w) +
         "\"/><integer name=\"height\" value=\"" + std::to_string(h) +
         "\"/><rfilter type=\"box\"/></film></sensor>\n" + body + "\n</scene>\n";
}
const char* glass_sphere = "<shape type=\"sphere\"><bsdf type=\"dielectric\"/></shape>";
loaded_scene parse_xml(const std::string& text, const fs::path& dir = ".") {
  return parse_scene(mitsuba_xml_to_yaml(text, "t.xml", dir), "t.yaml", dir);
}
bool near(const vec3& a, const vec3& b, double tol = 1e-12) { return glm::length(a - b) <= tol; }
// The colour of a material that has an albedo (lambertian, metal); -1 for the others.
rgb albedo_a(const material& m) {
  if (const auto* k = m.get<material_kinds::lambertian>()) return k->albedo.a;
  if (const auto* k = m.get<material_kinds::fuzzy_metal>()) return k->albedo.a;
  return rgb(-1);
}

}  // namespace

TEST_CASE("Mitsuba XML: each bad file gives the error its first line expects") {
  zraka_test::check_expected_errors(resource_root() / "tests" / "scenes" / "bad" / "xml", ".xml", "<!-- expect: ", " -->",
                                    25, false, [](const fs::path& f) { (void)load_scene_argument(f.string()); });
}

TEST_CASE("Mitsuba XML: the Cornell box of scenes/mitsuba is scenes/cornell.yaml, quad for quad") {
  const scene x = load_scene_argument("scenes/mitsuba/cornell-box.xml").sc;
  const scene y = load_scene_argument("scenes/cornell.yaml").sc;
  CHECK(x.settings.width == y.settings.width);
  CHECK(x.settings.height == y.settings.height);
  CHECK(x.settings.spp == y.settings.spp);
  CHECK(x.settings.max_depth == y.settings.max_depth);
  CHECK(near(x.camera.position, y.camera.position));
  CHECK(near(glm::normalize(x.camera.look_at - x.camera.position), glm::normalize(y.camera.look_at - y.camera.position)));
  CHECK(near(x.camera.up, y.camera.up));
  CHECK(x.camera.vfov_degrees == doctest::Approx(y.camera.vfov_degrees));
  // Every quad of one has a quad in the other at the same centre, facing the same way, of the
  // same area and material colour (u and v may start from another corner).
  REQUIRE(x.quads.size() == y.quads.size());
  for (const auto& qx : x.quads) {
    const vec3 cx = qx.shape.corner + 0.5 * (qx.shape.u + qx.shape.v), nx = glm::cross(qx.shape.u, qx.shape.v);
    int matches = 0;
    for (const auto& qy : y.quads) {
      const vec3 cy = qy.shape.corner + 0.5 * (qy.shape.u + qy.shape.v), ny = glm::cross(qy.shape.u, qy.shape.v);
      const material& mx = x.materials[std::size_t(qx.material)];
      const material& my = y.materials[std::size_t(qy.material)];
      if (near(cx, cy, 1e-9) && near(nx, ny, 1e-9) && mx.kind.index() == my.kind.index() && albedo_a(mx) == albedo_a(my) &&
          mx.radiance == my.radiance)
        ++matches;
    }
    CHECK_MESSAGE(matches == 1, "quad centred at " << cx.x << " " << cx.y << " " << cx.z);
  }
}

TEST_CASE("Mitsuba XML: the scenes of scenes/mitsuba load, and their YAML loads again to the same") {
  for (const char* f : {"scenes/mitsuba/cornell-box.xml", "scenes/mitsuba/materials.xml", "scenes/mitsuba/veach-mis.xml",
                        "scenes/mitsuba/checkerboard.xml"}) {
    INFO(f);
    const loaded_scene ls = load_scene_argument(f);
    CHECK(ls.sc.bounded_count() > 0);
    const fs::path dir = resource_root() / "scenes" / "mitsuba";
    CHECK(parse_scene(ls.resolved, "again.yaml", dir).resolved == ls.resolved);
  }
  const loaded_scene m = load_scene_argument("scenes/mitsuba/materials.xml");
  REQUIRE(m.sc.environment);
  CHECK(m.sc.environment->rotate_degrees() == doctest::Approx(40));  // rotate y 40
  REQUIRE(m.sc.lights.size() == 1);
  REQUIRE(m.sc.lights[0].is<light_kinds::point>());
  CHECK(m.sc.lights[0].get<light_kinds::point>()->position == vec3(-2, 4, 3));
  // bk7 in air, Mitsuba's defaults; water inside air for the rough glass.
  int glass = 0;
  for (const material& mat : m.sc.materials) {
    if (mat.is<material_kinds::dielectric>()) {
      CHECK(mat.get<material_kinds::dielectric>()->ior == doctest::Approx(1.5046 / 1.000277));
      ++glass;
    }
    if (mat.is<material_kinds::rough_dielectric>()) {
      CHECK(mat.get<material_kinds::rough_dielectric>()->ior == doctest::Approx(1.333 / 1.000277));
      ++glass;
    }
  }
  CHECK(glass == 2);
  // The checkerboard: zraka's checker in uv, cells 1/2 / to_uv's scale 4, even cells color0.
  const loaded_scene c = load_scene_argument("scenes/mitsuba/checkerboard.xml");
  REQUIRE(c.sc.quads.size() == 2);
  const texture& t = c.sc.material_of({shape_kind::quad, 0}).get<material_kinds::lambertian>()->albedo;
  CHECK(t.type == texture::kind::checker);
  CHECK(t.uv_space);
  CHECK(t.cell == doctest::Approx(0.125));
  CHECK(t.a == rgb(0.8f, 0.2f, 0.1f));
  CHECK(t.b == rgb(0.1f, 0.3f, 0.7f));
  const texture& d = c.sc.material_of({shape_kind::quad, 1}).get<material_kinds::lambertian>()->albedo;  // Mitsuba's defaults
  CHECK(d.cell == doctest::Approx(0.5));
  CHECK(d.a == rgb(0.4f));
  CHECK(d.b == rgb(0.2f));
  // Not flipped as a bitmap's rectangle is: the quad's (a, b) are Mitsuba's (u, v).
  CHECK(c.sc.quads[1].shape.v.y > 0);
}

TEST_CASE("Mitsuba XML: a bitmap on a rectangle: zraka's image texture, the quad's v edge running down") {
  const scene sc = load_scene_argument("scenes/mitsuba/bitmap.xml").sc;
  REQUIRE(sc.quads.size() == 1);
  const material& m = sc.materials[std::size_t(sc.quads[0].material)];
  REQUIRE(m.get<material_kinds::lambertian>());
  CHECK(m.get<material_kinds::lambertian>()->albedo.type == texture::kind::image);
  CHECK(m.get<material_kinds::lambertian>()->albedo.srgb);
  CHECK(m.get<material_kinds::lambertian>()->albedo.repeat);
  // to_world: scale 1.2 x 0.9, then 10 degrees about z. Mitsuba's (u, v) = (0, 0) is the corner
  // (-1, -1) in the shape's space and shows the image's top-left texel; zraka's uv (0, 0) shows
  // the bottom-left one, so the quad starts at (-1, +1) and runs v down.
  const affine a = affine::rotate(vec3(0, 0, 1), 10 * pi<double> / 180) * affine::scale(vec3(1.2, 0.9, 1));
  CHECK(near(sc.quads[0].shape.corner, a.point(vec3(-1, 1, 0)), 1e-12));
  CHECK(near(sc.quads[0].shape.u, a.vector(vec3(2, 0, 0)), 1e-12));
  CHECK(near(sc.quads[0].shape.v, a.vector(vec3(0, -2, 0)), 1e-12));
}

TEST_CASE("Mitsuba XML: fov along x, y, the diagonal, the smaller and the larger side") {
  const double w = 200, h = 100, t = std::tan(90.0 * pi<double> / 360);
  auto vfov = [&](const std::string& axis) {
    const std::string s = "<float name=\"fov\" value=\"90\"/>" +
                          (axis.empty() ? "" : "<string name=\"fov_axis\" value=\"" + axis + "\"/>");
    return parse_xml(scene_xml(glass_sphere, s, int(w), int(h))).sc.camera.vfov_degrees;
  };
  auto deg = [](double tan_half) { return 2 * std::atan(tan_half) * 180 / pi<double>; };
  CHECK(vfov("") == doctest::Approx(deg(t * h / w)));  // Mitsuba's default axis is x
  CHECK(vfov("x") == doctest::Approx(deg(t * h / w)));
  CHECK(vfov("y") == doctest::Approx(90));
  CHECK(vfov("diagonal") == doctest::Approx(deg(t * h / std::sqrt(w * w + h * h))));
  CHECK(vfov("smaller") == doctest::Approx(90));  // the height is the smaller side
  CHECK(vfov("larger") == doctest::Approx(deg(t * h / w)));
}

TEST_CASE("Mitsuba XML: a camera by lookat and by its matrix is one camera; max_depth counts segments") {
  const std::string fov = "<float name=\"fov\" value=\"40\"/>";
  const scene a = parse_xml(scene_xml(glass_sphere, fov + "<transform name=\"to_world\"><lookat origin=\"1, 2, 5\" "
                                                          "target=\"0, 0.5, 0\" up=\"0, 1, 0\"/></transform>")).sc;
  // The same map as the matrix Mitsuba's lookat builds: columns left = up x dir, up', dir, origin.
  const vec3 o(1, 2, 5), dir = glm::normalize(vec3(0, 0.5, 0) - o), left = glm::normalize(glm::cross(vec3(0, 1, 0), dir)),
             up = glm::cross(dir, left);
  char m[512];
  std::snprintf(m, sizeof m, "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g 0 0 0 1", left.x,
                up.x, dir.x, o.x, left.y, up.y, dir.y, o.y, left.z, up.z, dir.z, o.z);
  const scene b = parse_xml(scene_xml(glass_sphere, fov + "<transform name=\"to_world\"><matrix value=\"" + std::string(m) +
                                                          "\"/></transform>", 64, 32, 9)).sc;
  CHECK(near(a.camera.position, b.camera.position));
  CHECK(near(a.camera.look_at, b.camera.look_at));
  CHECK(near(a.camera.up, b.camera.up));
  CHECK(a.settings.max_depth == 4);  // 5 segments
  CHECK(b.settings.max_depth == 8);  // 9 segments
  // A scale in the camera's to_world is refused, not silently dropped.
  CHECK(error_of([&] {
          parse_xml(scene_xml(glass_sphere, fov + "<transform name=\"to_world\"><scale value=\"2\"/></transform>"));
        }).find("a sensor's to_world must be a rotation and a translation") != std::string::npos);
}

TEST_CASE("Mitsuba XML: an obj's to_world becomes zraka's scale, rotate, translate, half turns too") {
  const fs::path dir = fs::temp_directory_path() / "zraka_test_mitsuba_xml_obj";
  fs::create_directories(dir);
  {
    std::ofstream(dir / "tri.obj") << "v 1 0 0\nv 0 2 0\nv 0 0 3\nvn 1 0 0\nvn 0 1 0\nvn 0 0 1\nf 1//1 2//2 3//3\n";
  }
  for (const std::string rot : {"<rotate x=\"0.6\" y=\"0.48\" z=\"-0.64\" angle=\"37\"/>", "<rotate y=\"1\" angle=\"180\"/>",
                                "<rotate x=\"0.6\" y=\"0.8\" angle=\"180\"/>", "<rotate z=\"1\" angle=\"179.99999\"/>",
                                "<rotate z=\"1\" angle=\"0\"/>"}) {
    INFO(rot);
    const std::string tw = "<transform name=\"to_world\"><scale x=\"2\" y=\"0.5\" z=\"3\"/>" + rot +
                           "<translate x=\"1\" y=\"-2\" z=\"0.25\"/></transform>";
    const std::string shape = "<shape type=\"obj\"><string name=\"filename\" value=\"tri.obj\"/>"
                              "<boolean name=\"face_normals\" value=\"true\"/>" + tw +
                              "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>";
    const scene sc = parse_xml(scene_xml(shape), dir).sc;
    REQUIRE(sc.meshes.size() == 1);
    // The same points through the to_world a <transform> of one rectangle builds.
    const scene r = parse_xml(scene_xml("<shape type=\"rectangle\">" + tw + "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>"), dir).sc;
    REQUIRE(r.quads.size() == 1);
    const auto& q = r.quads[0].shape;  // corner = M(-1,-1,0), u = L(2,0,0), v = L(0,2,0)
    const vec3 lx = q.u / 2.0, ly = q.v / 2.0, t = q.corner + lx + ly;
    const mesh& me = sc.meshes[0].shape;
    REQUIRE(me.positions.size() == 3);
    // L z from the mesh's third vertex (0, 0, 3): M = t + 3 Lz.
    const vec3 lz = (me.positions[2] - t) / 3.0;
    CHECK(near(me.positions[0], t + lx, 1e-9));
    CHECK(near(me.positions[1], t + 2.0 * ly, 1e-9));
    CHECK(glm::dot(glm::cross(lx, ly), lz) > 0);  // not mirrored
    CHECK(std::abs(glm::dot(lx, lz)) < 1e-9);
    CHECK(glm::length(lz) == doctest::Approx(3));
  }
}

#if ZRAKA_SCENE_MESH_FILES  // built with assimp
TEST_CASE("Mitsuba XML: a ply shape is read by mesh_file.hpp, the same triangles as the obj of the same sphere") {
  const fs::path meshes = resource_root() / "scenes" / "meshes";
  auto read = [&](const std::string& type, const std::string& file) {
    const std::string shape = "<shape type=\"" + type + "\"><string name=\"filename\" value=\"" + file + "\"/>"
                              "<boolean name=\"face_normals\" value=\"true\"/>"
                              "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>";
    const scene sc = parse_xml(scene_xml(shape), meshes).sc;
    REQUIRE(sc.meshes.size() == 1);
    return sc.meshes[0].shape;
  };
  const mesh ply = read("ply", "sphere.ply"), obj = read("obj", "sphere.obj");
  REQUIRE(ply.triangle_count() == obj.triangle_count());
  REQUIRE(ply.triangle_count() > 0);
  for (std::size_t t = 0; t < ply.triangles.size(); t += 37)
    for (int k = 0; k < 3; ++k)
      CHECK(near(ply.positions[ply.triangles[t][k]], obj.positions[obj.triangles[t][k]], 1e-6));
  // Flat shading is required of a ply as of an obj.
  const std::string smooth = "<shape type=\"ply\"><string name=\"filename\" value=\"sphere.ply\"/>"
                             "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>";
  CHECK(error_of([&] { parse_xml(scene_xml(smooth), meshes); }).find("face_normals") != std::string::npos);
}
#endif

TEST_CASE("Mitsuba XML: defaults and $name substitution; a default's value is not substituted again") {
  const std::string body = "<default name=\"r\" value=\"0.25\"/><default name=\"loop\" value=\"$loop\"/>"
                           "<shape type=\"sphere\"><float name=\"radius\" value=\"$r\"/><bsdf type=\"dielectric\"/></shape>";
  const scene sc = parse_xml(scene_xml(body)).sc;
  REQUIRE(sc.spheres.size() == 1);
  CHECK(sc.spheres[0].shape.radius == 0.25);
  const std::string uses_loop = "<default name=\"loop\" value=\"$loop\"/>"
                                "<shape type=\"sphere\"><float name=\"radius\" value=\"$loop\"/><bsdf type=\"dielectric\"/></shape>";
  CHECK(error_of([&] { parse_xml(scene_xml(uses_loop)); }).find("'$loop' is not a number") != std::string::npos);
}

TEST_CASE("Mitsuba XML: limits: element count and deep nesting stop with an error, quickly") {
  const input_limits saved = limits();
  limits().yaml_nodes = 50;
  std::string many;
  for (int i = 0; i < 60; ++i) many += glass_sphere;
  CHECK(error_of([&] { parse_xml(scene_xml(many)); }).find("XML nodes") != std::string::npos);
  limits() = saved;
  // 200000 nested elements: pugixml parses without recursion, and the reader refuses the first.
  std::string deep = "<scene version=\"3.0.0\">";
  for (int i = 0; i < 200000; ++i) deep += "<shape type=\"sphere\">";
  CHECK(error_of([&] { (void)mitsuba_xml_to_yaml(deep, "deep.xml", "."); }).rfind("deep.xml:1: XML syntax", 0) == 0);
  for (int i = 0; i < 200000; ++i) deep += "</shape>";
  deep += "</scene>";
  CHECK(error_of([&] { (void)mitsuba_xml_to_yaml(deep, "deep.xml", "."); }).find("unexpected in a shape") != std::string::npos);
  CHECK(error_of([&] { (void)mitsuba_xml_to_yaml("", "empty.xml", "."); }).rfind("empty.xml", 0) == 0);
  CHECK(error_of([&] { (void)mitsuba_xml_to_yaml(std::string("<scene\0", 7), "nul.xml", "."); }).rfind("nul.xml:1: XML syntax", 0) == 0);
}

TEST_CASE("Mitsuba XML: a disk, read through the program's registered disk shape") {
  // What a program's registered disk receives (book 2.3's disk takes center, normal, radius).
  struct seen_disk final : user_shape {
    vec3 c, n;
    double r;
    seen_disk(vec3 c_, vec3 n_, double r_) : c(c_), n(n_), r(r_) {}
    std::string name() const override { return "disk"; }
    bool intersect(const ray&, double, double, hit&) const override { return false; }
    aabb bounds() const override { return {c - vec3(r), c + vec3(r)}; }
  };
  scene_registry reg;
  reg.add_shape("disk", {"center", "normal", "radius"}, [](const scene_node& n) {
    return std::make_shared<seen_disk>(n.point("center", vec3(0)), n.direction("normal"), n.number("radius", 1.0));
  });
  // Mitsuba's disk is the unit disk in the xy plane facing +z; this one is scaled by 2, turned
  // 90 degrees about x (+z goes to -y: it faces down) and moved to (1, 3, 0): a lamp.
  const std::string xml = scene_xml(
      "<shape type=\"disk\"><transform name=\"to_world\"><scale value=\"2\"/><rotate x=\"1\" angle=\"90\"/>"
      "<translate x=\"1\" y=\"3\"/></transform><bsdf type=\"diffuse\"><rgb name=\"reflectance\" value=\"0\"/></bsdf>"
      "<emitter type=\"area\"><rgb name=\"radiance\" value=\"5\"/></emitter></shape>");
  const loaded_scene ls = parse_scene(mitsuba_xml_to_yaml(xml, "t.xml", ".", reg), "t.yaml", ".", reg);
  REQUIRE(ls.sc.user_shapes.size() == 1);
  const auto* d = dynamic_cast<const seen_disk*>(ls.sc.user_shapes[0].shape.get());
  REQUIRE(d != nullptr);
  CHECK(near(d->c, vec3(1, 3, 0), 1e-12));
  CHECK(near(d->n, vec3(0, -1, 0), 1e-12));
  CHECK(d->r == doctest::Approx(2.0));
  CHECK(ls.sc.material_of({shape_kind::user, 0}).is<material_kinds::emitter>());
  // A shear or a non-uniform scale would make an ellipse: refused at the transform.
  const std::string squashed = scene_xml("<shape type=\"disk\"><transform name=\"to_world\"><scale x=\"2\"/></transform>"
                                         "<bsdf type=\"twosided\"><bsdf type=\"diffuse\"/></bsdf></shape>");
  CHECK(error_of([&] { mitsuba_xml_to_yaml(squashed, "t.xml", ".", reg); }).find(
            "a disk's to_world may rotate, translate and scale uniformly only") != std::string::npos);
  // Without a registered disk, or with one that takes other keys: the error says what to do.
  scene_registry other;
  other.add_shape("disk", {"size"}, [](const scene_node&) { return user_shape_ptr<double>(); });
  CHECK(error_of([&] { mitsuba_xml_to_yaml(xml, "t.xml", ".", other); }).find("zraka has no disk of its own") !=
        std::string::npos);
}

// links: yaml-cpp
// scene_in<U>: a scene in another precision. The same objects, coordinates rounded once; the float
// render of the Cornell box has the double render's expectation; a shape that rounding to float
// destroys, a coordinate beyond float's range and a user shape are errors that name them.
#include <zraka/geometry/user_shape.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/scene/scene_precision.hpp>
#include <zraka/scene/scene_query.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <memory>
#include <string>

using namespace zraka;

namespace {

std::string error_of(auto&& f) {
  try {
    f();
  } catch (const error& e) {
    return e.what();
  }
  return "no error";
}

template <class T> double mean_of_render(const scene_t<T>& sc, int spp, std::uint64_t seed) {
  const path_tracer_t<T> pt(sc, path_options{});
  const auto cam = sc.prepared_camera();
  image img(sc.settings.width, sc.settings.height);
  render_options ro;
  ro.progress = false, ro.threads = 2;
  const int W = img.width, H = img.height;
  const render_stats st = render(img, spp, seed, [&](sample_context& c) {
    const vec2 u = c.random.uniform2();
    return pt(cam.generate(T((c.x + u.x) / W), T((c.y + u.y) / H)), c.random, c.rays);
  }, ro);
  CHECK(st.nonfinite == 0);
  double m = 0;
  for (const rgb& p : img.pixels) m += (double(p.x) + p.y + p.z) / 3;
  return m / double(img.pixels.size());
}

}  // namespace

TEST_CASE("the Cornell box in float: the same objects, and the same image in expectation") {
  scene sd = load_scene_argument("cornell-glass").sc;
  sd.settings.width = 20, sd.settings.height = 20;
  sd.build_acceleration();
  const scene_t<float> sf = scene_in<float>(sd);
  CHECK(sf.spheres.size() == sd.spheres.size());
  CHECK(sf.quads.size() == sd.quads.size());
  CHECK(sf.materials.size() == sd.materials.size());
  CHECK(sf.has_object_bvh() == sd.has_object_bvh());
  CHECK(sf.quads[0].shape.corner == vec3f(sd.quads[0].shape.corner));  // rounded once
  CHECK(sf.spheres[0].shape.radius == float(sd.spheres[0].shape.radius));
  // Independent batches of each; the means agree within 5 combined standard errors.
  estimator_t<double> ed, ef;
  for (std::uint64_t b = 0; b < 8; ++b) {
    ed.add(mean_of_render(sd, 16, 10 + b));
    ef.add(mean_of_render(sf, 16, 100 + b));
  }
  INFO("double " << ed.mean() << " +- " << ed.standard_error() << ", float " << ef.mean() << " +- " << ef.standard_error());
  CHECK(ed.mean() > 0.05);
  CHECK(std::abs(ed.mean() - ef.mean()) < 5 * std::hypot(ed.standard_error(), ef.standard_error()));
  // And back: float to double is exact.
  const scene back = scene_in<double>(sf);
  CHECK(back.quads[3].shape.u == vec3(sf.quads[3].shape.u));
}

TEST_CASE("a mesh converts with its normals and texture coordinates, and its BVH is rebuilt") {
  scene sd = load_scene_argument("teapot").sc;
  REQUIRE(!sd.meshes.empty());
  const scene_t<float> sf = scene_in<float>(sd);
  REQUIRE(sf.meshes.size() == sd.meshes.size());
  CHECK(sf.meshes[0].shape.triangle_count() == sd.meshes[0].shape.triangle_count());
  CHECK(sf.meshes[0].shape.normals.size() == sd.meshes[0].shape.normals.size());
  CHECK(sf.meshes[0].shape.texcoords.size() == sd.meshes[0].shape.texcoords.size());
  // A ray at the middle of the image hits the same surface in both, at nearly the same distance.
  const auto cd = sd.prepared_camera();
  const auto cf = sf.prepared_camera();
  scene_hit_t<double> hd;
  scene_hit_t<float> hf;
  REQUIRE(nearest_hit(sd, cd.generate(0.5, 0.55), hd));
  REQUIRE(nearest_hit(sf, cf.generate(0.5f, 0.55f), hf));
  CHECK(double(hf.h.t) == doctest::Approx(hd.h.t).epsilon(1e-4));
}

TEST_CASE("what rounding to float would destroy is an error that names it") {
  scene tiny;
  const int m = tiny.add_material(material{});
  tiny.add(quad{vec3(0), vec3(1e-30, 0, 0), vec3(0, 1e-30, 0)}, m);  // normal 1e-60: zero in float
  REQUIRE(tiny.quads[0].shape.valid());
  CHECK(error_of([&] { scene_in<float>(tiny); }) == "quad 0: its edges are parallel or too short in float");

  scene far;
  far.add_material(material{});
  far.add(sphere{vec3(1e300, 0, 0), 1.0}, 0);
  CHECK(error_of([&] { scene_in<float>(far); }) == "sphere 0: a coordinate beyond the range of float");

  scene small;
  small.add_material(material{});
  small.add(sphere{vec3(0), 1e-50}, 0);  // 0 in float
  CHECK(error_of([&] { scene_in<float>(small); }) == "sphere 0: its radius is zero or not finite in float");

  scene cam;
  cam.camera.position = vec3(1, 0, 0), cam.camera.look_at = vec3(1 + 1e-12, 0, 0);  // one point in float
  CHECK(error_of([&] { scene_in<float>(cam); }) == "camera: position and look_at are one point in float");
}

TEST_CASE("a user shape is written for one precision: refused by its name") {
  struct blob final : user_shape {
    std::string name() const override { return "blob"; }
    bool intersect(const ray&, double, double, hit&) const override { return false; }
    aabb bounds() const override { return {vec3(-1), vec3(1)}; }
  };
  scene sc;
  sc.add_material(material{});
  sc.add(std::make_shared<blob>(), 0);
  CHECK(error_of([&] { scene_in<float>(sc); }) ==
        "user shape 'blob' is written in double (user_shape.hpp) and cannot be converted; render this scene in double");
}

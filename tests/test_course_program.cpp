// links: yaml-cpp
// A course's program (issue 42, "the shipped programs take a course's kinds"): a torus shape and
// a matte material of the course's own (tests/course/torus.hpp), registered by name, in a scene
// file (tests/course/torus.yaml) rendered through zraka::pathtrace_main, the whole `pathtrace`
// command line, as the course's binary would. The image is checked against the closed form of
// where the torus is seen; Whitted and the OpenCL packer (and, where zraka has them compiled,
// whitted_main and realtime_main) refuse the scene by the kind's name and name the program that
// can render it; chapter 2.3's `pathtrace` (no registry) cannot load it at all.
#include "course/ao.hpp"
#include "course/torus.hpp"

#include <zraka/app/pathtrace_main.hpp>
#include <zraka/app/whitted_main.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/whitted.hpp>
#include <zraka/io/scene_argument.hpp>
#if defined(ZRAKA_COMPILED_OPENCL) && defined(ZRAKA_COMPILED_GL)
#include <zraka/app/realtime_main.hpp>
#endif

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

using namespace zraka;
namespace fs = std::filesystem;

namespace {

const char* const scene_file = "tests/course/torus.yaml";  // under the resource root

struct run_result {
  int code;
  std::string err;
};

// Runs a program function on a command line, its stderr captured.
template <class F> run_result run(F&& program_main, std::vector<std::string> args) {
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::ostringstream err;
  std::streambuf* old = std::cerr.rdbuf(err.rdbuf());
  const int code = program_main(int(args.size()), argv.data());
  std::cerr.rdbuf(old);
  return {code, err.str()};
}

fs::path scratch(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("zraka-course-" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d / name;
}

scene_registry course_registry() {
  scene_registry reg;
  course::register_types(reg);
  return reg;
}

// What the refusals must say of this scene: the kinds by name, and the program that can load it.
const std::string who_can = "render it with your course's program built on zraka::pathtrace_main (its registry has "
                            "'torus' and 'matte'; chapter 2.3's pathtrace has the built-in kinds only)";

}  // namespace

TEST_CASE("course program: pathtrace_main renders a registered torus in a registered material where the closed form puts it") {
  const scene_registry reg = course_registry();
  const fs::path out = scratch("torus.pfm");
  fs::remove(out);
  const run_result res = run([&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); },
                           {"course", "--scene", scene_file, "--centre", "--seed", "3", "--out", out.string()});
  REQUIRE_MESSAGE(res.code == 0, res.err);
  const image img = read_float_image(out);
  const loaded_scene ls = load_scene_argument(scene_file, reg);
  REQUIRE(img.width == ls.sc.settings.width);
  REQUIRE(img.height == ls.sc.settings.height);

  // Where each pixel centre's ray (the scene's own camera, --centre) crosses the torus's plane
  // y = 0, at radius rho. The torus (R = 1, r = 0.35, axis y) fills R - r < rho < R + r on that
  // plane, so such a ray enters the solid torus: it hits. A ray from the eye at height h = 4 is
  // at radius rho (h - y) / h at height y; if that stays below R - r or above R + r for all
  // |y| <= r, it misses. Between the two is the silhouette's band, not checked.
  const double R = 1, r = 0.35, h = 4, Le = 1, albedo = 0.5;
  const auto cam = ls.sc.prepared_camera();
  int hits = 0, misses = 0, top = 0;
  double hit_sum = 0, top_sum = 0;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const vec3 v(img.at(x, y));
      REQUIRE(is_finite(v));
      const ray ray = cam.generate((x + 0.5) / img.width, (y + 0.5) / img.height);
      const vec3 p = ray.at(-ray.origin.y / ray.direction.y);
      const double rho = std::sqrt(p.x * p.x + p.z * p.z);
      if (rho > R - r && rho < R + r) {
        ++hits;
        hit_sum += v.x;
        // Its own glow at least: every other term of the estimate is a product of non-negatives.
        CHECK_MESSAGE(v.x >= Le * (1 - 1e-6), "pixel " << x << "," << y << ": " << v.x);
        // Near the tube's top (radius R at height r; the ray crossed y = r at rho (h - r) / h).
        if (std::abs(rho * (h - r) / h - R) < 0.03) ++top, top_sum += v.x;
      } else if (rho * (h + r) / h < R - r || rho * (h - r) / h > R + r) {
        ++misses;
        CHECK_MESSAGE(v == vec3(0), "pixel " << x << "," << y << " should be the black background: " << v.x);
      }
    }
  INFO("hits " << hits << ", misses " << misses << ", near the top " << top);
  REQUIRE(hits > 300);
  REQUIRE(misses > 300);
  REQUIRE(top > 20);
  const double hit_mean = hit_sum / hits, top_mean = top_sum / top;
  INFO("mean over the torus " << hit_mean << ", near the tube's top " << top_mean);
  // At most Le / (1 - albedo): nothing in the scene is brighter than that bound.
  CHECK(hit_mean <= Le / (1 - albedo));
  // The inner slopes see the ring across the hole: the matte BSDF reflects some of its glow.
  CHECK(hit_mean > 1.01 * Le);
  // The tube's top sees only the black sky (its tangent plane is above the whole torus): nearly Le.
  CHECK(top_mean < 1.001 * Le);
  fs::remove(out);
}

TEST_CASE("course program: pathtrace_main gives the same image for a seed on any number of threads") {
  const scene_registry reg = course_registry();
  const fs::path a = scratch("one.pfm"), b = scratch("two.pfm");
  for (const auto& [file, threads] : {std::pair{a, "1"}, std::pair{b, "2"}}) {
    const run_result r = run([&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); },
                             {"course", "--scene", scene_file, "--spp", "4", "--seed", "9", "--threads", threads,
                              "--integrator", "nee", "--out", file.string()});
    REQUIRE_MESSAGE(r.code == 0, r.err);
  }
  const image ia = read_float_image(a), ib = read_float_image(b);
  CHECK(ia.pixels == ib.pixels);
  fs::remove(a), fs::remove(b);
}

TEST_CASE("course program: pathtrace_main gives the course's binary pathtrace's whole command line") {
  const scene_registry reg = course_registry();
  auto course_main = [&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); };
  const fs::path ref = scratch("ref.pfm"), csv = scratch("error.csv"), png = scratch("t.png");
  // A reference, then the error against it per pass (--reference, --report), under a time budget.
  run_result res = run(course_main, {"course", "--scene", scene_file, "--spp", "8", "--pfm", ref.string(), "--out",
                                     png.string()});
  REQUIRE_MESSAGE(res.code == 0, res.err);
  res = run(course_main, {"course", "--scene", scene_file, "--spp", "4", "--integrator", "naive", "--reference",
                          ref.string(), "--report", csv.string(), "--time-budget", "100", "--out", png.string()});
  REQUIRE_MESSAGE(res.code == 0, res.err);
  std::ifstream table(csv);
  std::string header;
  std::getline(table, header);
  CHECK_MESSAGE(header.find("rmse") != std::string::npos, header);
  // The built-in scenes by name and a Mitsuba 3 file still load beside the course's kinds.
  for (const char* scene : {"cornell", "scenes/mitsuba/cornell-box.xml"}) {
    res = run(course_main, {"course", "--scene", scene, "--width", "8", "--height", "8", "--spp", "1", "--out",
                            png.string()});
    CHECK_MESSAGE(res.code == 0, scene << ": " << res.err);
  }
  // Its refusals are pathtrace's.
  res = run(course_main, {"course", "--scene", scene_file, "--report", csv.string(), "--out", png.string()});
  CHECK(res.code == 1);
  CHECK(res.err == "error: --report needs --reference\n");
  fs::remove(ref), fs::remove(csv), fs::remove(png);
}

TEST_CASE("course program: chapter 2.3's pathtrace, with no registry, cannot load the course's scene") {
  const fs::path out = scratch("none.png");
  const run_result r = run([](int argc, char** argv) { return pathtrace_main(argc, argv); },
                           {"pathtrace", "--scene", scene_file, "--out", out.string()});
  CHECK(r.code == 1);
  CHECK_MESSAGE(r.err.find("unknown material type 'matte'") != std::string::npos, r.err);
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("course program: the OpenCL packer and Whitted refuse the course's kinds by name and name the program that can") {
  const scene_registry reg = course_registry();
  const loaded_scene ls = load_scene_argument(scene_file, reg);
  CHECK_THROWS_WITH_AS((void)pack_scene(ls.sc, 8, 8, path_options{}),
                       ("realtime: object 'ring' is a user shape ('torus'), which the OpenCL kernel cannot run; " +
                        who_can).c_str(),
                       error);
  CHECK_THROWS_WITH_AS(check_whitted_scene(ls.sc),
                       ("whitted: material 'glow' is a custom BSDF ('matte'), which the Whitted ray tracer cannot "
                        "shade; " + who_can).c_str(),
                       error);

  // whitted_main, as a course's binary offers it: the same refusal, exit 1, no image.
  const fs::path out = scratch("whitted.png");
  fs::remove(out);
  const run_result w = run([&](int argc, char** argv) { return whitted_main(argc, argv, reg); },
                           {"course-whitted", "--scene", scene_file, "--out", out.string()});
  CHECK(w.code == 1);
  CHECK(w.err == "error: whitted: material 'glow' is a custom BSDF ('matte'), which the Whitted ray tracer cannot "
                 "shade; " + who_can + "\n");
  CHECK_FALSE(fs::exists(out));

  // Whitted renders a course's shape in a built-in material (the shape goes through
  // scene_query.hpp like any other); the kernel still cannot, and says that a program built on
  // pathtrace_main can (chapter 2.3's cannot load the torus).
  const fs::path lambert = scratch("torus-lambert.yaml");
  {
    std::ofstream f(lambert);
    f << "settings: {width: 16, height: 16, spp: 1}\n"
         "camera: {position: [0, 4, 0], look_at: [0, 0, 0], up: [0, 0, -1], vfov: 40}\n"
         "materials: {white: {albedo: 0.7}}\n"
         "lights: [{type: point, position: [0, 3, 0], intensity: 10}]\n"
         "objects: [{type: torus, major: 1, minor: 0.35, material: white}]\n";
  }
  const run_result ok = run([&](int argc, char** argv) { return whitted_main(argc, argv, reg); },
                            {"course-whitted", "--scene", lambert.string(), "--out", out.string()});
  CHECK_MESSAGE(ok.code == 0, ok.err);
  CHECK(fs::exists(out));
  const loaded_scene plain = load_scene_argument(lambert.string(), reg);
  CHECK_THROWS_WITH_AS((void)pack_scene(plain.sc, 8, 8, path_options{}),
                       "realtime: objects[0] is a user shape ('torus'), which the OpenCL kernel cannot run; render "
                       "it with your course's program built on zraka::pathtrace_main (its registry has 'torus'; "
                       "chapter 2.3's pathtrace has the built-in kinds only)",
                       error);
  fs::remove(out), fs::remove(lambert);
}

#if defined(ZRAKA_COMPILED_OPENCL) && defined(ZRAKA_COMPILED_GL)
TEST_CASE("course program: realtime_main refuses the course's torus by name before it needs a device") {
  const scene_registry reg = course_registry();
  const fs::path out = scratch("realtime.png");
  fs::remove(out);
  const run_result r = run([&](int argc, char** argv) { return realtime_main(argc, argv, reg); },
                           {"course-realtime", "--scene", scene_file, "--headless", "--out", out.string()});
  CHECK(r.code == 1);
  CHECK(r.err == "error: realtime: object 'ring' is a user shape ('torus'), which the OpenCL kernel cannot run; " +
                     who_can + "\n");
  CHECK_FALSE(fs::exists(out));
}
#endif

// The integrator door (scene_registry::add_integrator): the course's ambient occlusion
// (tests/course/ao.hpp) chosen by --integrator, against the closed forms of tests/course/ao.yaml.
namespace {
const char* const ao_scene = "tests/course/ao.yaml";  // under the resource root

// tests/course/ao.yaml with settings.integrator set, written to `file`.
void write_ao_scene(const fs::path& file, const std::string& integrator) {
  std::ifstream in(fs::path(resource_root()) / ao_scene);
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string from = "settings: {";
  yaml.replace(yaml.find(from), from.size(), from + "integrator: " + integrator + ", ");
  std::ofstream(file) << yaml;
}

scene_registry ao_registry(double max_distance) {
  scene_registry reg = course_registry();
  course::register_ao(reg, max_distance);
  return reg;
}
}  // namespace

TEST_CASE("course program: pathtrace_main renders the course's ambient occlusion where its closed form puts it") {
  const fs::path out = scratch("ao.pfm");
  const loaded_scene ls = load_scene_argument(ao_scene, scene_registry{});
  const auto cam = ls.sc.prepared_camera();

  SUBCASE("a reach shorter than the gap between ball and floor: 1 exactly wherever a surface is seen") {
    const scene_registry reg = ao_registry(0.9);
    const run_result r = run([&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); },
                             {"course", "--scene", ao_scene, "--integrator", "ao", "--width", "16", "--height", "16",
                              "--spp", "64", "--centre", "--out", out.string()});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const image img = read_float_image(out);
    int seen = 0, sky = 0;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        scene_hit sh;
        const bool hit = nearest_hit(ls.sc, cam.generate((x + 0.5) / img.width, (y + 0.5) / img.height), sh);
        (hit ? seen : sky) += 1;
        CHECK_MESSAGE(img.at(x, y) == rgb(hit ? 1.0f : 0.0f), "pixel " << x << "," << y);
      }
    CHECK(seen > 100);  // the floor and the ball
    CHECK(sky > 10);    // above the horizon
  }

  SUBCASE("a long reach: 1 - sin^2(alpha) = 3/4 under the ball, within its Monte Carlo error") {
    const scene_registry reg = ao_registry(100);
    const int spp = 32768;
    const run_result r = run([&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); },
                             {"course", "--scene", ao_scene, "--integrator", "ao", "--spp", std::to_string(spp),
                              "--centre", "--seed", "5", "--out", out.string()});
    REQUIRE_MESSAGE(r.code == 0, r.err);
    const image img = read_float_image(out);
    REQUIRE(img.width == 5);
    REQUIRE(img.height == 5);
    // The central pixel's ray (--centre) meets the floor at the origin, under the ball.
    scene_hit sh;
    REQUIRE(nearest_hit(ls.sc, cam.generate(0.5, 0.5), sh));
    REQUIRE(glm::length(sh.h.p) < 1e-9);
    const double expected = 1 - 0.25, sigma = std::sqrt(expected * (1 - expected) / spp);
    const double got = img.at(2, 2).x;
    INFO("ambient occlusion under the ball " << got << ", expected " << expected << " +- " << sigma);
    CHECK(std::abs(got - expected) < 4 * sigma);
  }
  fs::remove(out);
}

TEST_CASE("course program: --integrator takes the built-ins and the course's integrators by name") {
  const scene_registry reg = ao_registry(1);
  auto course_main = [&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); };
  const fs::path out = scratch("names.png");
  run_result r = run(course_main, {"course", "--scene", ao_scene, "--integrator", "fog", "--out", out.string()});
  CHECK(r.code == 1);
  CHECK(r.err == "error: unknown integrator 'fog' (naive, nee, mis; registered: ao)\n");
  CHECK_FALSE(fs::exists(out));
  // Chapter 2.3's pathtrace (no registry) names the built-ins only, as before the door.
  r = run([](int argc, char** argv) { return pathtrace_main(argc, argv); },
          {"pathtrace", "--scene", ao_scene, "--integrator", "ao", "--out", out.string()});
  CHECK(r.code == 1);
  CHECK(r.err == "error: unknown integrator 'ao' (naive, nee, mis)\n");
  // --help lists the registered ones.
  std::ostringstream help;
  std::streambuf* old = std::cout.rdbuf(help.rdbuf());
  r = run(course_main, {"course", "--help"});
  std::cout.rdbuf(old);
  CHECK(r.code == 0);
  CHECK_MESSAGE(help.str().find("naive, nee or mis; registered: ao") != std::string::npos, help.str());
  // A course's integrator may not take a built-in's name, nor be registered twice.
  scene_registry twice = ao_registry(1);
  CHECK_THROWS_WITH_AS(course::register_ao(twice, 1), "scene registry: integrator type 'ao' is registered twice", error);
  scene_registry clash;
  clash.add_integrator("mis", [](const scene&, const path_options&) {
    return [](const ray&, rng&, std::uint64_t&) { return rgb(0); };
  });
  r = run([&](int argc, char** argv) { return pathtrace_main(argc, argv, clash); },
          {"course", "--scene", ao_scene, "--out", out.string()});
  CHECK(r.code == 1);
  CHECK(r.err == "error: scene registry: integrator 'mis' is built in; a registered integrator must have a new name\n");
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("course program: a scene file's settings.integrator names the course's integrator") {
  const scene_registry reg = ao_registry(0.9);
  auto course_main = [&](int argc, char** argv) { return pathtrace_main(argc, argv, reg); };
  const fs::path file = scratch("ao-settings.yaml"), out = scratch("ao-settings.pfm");
  auto write_scene = [&](const std::string& integrator) { write_ao_scene(file, integrator); };
  write_scene("ao");
  const loaded_scene ls = load_scene_argument(file.string(), reg);
  CHECK(ls.sc.settings.integrator == "ao");
  // No --integrator: the scene's, so the reach of 0.9 gives 1 wherever a surface is seen.
  run_result r = run(course_main, {"course", "--scene", file.string(), "--centre", "--out", out.string()});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  image img = read_float_image(out);
  CHECK(img.at(2, 2) == rgb(1.0f));
  // --integrator over the scene's: the path tracer, whose floor is lit by nothing.
  r = run(course_main, {"course", "--scene", file.string(), "--integrator", "nee", "--centre", "--out", out.string()});
  REQUIRE_MESSAGE(r.code == 0, r.err);
  img = read_float_image(out);
  CHECK(img.at(2, 2) == rgb(0.0f));
  // Whitted cannot run it and says so by name.
  const run_result w = run([&](int argc, char** argv) { return whitted_main(argc, argv, reg); },
                           {"course-whitted", "--scene", file.string(), "--out", scratch("w.png").string()});
  CHECK(w.code == 1);
  CHECK(w.err == "error: whitted: integrator 'ao' is a course's integrator, which the Whitted ray tracer cannot "
                 "run; render it with your course's program built on zraka::pathtrace_main\n");
  CHECK_FALSE(fs::exists(scratch("w.png")));
  // A name nobody registered: the file and the field, and the names there are.
  write_scene("fog");
  r = run(course_main, {"course", "--scene", file.string(), "--out", out.string()});
  CHECK(r.code == 1);
  CHECK(r.err == "error: " + file.string() + ": settings.integrator: unknown integrator 'fog' (naive, nee, mis; "
                 "registered: ao)\n");
  fs::remove(file), fs::remove(out);
}

#if defined(ZRAKA_COMPILED_OPENCL) && defined(ZRAKA_COMPILED_GL)
TEST_CASE("course program: realtime_main refuses the course's integrator by name before it needs a device") {
  const scene_registry reg = ao_registry(1);
  const fs::path out = scratch("realtime-ao.png");
  fs::remove(out);
  const run_result r = run([&](int argc, char** argv) { return realtime_main(argc, argv, reg); },
                           {"course-realtime", "--scene", ao_scene, "--integrator", "ao", "--headless", "--out",
                            out.string()});
  CHECK(r.code == 1);
  CHECK(r.err == "error: realtime: integrator 'ao' is a course's integrator, which the OpenCL kernel cannot run; "
                 "render it with your course's program built on zraka::pathtrace_main\n");
  CHECK_FALSE(fs::exists(out));  // The same when the scene file names it (settings.integrator).
  const fs::path file = scratch("ao-realtime.yaml");
  write_ao_scene(file, "ao");
  const run_result f = run([&](int argc, char** argv) { return realtime_main(argc, argv, reg); },
                           {"course-realtime", "--scene", file.string(), "--headless", "--out", out.string()});
  CHECK(f.code == 1);
  CHECK(f.err == r.err);
  CHECK_FALSE(fs::exists(out));
  fs::remove(file);
}
#endif

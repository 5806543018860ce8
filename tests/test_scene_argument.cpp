// links: yaml-cpp
#include <zraka/io/scene_argument.hpp>

#include <doctest/doctest.h>

using namespace zraka;

TEST_CASE("scene_argument: every registry name loads, the YAML ones from scenes/") {
  for (const named_scene& n : named_scenes) {
    CAPTURE(n.name);
    const loaded_scene ls = load_scene_argument(std::string(n.name));
    CHECK(ls.sc.materials.size() > 0);
    CHECK(ls.resolved.empty() == (n.build != nullptr));  // only a YAML scene has resolved text
  }
}

TEST_CASE("scene_argument: the C++ Cornell boxes and scenes/cornell*.yaml are the same scenes") {
  // (Material lists differ: the YAML loader adds its default material. 2.3's smoke test compares
  // the images bit for bit.)
  for (const char* name : {"cornell", "cornell-glass", "cornell-spheres"}) {
    CAPTURE(name);
    const scene a = load_scene_argument(name).sc;
    const scene b = load_scene_argument(std::string("scenes/") + name + ".yaml").sc;
    CHECK(a.quads.size() == b.quads.size());
    CHECK(a.spheres.size() == b.spheres.size());
    CHECK(a.settings.width == b.settings.width);
    CHECK(a.settings.spp == b.settings.spp);
  }
}

TEST_CASE("scene_argument: a typo in a path is a missing file named as given") {
  CHECK_THROWS_WITH_AS(load_scene_argument("scenes/cornel.yaml"), "scene file not found: scenes/cornel.yaml", error);
  CHECK_THROWS_WITH_AS(load_scene_argument("/no/such/dir/x.yaml"), "scene file not found: /no/such/dir/x.yaml", error);
  CHECK_THROWS_WITH_AS(load_scene_argument("cornel"), doctest::Contains("unknown scene 'cornel'"), error);
}

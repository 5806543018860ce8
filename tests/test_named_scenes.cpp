#include <zraka/scene/named_scenes.hpp>

#include <doctest/doctest.h>

#include <set>
#include <string>

using namespace zraka;

TEST_CASE("named_scenes: every name once, and the list --help prints holds them all") {
  std::set<std::string_view> seen;
  const std::string list = named_scene_list();
  for (const named_scene& n : named_scenes) {
    CHECK(seen.insert(n.name).second);
    CHECK(list.find(std::string(n.name)) != std::string::npos);
    CHECK(find_named_scene(n.name) == &n);
  }
  CHECK(find_named_scene("cornel") == nullptr);
}

TEST_CASE("named_scenes: cornell is the two-box Cornell box, the same in every program") {
  const scene boxes = builtin_scene("cornell");
  CHECK(boxes.quads.size() == 18);  // room 5 + light 1 + two boxes 12
  CHECK(boxes.spheres.empty());
  const scene glass = builtin_scene("cornell-glass");
  CHECK(glass.quads.size() == 12);
  CHECK(glass.spheres.size() == 1);
  const scene spheres = builtin_scene("cornell-spheres");
  CHECK(spheres.spheres.size() == 2);
  CHECK(builtin_scene("spheres").spheres.size() == 5);
  CHECK(builtin_scene("furnace").spheres.size() == 1);
}

TEST_CASE("named_scenes: an unknown name lists the accepted ones; a file scene needs YAML") {
  CHECK_THROWS_WITH_AS(builtin_scene("cornel"), doctest::Contains("unknown scene 'cornel' (cornell, cornell-glass"), error);
  CHECK_THROWS_WITH_AS(builtin_scene("box"), doctest::Contains("scene 'box' is a scene file (scenes/box.yaml)"), error);
}

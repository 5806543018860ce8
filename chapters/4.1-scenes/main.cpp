// Chapter 4.1 — scene files. Loads a YAML scene (scenes/README.md) and prints it back with every
// default filled in, then what a renderer would build for it and how long loading took. A bad
// scene gives one error naming the file, the line, the column and the field, and exit code 1.
//
//   scenes                                           the default scene
//   scenes --scene scenes/box.yaml
//   scenes --scene tests/scenes/bad/negative-radius.yaml   error: ...:4:37: objects[0].radius: ...
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene_query.hpp>

#include <cstdio>

using namespace zraka;

int main(int argc, char** argv) {
  program_options po{"Chapter 4.1: load a scene file and print it with its defaults filled in", take::scene};
  po.scene_names = named_scene_list();
  po.scene = "default";
  bool quiet = false;
  po.app.add_flag("--quiet", quiet, "print only what was built, not the scene");
  if (const auto done = po.parse(argc, argv)) return *done;
  const std::string& scene_path = po.scene;

  return guarded([&] {
    stopwatch clock;
    // [listing load]
    const loaded_scene ls = load_scene_argument(scene_path);
    const double seconds = clock.seconds();
    if (!quiet && ls.resolved.empty()) std::printf("# %s is built in C++ (named_scenes.hpp): no YAML to print\n\n", scene_path.c_str());
    else if (!quiet) std::printf("# %s, with every default filled in\n%s\n\n", scene_path.c_str(), ls.resolved.c_str());
    std::printf("%s\n", describe_built(ls.sc).c_str());
    // [end]
    const std::size_t objects = ls.sc.bounded_count() + ls.sc.planes.size();
    std::printf("summary: loaded %s in %.3f s: %zu materials, %zu objects, %zu point lights, %zu area lights, "
                "image %dx%d at %d spp\n",
                scene_path.c_str(), seconds, ls.sc.materials.size(), objects, ls.sc.lights.size(),
                light_set(ls.sc).size() - ls.sc.lights.size(), ls.sc.settings.width, ls.sc.settings.height, ls.sc.settings.spp);
    return 0;
  });
}

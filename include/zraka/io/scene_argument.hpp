#pragma once
// What a program's --scene names: a name from the registry (named_scenes.hpp), a path to a
// .yaml scene file or to a Mitsuba 3 .xml scene (mitsuba_xml.hpp). Every program that takes a
// scene reads it through load_scene_argument, so `--scene cornell` is one scene everywhere; a
// course's program passes its registry (scene_registry.hpp), and its files may then name its own
// shapes and materials. Needs yaml-cpp (scene_file.hpp) and, for .xml, pugixml.
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/io/mitsuba_xml.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/scene/named_scenes.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <filesystem>
#include <string>

namespace zraka {

inline bool is_scene_path(const std::string& arg) {
  return arg.ends_with(".yaml") || arg.ends_with(".yml") || arg.ends_with(".xml") || arg.find('/') != std::string::npos;
}

// The file a --scene argument names, as the scene reader is given it (a path as written, or
// "scenes/<name>.yaml" under the resource root); empty for a scene built in C++. A path is looked
// for as given, then under `root`; a typo is a missing file named as the user wrote it, not a
// resource-root problem.
ZRAKA_SCENE_FILE_FN std::filesystem::path scene_argument_file(const std::string& arg, const std::filesystem::path& root)
#if ZRAKA_SCENE_FILE_DEFINITIONS
{
  if (is_scene_path(arg)) {
    const std::filesystem::path p(arg);
    std::error_code ec;
    if (!std::filesystem::exists(p, ec) && (p.is_absolute() || !std::filesystem::exists(root / p, ec)))
      throw error("scene file not found: " + arg);
    return p;
  }
  const named_scene* n = find_named_scene(arg);
  if (!n) throw error("unknown scene '" + arg + "' (" + named_scene_list() + ", or a .yaml or Mitsuba .xml file)");
  if (n->build) return {};
  return "scenes/" + std::string(n->name) + ".yaml";
}
#else
    ;
#endif

namespace detail {
// Compiled once with the scene-file reader (ZRAKA_SCENE_FILE_FN, scene_file.hpp); the resource root
// is the program's, passed in.
ZRAKA_SCENE_FILE_FN loaded_scene load_scene_argument_in(const std::string& arg, const std::filesystem::path& root,
                                                        const scene_registry& registry)
#if ZRAKA_SCENE_FILE_DEFINITIONS
{
  const std::filesystem::path p = scene_argument_file(arg, root);
  if (p.empty()) return loaded_scene{find_named_scene(arg)->build(), {}};
  return is_mitsuba_xml_path(p) ? load_mitsuba_xml_in(p, root, registry) : load_scene_file_in(p, registry, root);
}
#else
    ;
#endif
}  // namespace detail

inline loaded_scene load_scene_argument(const std::string& arg, const scene_registry& registry = {}) {
  return detail::load_scene_argument_in(arg, resource_root(), registry);
}

}  // namespace zraka

#pragma once
// The options every chapter program shares, in one struct (issue 12), in the spirit of RTIOW's
// camera: main sets the defaults it wants, says which options it takes, adds its own to `app`,
// and parses; what comes back is checked, so main shows only its chapter's new idea.
//
//   program_options opt{"Chapter 1.2: ...", take::size | take::out};
//   opt.width = 400, opt.height = 300, opt.out = "sphere.png";   // defaults, shown by --help
//   opt.app.add_option("--radius", radius, "...");               // the chapter's own
//   if (const auto done = opt.parse(argc, argv)) return *done;   // --help, or error: ... exit 1
//
// The convention (book/README.md): --out is a full file name whose extension picks the format
// (.png, .ppm, .pfm, .exr); a bare file name run from inside the checkout lands in build/out/, never
// loose in the repository (a name with a folder is taken as given); --scene is a name from named_scenes.hpp or a .yaml path; --help
// shows every default; a bad value is "error: ..." and exit code 1.
#include <zraka/app/cli.hpp>
#include <zraka/core/atomic_file.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/image/image.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/samplers.hpp>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace zraka {

// Which shared options a program takes (combine with |).
enum class take : unsigned {
  none = 0, size = 1, spp = 2, depth = 4, seed = 8, threads = 16, out = 32, scene = 64,
  window = 128,  // --window, --window-screenshot: a progressive render shown as it goes (preview_window.hpp)
  sampler = 256,  // --sampler: where a sample's numbers come from (samplers.hpp, book 5.1)
  image = 1 | 2 | 8 | 16 | 32,  // a rendering program: size, spp, seed, threads, out
};
constexpr take operator|(take a, take b) { return take(unsigned(a) | unsigned(b)); }
constexpr bool has(take set, take one) { return (unsigned(set) & unsigned(one)) == unsigned(one); }

namespace detail {
// The bodies of output_folder and output_file below, compiled (compiled.hpp); the root and the
// folder are arguments because only the program knows its resource root.
ZRAKA_COMPILED_FN std::filesystem::path output_folder_in(const std::filesystem::path& resource_root);
ZRAKA_COMPILED_FN std::filesystem::path output_file_in(const std::filesystem::path& name,
                                                       const std::filesystem::path& folder);
ZRAKA_COMPILED_FN std::filesystem::path input_file_in(const std::filesystem::path& name,
                                                      const std::filesystem::path& folder);
// output_file below, with the resource root given.
ZRAKA_COMPILED_FN std::filesystem::path output_file_under(const std::filesystem::path& name,
                                                          const std::filesystem::path& resource_root);
// --window needs an X display: without one, an error that says so, before any work is done.
ZRAKA_COMPILED_FN void check_window_display();
}  // namespace detail

// Where a relative output name goes: <checkout>/build/out/ when the program runs inside the
// source checkout (outside its build folders), else the current folder ("" returned).
inline std::filesystem::path output_folder() { return detail::output_folder_in(resource_root()); }

// The file an output name stands for: a bare file name ("x.png") goes to output_folder(), which
// is made if needed; a name with a folder ("renders/x.png", "/tmp/x.png") is taken as given.
// The name is checked (check_output_name: not empty, its folder exists and can be written), so
// a program that calls this before rendering fails before it writes anything.
inline std::filesystem::path output_file(const std::filesystem::path& name) {
  const std::filesystem::path file = detail::output_file_under(name, resource_root());
  check_output_name(file);
  return file;
}

// An input that an earlier run wrote (e.g. --reference ref.pfm): as given when it exists there,
// else where output_file put it; a missing file is then reported under the name as given.
inline std::filesystem::path input_file(const std::filesystem::path& name) {
  return detail::input_file_in(name, output_folder());
}

// The folder for programs that write several files (--out-dir): output_folder(), or ".".
inline std::string output_dir() {
  const std::filesystem::path f = output_file("f");
  return f.has_parent_path() ? f.parent_path().string() : ".";
}

struct program_options {
  // Defaults: set them before parse(); --help shows them.
  int width = 400, height = 300;
  int spp = 1;
  int depth = 8, min_depth = 1, max_depth = 64;  // depth must be in min_depth..max_depth
  std::uint64_t seed = 1;
  int threads = 0;  // 0 = all cores
  std::string out;  // a full file name; its extension picks the format
  std::vector<std::string> out_types{".png", ".ppm", ".pfm", ".exr"};
  std::string scene = "cornell";  // a name from named_scenes.hpp or a .yaml path
  std::string sampler = "independent";  // --sampler: a name from samplers.hpp; sampler_choice() after parse
  std::string scene_names;        // for --help: named_scene_list() (this header needs no scene types)
  // true: size, spp, depth and seed default to the scene's own settings (apply_to); --help says so.
  bool scene_settings = false;
  bool window = false;            // --window
  std::string window_screenshot;  // --window-screenshot FILE

  cli_app app;  // the program's own options: app.add_option("--name", value, "help")

  ZRAKA_COMPILED_FN program_options(std::string description, take options);

  // Adds the shared options, parses, checks. Returns the exit code when main should stop now.
  // Inline for the resource root (the program's, not the library's; compiled.hpp).
  std::optional<int> parse(int argc, char** argv) { return parse_shared(argc, argv, resource_root()); }
  // The same with the root given: for a program compiled into the library (pathtrace_main.hpp).
  std::optional<int> parse(int argc, char** argv, const std::filesystem::path& root) {
    return parse_shared(argc, argv, root);
  }

  // The render options that --threads asks for.
  render_options render() const {
    render_options ro;
    ro.threads = threads;
    return ro;
  }

  // A file next to --out for a program that writes several: sibling("-reference") of
  // "aa.png" is "aa-reference.png", sibling("-regular", ".csv") is "aa-regular.csv".
  ZRAKA_COMPILED_FN std::string sibling(const std::string& suffix, const std::string& extension = "") const;

  // The sampler --sampler named (parse has checked the name).
  sampler_kind sampler_choice() const { return parse_sampler(sampler); }

  // Was this option on the command line (e.g. given("--spp"))?
  bool given(const std::string& name) const { return app.count(name) > 0; }

  // For scene_settings programs: the scene's settings, overridden by what the command line gave,
  // then checked; the options' fields hold the result. Throws zraka::error.
  template <class Settings> void apply_to(Settings& s) {
    auto take_over = [&](take t, const char* name, auto& field, auto& mine) {
      if (!has(taken_, t)) return;
      if (given(name)) field = mine;
      else mine = field;
    };
    take_over(take::size, "--width", s.width, width);
    take_over(take::size, "--height", s.height, height);
    take_over(take::spp, "--spp", s.spp, spp);
    take_over(take::depth, "--depth", s.max_depth, depth);
    take_over(take::seed, "--seed", s.seed, seed);
    check();
  }

 private:
  take taken_;

  // The parts without templates, compiled once into zraka::compiled (compiled.hpp).
  // parse(), then --out and --window-screenshot put where output_file puts them under this root.
  ZRAKA_COMPILED_FN std::optional<int> parse_shared(int argc, char** argv, const std::filesystem::path& resource_root);
  ZRAKA_COMPILED_FN void check() const;
  ZRAKA_COMPILED_FN void add_shared();
};

}  // namespace zraka

#if ZRAKA_COMPILED_DEFINITIONS
namespace zraka {
ZRAKA_COMPILED_FN std::string program_options::sibling(const std::string& suffix, const std::string& extension) const {
  const std::filesystem::path o(out);
  return ((o.parent_path() / o.stem()).string() + suffix) + (extension.empty() ? o.extension().string() : extension);
}

ZRAKA_COMPILED_FN std::filesystem::path detail::output_folder_in(const std::filesystem::path& resource_root) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path root = fs::weakly_canonical(resource_root, ec);
  if (ec || !fs::exists(root / "CMakeLists.txt", ec) || !fs::exists(root / "include" / "zraka", ec)) return {};
  const fs::path here = fs::weakly_canonical(fs::current_path(ec), ec);
  if (ec) return {};
  const fs::path rel = here.lexically_relative(root);
  if (rel.empty() || *rel.begin() == "..") return {};  // outside the checkout
  if (rel != "." && rel.begin()->string().starts_with("build")) return {};  // build/, build-debug/...
  return root / "build" / "out";
}

ZRAKA_COMPILED_FN std::filesystem::path detail::output_file_under(const std::filesystem::path& name,
                                                                  const std::filesystem::path& resource_root) {
  if (name.has_parent_path()) return name;
  return output_file_in(name, output_folder_in(resource_root));
}

ZRAKA_COMPILED_FN std::filesystem::path detail::output_file_in(const std::filesystem::path& name,
                                                                const std::filesystem::path& dir) {
  if (dir.empty()) return name;
  std::error_code ec;  // a folder that cannot be made shows up as a clear error when writing
  std::filesystem::create_directories(dir, ec);
  // say it short: build/out/x.png when run from the checkout's top
  const auto rel = (dir / name).lexically_relative(std::filesystem::current_path(ec));
  return ec || rel.empty() ? dir / name : rel;
}

ZRAKA_COMPILED_FN std::filesystem::path detail::input_file_in(const std::filesystem::path& name,
                                                              const std::filesystem::path& folder) {
  std::error_code ec;
  if (name.has_parent_path() || std::filesystem::exists(name, ec)) return name;
  if (!folder.empty() && std::filesystem::exists(folder / name, ec)) return output_file_in(name, folder);
  return name;
}

ZRAKA_COMPILED_FN void detail::check_window_display() {
  const char* display = std::getenv("DISPLAY");
  if (!display || !*display)
    throw error("--window needs an X display, and DISPLAY is not set; run it under a virtual one "
                "(xvfb-run -a ... --window --window-screenshot shot.png) or leave out --window");
}

ZRAKA_COMPILED_FN program_options::program_options(std::string description, take options)
    : app(description), taken_(options) {
  app.always_capture_default();  // --help shows every default, the chapter's own too
}

ZRAKA_COMPILED_FN std::optional<int> program_options::parse_shared(int argc, char** argv,
                                                                  const std::filesystem::path& resource_root) {
  add_shared();
  if (const auto done = parse_command_line(app, argc, argv)) return done;
  try {
    if (has(taken_, take::threads)) threads = resolve_threads(threads);
    if (has(taken_, take::sampler)) parse_sampler(sampler);  // an unknown name: the error lists the known ones
    if (has(taken_, take::out)) {
      try {
        check_output_name(out);
      } catch (const error& e) {
        throw error(std::string(e.what()) + " (the value of --out)");
      }
      const std::string ext = std::filesystem::path(out).extension().string();
      bool known = false;
      std::string list;
      for (const std::string& t : out_types) known |= ext == t, list += (list.empty() ? "" : ", ") + t;
      if (!known) throw error("--out " + out + ": unknown image type '" + ext + "' (use " + list + ")");
    }
    if (!window_screenshot.empty()) {
      if (!window) throw error("--window-screenshot needs --window");
      try {
        check_output_name(window_screenshot);
      } catch (const error& e) {
        throw error(std::string(e.what()) + " (the value of --window-screenshot)");
      }
      if (std::filesystem::path(window_screenshot).extension() != ".png")
        throw error("--window-screenshot " + window_screenshot + ": must be a .png file");
    }
    if (window) detail::check_window_display();
    if (!scene_settings) check();
  } catch (const error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  // output_file(), with the program's root
  if (has(taken_, take::out)) out = detail::output_file_under(out, resource_root).string();
  if (!window_screenshot.empty())
    window_screenshot = detail::output_file_under(window_screenshot, resource_root).string();
  return std::nullopt;
}

ZRAKA_COMPILED_FN void program_options::check() const {
  if (has(taken_, take::size)) image::check_size(width, height);
  if (has(taken_, take::spp) && (spp < 1 || spp > 65536))
    throw error("--spp must be in 1..65536, got " + std::to_string(spp));
  if (has(taken_, take::depth) && (depth < min_depth || depth > max_depth))
    throw error("--depth must be in " + std::to_string(min_depth) + ".." + std::to_string(max_depth) +
                ", got " + std::to_string(depth));
}

ZRAKA_COMPILED_FN void program_options::add_shared() {
  auto dflt = [&](cli_option* o) {
    if (scene_settings) o->default_str("the scene's");
  };
  if (has(taken_, take::scene))
    app.add_option("--scene", scene, "a scene name (" + (scene_names.empty() ? "see named_scenes.hpp" : scene_names) +
                                         ") or a .yaml or Mitsuba .xml scene file")
      ;
  if (has(taken_, take::size)) {
    dflt(app.add_option("--width", width, "image width in pixels"));
    dflt(app.add_option("--height", height, "image height in pixels"));
  }
  if (has(taken_, take::spp)) dflt(app.add_option("--spp", spp, "samples per pixel"));
  if (has(taken_, take::depth))
    dflt(app.add_option("--depth", depth, "maximum bounces (" + std::to_string(min_depth) + ".." +
                                              std::to_string(max_depth) + ")"));
  if (has(taken_, take::seed)) dflt(app.add_option("--seed", seed, "random seed (same seed, same result)"));
  if (has(taken_, take::threads))
    app.add_option("--threads", threads, "threads (0 = all cores)");
  if (has(taken_, take::sampler))
    app.add_option("--sampler", sampler, std::string("where each sample's numbers come from: ") + sampler_names +
                                             " (book 5.1)");
  if (has(taken_, take::out)) {
    std::string types;
    for (const std::string& t : out_types) types += (types.empty() ? "" : ", ") + t;
    app.add_option("--out", out, "output file; its extension (" + types +
                                     ") picks the format; a bare name run inside the checkout goes to build/out/");
  }
  if (has(taken_, take::window)) {
    app.add_flag("--window", window, "show the image in a window after every pass, with spp, seconds and the "
                                     "error; S saves a screenshot, Q or Escape stops after the pass (needs a display)");
    app.add_option("--window-screenshot", window_screenshot, "with --window: save the window as this .png after every "
                                                             "pass, and close it at the end (for scripts and tests)");
  }
}
}  // namespace zraka
#endif

// Fuzz target: the command line of pathtrace (chapters/2.3-pathtrace/main.cpp, which calls
// zraka::pathtrace_main, include/zraka/app/pathtrace_main.hpp). The input is the argument list, one
// argument per line; the chapter's main() is compiled into this program as zraka_pathtrace_main
// and called with it, and the program's body (pathtrace_main.hpp's definitions) is compiled here
// too, not taken from zraka::compiled, so that the macros below reach it.
//
// Rendering is cut short here, not in the chapter: render_progressive in that body is replaced,
// by a macro, with small_render below (and --window, preview_window, with no_window, which refuses it), which refuses images above 32x32 pixels (a zraka::error,
// as the program's own refusals are) and renders at most 2 samples per pixel. Everything before
// the render (parsing, scene loading, validation) and after it (reports, PNG/PFM writing) runs as
// in the real program.
//
// The program writes files (--out, --pfm, --report, --export): it runs in a scratch folder that
// is emptied before every input, and inputs with an absolute path or '..' are not run, so a
// mutated argument cannot write outside that folder. Relative scene names are found as usual,
// in the folder or in the resource root (scenes/, tests/scenes/, ...).
#include "fuzz_common.hpp"

// Everything pathtrace_main.hpp includes, first, so that the macros below reach its body only.
#include <zraka/app/cli.hpp>
#include <zraka/app/preview_window.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/input_file.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/io/mitsuba_export.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/io/scene_file.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/cornell.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/named_scenes.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>
#include <vector>

namespace zraka_fuzz {

constexpr long long max_render_pixels = 32 * 32;
constexpr int max_render_spp = 2;

template <class SampleFn, class PassFn>
zraka::image small_render(int width, int height, zraka::progressive_options opt, SampleFn&& fn,
                          PassFn&& on_pass, zraka::progressive_totals* totals_out = nullptr) {
  if (static_cast<long long>(width) * height > max_render_pixels)
    throw zraka::error("fuzz harness: renders at most 32x32 pixels, not " + std::to_string(width) + "x" +
                       std::to_string(height));
  opt.max_spp = std::min(opt.max_spp, max_render_spp);  // a value below 1 still reaches the check
  return zraka::render_progressive(width, height, opt, fn, on_pass, totals_out);
}

// --window would open a window (and wait for a key) wherever DISPLAY is set: the harness has none
// to offer, so the window is replaced by one that refuses it, as the program does without a display.
struct no_window {
  no_window(const zraka::program_options& opt, int, int, const zraka::image* = nullptr, const char* = nullptr,
            const std::filesystem::path& = {}) {
    if (opt.window) throw zraka::error("fuzz harness: no --window");
  }
  bool show(const zraka::image&, int, double) { return true; }
};

}  // namespace zraka_fuzz

#define preview_window zraka_fuzz::no_window
#define render_progressive zraka_fuzz::small_render
#define ZRAKA_COMPILING_PATHTRACE_MAIN  // the definitions here, also when zraka::compiled is linked
#include <zraka/app/pathtrace_main.hpp>
#define main zraka_pathtrace_main
#include "chapters/2.3-pathtrace/main.cpp"
#undef main
#undef render_progressive
#undef preview_window

namespace {

// The scratch folder as the working directory, empty but for ref.pfm (24x24, as the smoke test's).
// The caller goes back to its own folder afterwards (libFuzzer's corpus paths may be relative).
void fresh_folder() {
  static const std::filesystem::path dir = zraka_fuzz::scratch() / "run";
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::filesystem::create_directories(dir);
  if (::chdir(dir.c_str()) != 0) {
    std::perror("zraka fuzz: chdir");
    std::abort();
  }
  zraka::write_pfm(zraka::image(24, 24, zraka::rgb(0.25f, 0.5f, 0.75f)), "ref.pfm");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> args{"pathtrace"};
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    args.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  if (args.size() > 64) return -1;  // not kept in the corpus
  for (const std::string& a : args)
    if (a.find("..") != std::string::npos || a.find("=/") != std::string::npos || (!a.empty() && a[0] == '/'))
      return -1;  // could reach outside the scratch folder
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  static const std::filesystem::path home = std::filesystem::current_path();
  fresh_folder();
  (void)zraka_pathtrace_main(int(args.size()), argv.data());
  if (::chdir(home.c_str()) != 0) {
    std::perror("zraka fuzz: chdir back");
    std::abort();
  }
  return 0;
}

#pragma once
// A window that shows a progressive render as its passes finish (book 2.3, `--window`): after
// each pass the current mean, turned into bytes as the PNG output is (image_io.hpp), over a status
// bar with the samples per pixel, the seconds and, with a reference, the RMSE so far (the title
// says the same). S saves a screenshot; Q, Escape or closing the window stops the render after the
// current pass, and the program still writes what it has. The window is drawn only between
// passes: the render pays one texture upload per pass, and no thread of its own.
//
// The GL side (gl.hpp: GLFW and libepoxy) is compiled once into zraka::compiled where zraka was
// built with both (ZRAKA_COMPILED_GL), in a unit of its own (src/preview_window.cpp), so only
// a program that opens a preview links GLFW, and no chapter's unit reads the GL headers.
// Header-only, this header includes gl.hpp and the program links glfw and epoxy (README.md's
// table). A zraka built without them refuses --window by name.
#include <zraka/app/program_options.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/image/image.hpp>

#include <filesystem>
#include <memory>

#if defined(ZRAKA_COMPILED_GL)
#define ZRAKA_PREVIEW_FN
#else
#define ZRAKA_PREVIEW_FN inline
#endif
#if !defined(ZRAKA_COMPILED_GL) || defined(ZRAKA_COMPILING_PREVIEW)  // src/preview_window.cpp
#define ZRAKA_PREVIEW_DEFINITIONS 1
#else
#define ZRAKA_PREVIEW_DEFINITIONS 0
#endif
// Whether the definitions can open a window at all.
#if defined(ZRAKA_COMPILED_GL) || \
    (!defined(ZRAKA_COMPILED) && __has_include(<epoxy/gl.h>) && __has_include(<GLFW/glfw3.h>))
#define ZRAKA_PREVIEW_GL 1
#else
#define ZRAKA_PREVIEW_GL 0
#endif

namespace zraka {

class preview_window {
 public:
  // Opens the window when the command line said --window (opt.window), else does nothing.
  // `reference`: what the error shown is measured against (nullptr: none); `unit`: what show()'s
  // count counts. Throws zraka::error when there is no display.
  // The shaders are resources: the root is the program's, taken where it calls (compiled.hpp).
  ZRAKA_PREVIEW_FN preview_window(const program_options& opt, int width, int height, const image* reference = nullptr,
                                  const char* unit = "spp",
                                  const std::filesystem::path& resource_root = zraka::resource_root());
  // Without --window-screenshot, waits until the user closes the window (Q, Escape).
  ZRAKA_PREVIEW_FN ~preview_window();
  preview_window(const preview_window&) = delete;
  preview_window& operator=(const preview_window&) = delete;

  // After a pass: shows `mean` after `count` samples per pixel (or passes). False once the user asked to stop.
  bool show(const image& mean, int count, double seconds) { return !s_ || show_pass(mean, count, seconds); }

 private:
  struct state;
  std::unique_ptr<state> s_;
  ZRAKA_PREVIEW_FN bool show_pass(const image& mean, int count, double seconds);
};

}  // namespace zraka

#if ZRAKA_PREVIEW_DEFINITIONS
#if ZRAKA_PREVIEW_GL
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/gpu/gl.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>

#include <stb/stb_easy_font.h>  // a tiny stroke font as axis-aligned quads (Debian's libstb-dev)

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <optional>
#include <string>
#include <vector>

namespace zraka {

struct preview_window::state {
  static constexpr int font_scale = 2, line_height = 12 * font_scale, pad = 6;
  static constexpr int bar = 2 * line_height + 2 * pad;  // two lines of text under the image
  static constexpr std::uint8_t bar_grey = 32, text_grey = 235;
  static constexpr const char* done_keys = "done. S: screenshot   Q, Esc: close";

  int width, height;      // the image
  int zoom = 1, shrink = 1;  // shown at zoom/shrink: whole pixels, so a screenshot holds the image's bytes
  int shown_w = 0, shown_h = 0, fw = 0, fh = 0;  // the image as shown; the window
  const image* reference;
  std::string unit, screenshot_every_pass, screenshot_stem;
  gl::glfw_session glfw;
  std::optional<gl::window> win;
  GLuint program = 0, vao = 0, texture = 0;
  std::string bytes;                // the last mean, 8-bit sRGB as written to PNG
  std::vector<std::uint8_t> frame;  // the window's pixels, rows bottom to top (OpenGL's order)
  std::vector<char> quads;          // the font's output
  int count = 0, shots = 0, passes = 0;
  double busy = 0;  // seconds spent showing passes: inside the render's measured time
  double seconds = 0, error = std::numeric_limits<double>::quiet_NaN();
  bool stop = false, save = false, said_stop = false;

  state(const program_options& opt, int w, int h, const image* ref, const char* what, const std::filesystem::path& root)
      : width(w), height(h), reference(ref), unit(what), screenshot_every_pass(opt.window_screenshot),
        screenshot_stem(window_stem(opt.out)) {
    zoom = std::max(1, std::min(768 / w, 384 / h));  // small test renders (and rows of them) are shown large
    if (const GLFWvidmode* mode = glfwGetVideoMode(glfwGetPrimaryMonitor())) {  // larger than the screen: shrunk
      const int room_w = mode->width, room_h = std::max(1, mode->height - bar);
      if (w * zoom > room_w || h * zoom > room_h)
        zoom = 1, shrink = std::max((w + room_w - 1) / room_w, (h + room_h - 1) / room_h);
    }
    shown_w = w * zoom / shrink, shown_h = h * zoom / shrink;
    const int text_w = std::max(text_width(done_keys), text_width(("65536 " + unit + "  99999.99 s  RMSE 0.00000").c_str()));
    fw = std::max(shown_w, text_w + 2 * pad), fh = shown_h + bar;
    win.emplace(fw, fh, "zraka preview", 3, 3);
    program = gl::link_program({{GL_VERTEX_SHADER, detail::resource_path_in("kernels/realtime.vert", root)},
                                {GL_FRAGMENT_SHADER, detail::resource_path_in("kernels/realtime.frag", root)}});
    glGenVertexArrays(1, &vao);
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, fw, fh, 0, GL_RGB, GL_UNSIGNED_BYTE, nullptr);
    glUseProgram(program);
    glUniform1i(gl::uniform(program, "image"), 0);
    glfwSetWindowUserPointer(win->get(), this);
    glfwSetKeyCallback(win->get(), [](GLFWwindow* gw, int key, int, int action, int) {
      if (action != GLFW_PRESS) return;
      auto& s = *static_cast<state*>(glfwGetWindowUserPointer(gw));
      if (key == GLFW_KEY_Q || key == GLFW_KEY_ESCAPE) s.stop = true;
      if (key == GLFW_KEY_S) s.save = true;
    });
  }
  ~state() {
    glDeleteTextures(1, &texture);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
  }

  // S saves <out's stem>-window-1.png, -2.png, ... beside --out.
  static std::string window_stem(const std::filesystem::path& out) {
    return out.empty() ? "window-" : (out.parent_path() / out.stem()).string() + "-window-";
  }

  static int text_width(const char* text) { return font_scale * stb_easy_font_width(std::string(text).data()); }

  // The font's quads, filled at font_scale into the frame; (x, y) from the window's top left.
  void text(int x, int y, std::string line) {
    quads.resize(64 * 16 * line.size());  // 64 bytes a quad (4 vertices), at most 16 quads a character
    const int n = stb_easy_font_print(0, 0, line.data(), nullptr, quads.data(), int(quads.size()));
    for (int q = 0; q < n; ++q) {
      float v[8];  // x, y of the quad's first and third vertex (opposite corners)
      std::memcpy(v, quads.data() + 64 * q, 8), std::memcpy(v + 2, quads.data() + 64 * q + 32, 8);
      const int x0 = x + int(std::lround(v[0] * font_scale)), x1 = x + int(std::lround(v[2] * font_scale));
      const int y0 = y + int(std::lround(v[1] * font_scale)), y1 = y + int(std::lround(v[3] * font_scale));
      for (int py = std::max(y0, 0); py < std::min(y1, fh); ++py)
        for (int px = std::max(x0, 0); px < std::min(x1, fw); ++px)
          std::fill_n(frame.begin() + 3 * (std::ptrdiff_t(fh - 1 - py) * fw + px), 3, text_grey);
    }
  }

  // The frame: the image at zoom/shrink, the status bar under it; then drawn (not yet swapped).
  void draw(bool done) {
    frame.assign(std::size_t(fw) * std::size_t(fh) * 3, bar_grey);
    for (int y = 0; y < shown_h; ++y)
      for (int x = 0; x < shown_w; ++x) {
        const std::size_t from = 3 * (std::size_t(y * shrink / zoom) * std::size_t(width) + std::size_t(x * shrink / zoom));
        const std::size_t to = 3 * (std::size_t(fh - 1 - y) * std::size_t(fw) + std::size_t(x));
        for (int c = 0; c < 3; ++c) frame[to + std::size_t(c)] = std::uint8_t(bytes[from + std::size_t(c)]);
      }
    char line[160];
    int n = std::snprintf(line, sizeof line, "%d %s  %.2f s", count, unit.c_str(), seconds);
    if (reference) std::snprintf(line + n, sizeof line - std::size_t(n), "  RMSE %.5f", error);
    text(pad, shown_h + pad, line);
    text(pad, shown_h + pad + line_height, done ? done_keys : "S: screenshot   Q, Esc: stop");
    glfwSetWindowTitle(win->get(), ("zraka preview: " + std::string(line)).c_str());

    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, fw, fh, GL_RGB, GL_UNSIGNED_BYTE, frame.data());
    glViewport(0, 0, fw, fh);
    glBindVertexArray(vao);
    glDrawArrays(GL_TRIANGLES, 0, 3);
  }

  // The back buffer just drawn, as a PNG (atomic, image_io.hpp).
  void write_screenshot(const std::string& file) {
    write_png(gl::to_image(gl::read_pixels(fw, fh)), file);
    std::printf("window: wrote %s (%d %s)\n", file.c_str(), count, unit.c_str());
  }

  // Draws, saves what was asked for, shows it, and reads the keys.
  void present(bool done) {
    draw(done);
    if (!screenshot_every_pass.empty() && !done) write_screenshot(screenshot_every_pass);
    if (save) write_screenshot(screenshot_stem + std::to_string(++shots) + ".png"), save = false;
    glfwSwapBuffers(win->get());
    glfwPollEvents();
    stop = stop || !win->open();
  }
};

ZRAKA_PREVIEW_FN preview_window::preview_window(const program_options& opt, int width, int height,
                                                const image* reference, const char* unit,
                                                const std::filesystem::path& resource_root) {
  if (!opt.window) return;
  detail::check_window_display();  // program_options checked it already; a caller may have set opt.window itself
  if (reference) check_same_size(image(width, height), *reference);
  try {
    s_ = std::make_unique<state>(opt, width, height, reference, unit, resource_root);
  } catch (const error& e) {
    throw error(std::string("--window: ") + e.what());
  }
  std::printf("window: %dx%d, the image at %d/%d; S saves a screenshot, Q or Escape stops after the pass\n",
              s_->fw, s_->fh, s_->zoom, s_->shrink);
}

ZRAKA_PREVIEW_FN bool preview_window::show_pass(const image& mean, int count, double seconds) {
  state& s = *s_;
  const stopwatch clock;
  s.count = count, s.seconds = seconds;
  if (s.reference) s.error = rmse(mean, *s.reference);
  detail::encode_8bit(mean, s.bytes);  // the bytes the PNG gets
  s.present(false);
  while (s.save) s.present(false);  // S was pressed: draw again, since the back buffer was swapped
  if (s.stop && !s.said_stop) {
    std::printf("window: stopped after %d %s\n", count, s.unit.c_str());
    s.said_stop = true;
  }
  s.busy += clock.seconds(), ++s.passes;
  return !s.stop;
}

ZRAKA_PREVIEW_FN preview_window::~preview_window() {
  // The last image stays until the user closes the window, unless they stopped the render there
  // (or a screenshot file says this is a scripted run, or an error is on its way out).
  if (!s_) return;
  if (s_->passes > 0)
    std::printf("window: %d passes shown in %.3f s (%.1f ms each)\n", s_->passes,
                s_->busy, 1e3 * s_->busy / s_->passes);
  if (s_->stop || !s_->screenshot_every_pass.empty() || std::uncaught_exceptions() > 0 || s_->bytes.empty()) return;
  try {
    state& s = *s_;
    std::printf("window: done; Q or Escape closes it\n");
    std::fflush(stdout);
    while (!s.stop) {
      s.present(true);
      if (!s.stop && !s.save) glfwWaitEvents();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
  }
}

}  // namespace zraka

#else  // no GLFW or libepoxy

#include <zraka/core/error.hpp>

namespace zraka {
struct preview_window::state {};
ZRAKA_PREVIEW_FN preview_window::preview_window(const program_options& opt, int, int, const image*, const char*,
                                                const std::filesystem::path&) {
  if (opt.window) throw error("--window: this zraka was built without GLFW and libepoxy (tools/setup.sh installs them)");
}
ZRAKA_PREVIEW_FN preview_window::~preview_window() = default;
ZRAKA_PREVIEW_FN bool preview_window::show_pass(const image&, int, double) { return true; }
}  // namespace zraka

#endif  // ZRAKA_PREVIEW_GL
#endif  // ZRAKA_PREVIEW_DEFINITIONS

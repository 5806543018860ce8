#pragma once
// OpenGL helpers for the chapters of book 3.2: a GLFW window with an OpenGL core context (and a
// clear error when there is no display), shaders compiled and linked from files with their logs,
// and a screenshot of the framebuffer as a zraka::image. Function pointers come from libepoxy,
// which loads them on first use, so there is no loader to initialise.
// Link with glfw and epoxy (needs.txt: glfw, epoxy).
// Where zraka was built with both (ZRAKA_COMPILED_GL), the functions marked ZRAKA_GL_FN are
// compiled once into zraka::compiled, in a unit of their own (src/gl.cpp), as compiled.hpp
// explains; header-only they are inline.
#if __has_include(<epoxy/gl.h>) && __has_include(<GLFW/glfw3.h>)  // else empty (chapter skipped)
#include <epoxy/gl.h>  // before GLFW, which then includes no GL header of its own
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/image/image.hpp>
#include <zraka/image/image_io.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#if defined(ZRAKA_COMPILED_GL)
#define ZRAKA_GL_FN
#else
#define ZRAKA_GL_FN inline
#endif
#if !defined(ZRAKA_COMPILED_GL) || defined(ZRAKA_COMPILING_GL)  // src/gl.cpp
#define ZRAKA_GL_DEFINITIONS 1
#else
#define ZRAKA_GL_DEFINITIONS 0
#endif

namespace zraka::gl {

namespace detail {
inline std::string& last_glfw_error() {
  static std::string message;
  return message;
}
}  // namespace detail

// [listing gl-window]
// GLFW for the whole program (step 1 of the life cycle: the window and the context).
class glfw_session {
 public:
  glfw_session();  // or an error that says how to run without a display
  ~glfw_session() { glfwTerminate(); }
  glfw_session(const glfw_session&) = delete;
  glfw_session& operator=(const glfw_session&) = delete;
};

// A window with an OpenGL `major.minor` core-profile context, made current.
class window {
 public:
  window(int width, int height, const std::string& title, int major, int minor);
  ~window() { glfwDestroyWindow(w_); }
  window(const window&) = delete;
  window& operator=(const window&) = delete;
  GLFWwindow* get() const { return w_; }
  bool open() const { return !glfwWindowShouldClose(w_); }
  std::pair<int, int> framebuffer_size() const {
    int w = 0, h = 0;
    glfwGetFramebufferSize(w_, &w, &h);
    return {w, h};
  }

 private:
  GLFWwindow* w_ = nullptr;
};
// [end]

inline std::string gl_string(GLenum what) {
  const auto* s = reinterpret_cast<const char*>(glGetString(what));
  return s ? s : "?";
}

ZRAKA_GL_FN GLuint compile_shader(GLenum stage, const std::filesystem::path& file);
ZRAKA_GL_FN GLuint link_program(const std::vector<std::pair<GLenum, std::filesystem::path>>& stages);

#if ZRAKA_GL_DEFINITIONS
// [listing gl-shaders]
// Steps 4-5: load one shader stage from a file (through the resource root) and compile it.
// A failure names the file and carries the compiler's log.
ZRAKA_GL_FN GLuint compile_shader(GLenum stage, const std::filesystem::path& file) {
  const auto path = resource_path(file.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw error("cannot open shader file " + path.string());
  std::ostringstream text;
  text << in.rdbuf();
  const std::string source = text.str();
  const char* ptr = source.c_str();

  const GLuint shader = glCreateShader(stage);
  glShaderSource(shader, 1, &ptr, nullptr);
  glCompileShader(shader);
  GLint ok = GL_FALSE, length = 0;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetShaderInfoLog(shader, length, nullptr, log.data());
    glDeleteShader(shader);
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    throw error("cannot compile shader " + file.generic_string() + ":\n" + log);
  }
  return shader;
}

// Step 6: link the stages into one program; the shader objects are not needed after that.
ZRAKA_GL_FN GLuint link_program(const std::vector<std::pair<GLenum, std::filesystem::path>>& stages) {
  std::vector<GLuint> shaders;
  std::string names;
  try {
    for (const auto& [stage, file] : stages) {
      shaders.push_back(compile_shader(stage, file));
      names += (names.empty() ? "" : ", ") + file.generic_string();
    }
  } catch (...) {
    for (GLuint s : shaders) glDeleteShader(s);
    throw;
  }
  const GLuint program = glCreateProgram();
  for (GLuint s : shaders) glAttachShader(program, s);
  glLinkProgram(program);
  for (GLuint s : shaders) glDeleteShader(s);  // flagged; freed with the program
  GLint ok = GL_FALSE, length = 0;
  glGetProgramiv(program, GL_LINK_STATUS, &ok);
  if (!ok) {
    glGetProgramiv(program, GL_INFO_LOG_LENGTH, &length);
    std::string log(std::size_t(std::max(length, 1)), '\0');
    glGetProgramInfoLog(program, length, nullptr, log.data());
    glDeleteProgram(program);
    while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    throw error("cannot link shader program " + names + ":\n" + log);
  }
  return program;
}
// [end]
#endif

// The uniform's location; a name the linker removed (unused) or misspelt is an error here,
// not a silent -1 that makes glUniform* do nothing.
inline GLint uniform(GLuint program, const char* name) {
  const GLint loc = glGetUniformLocation(program, name);
  if (loc < 0) throw error(std::string("shader program has no active uniform '") + name + "'");
  return loc;
}

// A screenshot: 8-bit RGB, 3 bytes per pixel (read_pixels below).
struct rgb8_pixels {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bytes;  // 3 per pixel, rows top to bottom
  std::array<int, 3> at(int x, int y) const {
    const std::size_t i = 3 * (std::size_t(y) * std::size_t(width) + std::size_t(x));
    return {bytes[i], bytes[i + 1], bytes[i + 2]};
  }
};

ZRAKA_GL_FN rgb8_pixels read_pixels(int width, int height);  // top row first
ZRAKA_GL_FN image to_image(const rgb8_pixels& p);              // decoded from sRGB to linear

#if ZRAKA_GL_DEFINITIONS
// Step 1 of the life cycle, once per program.
ZRAKA_GL_FN glfw_session::glfw_session() {
  glfwSetErrorCallback([](int, const char* text) { detail::last_glfw_error() = text; });
  if (!glfwInit()) {
    const char* display = std::getenv("DISPLAY");
    std::string why = detail::last_glfw_error();
    if (!display || !*display)
      throw error("cannot open a window: " + why + ". This program needs an X display; on a "
                  "machine without one, run it under a virtual X server: xvfb-run -a -s "
                  "\"-screen 0 1280x720x24\" <program> --frames 10 --screenshot out.png");
    throw error("cannot initialise GLFW: " + why);
  }
}

ZRAKA_GL_FN window::window(int width, int height, const std::string& title, int major, int minor) {
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, major);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, minor);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  glfwWindowHint(GLFW_RESIZABLE, GLFW_FALSE);  // screenshots have the size asked for
  w_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!w_)
    throw error("cannot create a window with an OpenGL " + std::to_string(major) + "." +
                std::to_string(minor) + " core context: " + detail::last_glfw_error());
  glfwMakeContextCurrent(w_);
  glfwSwapInterval(0);  // do not wait for a (virtual) vertical retrace
}

// [listing gl-screenshot]
// The pixels of the current read buffer as 8-bit RGB, top row first. OpenGL's row 0 is the
// bottom one, and its default 4-byte row alignment would pad rows whose size is not a multiple
// of 4, so both are set right here.
ZRAKA_GL_FN rgb8_pixels read_pixels(int width, int height) {
  rgb8_pixels out{width, height, std::vector<std::uint8_t>(std::size_t(width) * height * 3)};
  std::vector<std::uint8_t> bottom_up(out.bytes.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, bottom_up.data());
  const std::size_t row = std::size_t(width) * 3;
  for (int y = 0; y < height; ++y)
    std::copy_n(bottom_up.data() + row * std::size_t(height - 1 - y), row,
                out.bytes.data() + row * std::size_t(y));
  return out;
}

// The framebuffer's bytes are what the screen shows, i.e. sRGB-encoded; zraka::image is linear,
// so they are decoded here and write_png encodes them back to the same bytes (exactly, for all
// 256 values: the sRGB curve's slope keeps neighbouring bytes more than a rounding step apart).
ZRAKA_GL_FN image to_image(const rgb8_pixels& p) {
  image img(p.width, p.height);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const auto c = p.at(x, y);
      img.at(x, y) = rgb(srgb_to_linear(float(c[0]) / 255.0f), srgb_to_linear(float(c[1]) / 255.0f),
                         srgb_to_linear(float(c[2]) / 255.0f));
    }
  return img;
}
// [end]
#endif

}  // namespace zraka::gl
#endif

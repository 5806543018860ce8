// Chapter 3.2 — tessellation on the GPU. The teapot's 32 bicubic Bezier patches go to OpenGL
// as they are, 16 control points per patch; the tessellation control shader (kernels/
// teapot.tesc) sets the levels, the fixed tessellator subdivides each patch's (u, v) square, and
// the evaluation shader (kernels/teapot.tese) maps every generated (u, v) through the patch
// (eq. 1.4) and the model-view-projection matrix. Keys: Up/Down outer level, Right/Left inner
// level, W wireframe, Esc quit. The GPU's triangle count (a GL_PRIMITIVES_GENERATED query) is
// compared with the CPU tessellation of book 1.4 (tessellate.hpp) at the same level.
// Without a display: xvfb-run -a -s "-screen 0 1280x720x24" bin/tessellation --frames 3 --screenshot t.png
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/gpu/gl.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/io/bpt.hpp>
#if __has_include(<zraka/geometry/tessellate.hpp>)
#include <zraka/geometry/tessellate.hpp>
#define ZRAKA_HAVE_CPU_TESSELLATION 1
#endif

#include <zraka/app/cli.hpp>
#include <zraka/app/program_options.hpp>  // output_file: a bare name from the checkout goes to build/out/
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <cstdio>
#include <vector>

namespace {

struct controls {
  float outer = 8, inner = 8;
  bool wireframe = false;
  bool changed = true;
};

// Keys change the levels (1..64: every implementation supports at least 64).
void on_key(GLFWwindow* w, int key, int, int action, int) {
  if (action != GLFW_PRESS && action != GLFW_REPEAT) return;
  auto& c = *static_cast<controls*>(glfwGetWindowUserPointer(w));
  const auto step = [](float& level, float by) { level = std::clamp(level + by, 1.0f, 64.0f); };
  switch (key) {
    case GLFW_KEY_UP: step(c.outer, 1); break;
    case GLFW_KEY_DOWN: step(c.outer, -1); break;
    case GLFW_KEY_RIGHT: step(c.inner, 1); break;
    case GLFW_KEY_LEFT: step(c.inner, -1); break;
    case GLFW_KEY_W: c.wireframe = !c.wireframe; break;
    case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(w, GLFW_TRUE); return;
    default: return;
  }
  c.changed = true;
}

}  // namespace

int main(int argc, char** argv) {
  int width = 400, height = 300, frames = 0, level = 8, inner_level = 0;
  double angle = 30;
  bool wireframe = false;
  std::string screenshot, patch_file = "scenes/teapot.bpt";
  zraka::cli_app app{"Chapter 3.2: the teapot's Bezier patches tessellated on the GPU (OpenGL 4.1)"};
  app.add_option("--width", width, "window width in pixels");
  app.add_option("--height", height, "window height in pixels");
  app.add_option("--frames", frames, "draw this many frames, then stop (0: until the window closes)");
  app.add_option("--screenshot", screenshot, "write the last frame to this PNG file");
  app.add_option("--level", level, "outer tessellation level, 1..64");
  app.add_option("--inner", inner_level, "inner level, 1..64 (default: the same as --level)");
  app.add_option("--angle", angle, "turn the teapot about the vertical axis, degrees");
  app.add_flag("--wireframe", wireframe, "draw the triangles' edges only");
  app.add_option("--patches", patch_file, "Bezier patch file (.bpt)");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return zraka::guarded([&] {
    using namespace zraka;
    const stopwatch clock;
    if (width < 16 || height < 16 || width > 4096 || height > 4096)
      throw error("window size " + std::to_string(width) + "x" + std::to_string(height) +
                  " is out of range (16..4096 each side)");
    if (inner_level == 0) inner_level = level;
    if (level < 1 || level > 64 || inner_level < 1 || inner_level > 64)
      throw error("tessellation levels must be in 1..64, got --level " + std::to_string(level) +
                  " --inner " + std::to_string(inner_level));
    if (frames < 0) throw error("--frames must not be negative");
    if (!screenshot.empty() && frames == 0)
      throw error("--screenshot needs --frames N (the frame to capture is the last one)");
    if (!screenshot.empty() && std::filesystem::path(screenshot).extension() != ".png")
      throw error("--screenshot must name a .png file, got " + screenshot);
    if (!screenshot.empty()) screenshot = output_file(screenshot).string();
    const auto set = load_bpt<float>(resource_path(patch_file));

    gl::glfw_session session;
    gl::window win(width, height, "zraka 3.2: tessellated teapot", 4, 1);  // tessellation: 4.0+
    std::printf("OpenGL %s on %s\n", gl::gl_string(GL_VERSION).c_str(),
                gl::gl_string(GL_RENDERER).c_str());
    const GLuint program = gl::link_program({{GL_VERTEX_SHADER, "kernels/teapot.vert"},
                                             {GL_TESS_CONTROL_SHADER, "kernels/teapot.tesc"},
                                             {GL_TESS_EVALUATION_SHADER, "kernels/teapot.tese"},
                                             {GL_FRAGMENT_SHADER, "kernels/teapot.frag"}});

    // [listing patches]
    // The control points once, and 16 indices per patch: the patch table of the .bpt file.
    std::vector<std::uint32_t> indices;
    for (const auto& p : set.patches) indices.insert(indices.end(), p.begin(), p.end());
    GLuint vao = 0, vbo = 0, ebo = 0;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glGenBuffers(1, &ebo);
    glBindVertexArray(vao);
    glBindBuffer(GL_ARRAY_BUFFER, vbo);
    glBufferData(GL_ARRAY_BUFFER, GLsizeiptr(set.vertices.size() * sizeof(glm::vec3)),
                 set.vertices.data(), GL_STATIC_DRAW);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, sizeof(glm::vec3), nullptr);
    glEnableVertexAttribArray(0);
    glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, ebo);
    glBufferData(GL_ELEMENT_ARRAY_BUFFER, GLsizeiptr(indices.size() * sizeof(std::uint32_t)),
                 indices.data(), GL_STATIC_DRAW);
    glPatchParameteri(GL_PATCH_VERTICES, 16);  // a patch is 16 vertices, not the default 3
    // [end]
    std::printf("patches: %zu, control points: %zu\n", set.patches.size(), set.vertices.size());

    // The teapot data has z up; turn it to y up, then about y by --angle.
    const glm::mat4 model =
        glm::rotate(glm::mat4(1.0f), glm::radians(float(angle)), glm::vec3(0, 1, 0)) *
        glm::rotate(glm::mat4(1.0f), glm::radians(-90.0f), glm::vec3(1, 0, 0));
    const glm::mat4 view = glm::lookAt(glm::vec3(0, 4.2f, 7.5f), glm::vec3(0, 1.3f, 0), glm::vec3(0, 1, 0));
    const glm::mat4 projection =
        glm::perspective(glm::radians(40.0f), float(width) / float(height), 0.1f, 100.0f);
    const glm::mat4 mvp = projection * view * model;
    const glm::mat3 normal_to_world = glm::mat3(model);  // a rotation: its own inverse transpose
    const glm::vec3 light = glm::normalize(glm::vec3(0.3f, 0.6f, 1.0f));

    controls ctl{float(level), float(inner_level), wireframe, true};
    glfwSetWindowUserPointer(win.get(), &ctl);
    glfwSetKeyCallback(win.get(), on_key);
    glEnable(GL_DEPTH_TEST);
    GLuint query = 0;
    glGenQueries(1, &query);

    gl::rgb8_pixels shot;
    GLuint gpu_triangles = 0;
    int drawn = 0;
    while (win.open() && (frames == 0 || drawn < frames)) {
      if (ctl.changed) {
        std::printf("levels: outer %g, inner %g%s\n", double(ctl.outer), double(ctl.inner),
                    ctl.wireframe ? ", wireframe" : "");
        ctl.changed = false;
      }
      glClearColor(0.1f, 0.1f, 0.12f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
      glPolygonMode(GL_FRONT_AND_BACK, ctl.wireframe ? GL_LINE : GL_FILL);
      glUseProgram(program);
      // [listing draw]
      glUniform2f(gl::uniform(program, "outer"), ctl.outer, ctl.outer);
      glUniform2f(gl::uniform(program, "inner"), ctl.inner, ctl.inner);
      glUniformMatrix4fv(gl::uniform(program, "mvp"), 1, GL_FALSE, glm::value_ptr(mvp));
      // [end]
      glUniformMatrix3fv(gl::uniform(program, "normal_to_world"), 1, GL_FALSE,
                         glm::value_ptr(normal_to_world));
      glUniform3fv(gl::uniform(program, "light"), 1, glm::value_ptr(light));
      glUniform1i(gl::uniform(program, "wireframe"), ctl.wireframe ? 1 : 0);
      glBindVertexArray(vao);
      glBeginQuery(GL_PRIMITIVES_GENERATED, query);  // triangles out of the tessellator
      glDrawElements(GL_PATCHES, GLsizei(indices.size()), GL_UNSIGNED_INT, nullptr);
      glEndQuery(GL_PRIMITIVES_GENERATED);
      glGetQueryObjectuiv(query, GL_QUERY_RESULT, &gpu_triangles);  // waits for the GPU: a demo
      if (++drawn == frames) shot = gl::read_pixels(width, height);
      glfwSwapBuffers(win.get());
      glfwPollEvents();
    }
    const double seconds = clock.seconds();
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
      throw error("OpenGL error " + std::to_string(e));

    std::printf("GPU tessellator: %u triangles at outer %g, inner %g\n", gpu_triangles,
                double(ctl.outer), double(ctl.inner));
#ifdef ZRAKA_HAVE_CPU_TESSELLATION
    // With equal integer levels L the quad domain becomes an L x L grid: 2 L^2 triangles per
    // patch, the same grid tessellate() makes on the CPU (book 1.4) with divs = L.
    if (ctl.outer == ctl.inner) {
      const int L = int(ctl.outer);
      const auto mesh = tessellate(set.all_patches(), L);
      std::printf("CPU tessellate(divs %d): %zu triangles, %zu vertices; GPU %s\n", L,
                  mesh.triangle_count(), mesh.positions.size(),
                  mesh.triangle_count() == gpu_triangles ? "the same count" : "a different count");
    }
#endif

    int teapot = 0;
    if (drawn == frames && frames > 0) {
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const auto c = shot.at(x, y);
          teapot += std::abs(c[0] - 26) + std::abs(c[1] - 26) + std::abs(c[2] - 31) > 6 ? 1 : 0;
        }
      const auto c = shot.at(width / 2, height / 2);
      std::printf("pixels not background: %d of %d (%.1f%%); centre pixel %d %d %d\n", teapot,
                  width * height, 100.0 * teapot / (width * height), c[0], c[1], c[2]);
    }
    glDeleteQueries(1, &query);
    glDeleteBuffers(1, &ebo);
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
    if (!screenshot.empty()) {
      write_png(gl::to_image(shot), screenshot);
      std::printf("wrote %s\n", screenshot.c_str());
    }
    std::printf("summary: %d frame(s) of %dx%d in %.3f s, %u triangles from %zu patches per frame\n",
                drawn, width, height, seconds, gpu_triangles, set.patches.size());
    return 0;
  });
}

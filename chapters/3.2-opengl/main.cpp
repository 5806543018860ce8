// Chapter 3.2 — OpenGL. One coloured triangle, following the thesis's 20-step life cycle of an
// OpenGL program: a window and context, a VBO holding position and colour interleaved (the
// stride is 6 floats, errata B12), a VAO recording that layout, shaders read from
// kernels/triangle.vert and .frag, the render loop, and clean-up. With --frames N it draws N
// frames and stops; --screenshot writes the last one as PNG, and the program checks a few of
// its pixels against the colours interpolated from the vertices. --points draws the vertices as
// points that a geometry shader (kernels/points.geom, the thesis's Listing 3.3) turns into lines.
// Without a display: xvfb-run -a -s "-screen 0 1280x720x24" bin/opengl --frames 3 --screenshot t.png
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/gpu/gl.hpp>
#include <zraka/image/image_io.hpp>

#include <zraka/app/cli.hpp>
#include <zraka/app/program_options.hpp>  // output_file: a bare name from the checkout goes to build/out/

#include <array>
#include <cmath>
#include <cstdio>

namespace {

// The triangle in normalised device coordinates, a colour per vertex.
constexpr std::array<float, 18> vertices = {
    // [listing vertices]
    // x      y     z     r     g     b
    -0.8f, -0.7f, 0.0f, 1.0f, 0.0f, 0.0f,  // vertex 0: position, then colour
    0.8f,  -0.7f, 0.0f, 0.0f, 1.0f, 0.0f,  // vertex 1
    0.0f,  0.8f,  0.0f, 0.0f, 0.0f, 1.0f,  // vertex 2
    // [end]
};

}  // namespace

int main(int argc, char** argv) {
  int width = 400, height = 300, frames = 0;
  std::string screenshot, vertex_file = "kernels/triangle.vert",
                          fragment_file = "kernels/triangle.frag";
  bool thesis_stride = false, points = false;
  zraka::cli_app app{"Chapter 3.2: a coloured triangle with OpenGL 3.3 core"};
  app.add_option("--width", width, "window width in pixels");
  app.add_option("--height", height, "window height in pixels");
  app.add_option("--frames", frames, "draw this many frames, then stop (0: until the window closes)");
  app.add_option("--screenshot", screenshot, "write the last frame to this PNG file");
  app.add_option("--vertex", vertex_file, "vertex shader file");
  app.add_option("--fragment", fragment_file, "fragment shader file");
  app.add_flag("--thesis-stride", thesis_stride, "use the thesis's stride of 3 floats (wrong: B12)");
  app.add_flag("--points", points, "draw the vertices as points that a geometry shader turns "
                                   "into short lines (kernels/points.geom)");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return zraka::guarded([&] {
    using namespace zraka;
    const stopwatch clock;
    if (width < 16 || height < 16 || width > 4096 || height > 4096)
      throw error("window size " + std::to_string(width) + "x" + std::to_string(height) +
                  " is out of range (16..4096 each side)");
    if (frames < 0) throw error("--frames must not be negative");
    if (!screenshot.empty() && frames == 0)
      throw error("--screenshot needs --frames N (the frame to capture is the last one)");
    if (!screenshot.empty() && std::filesystem::path(screenshot).extension() != ".png")
      throw error("--screenshot must name a .png file, got " + screenshot);
    if (!screenshot.empty()) screenshot = output_file(screenshot).string();

    // 1. the window and the OpenGL context
    gl::glfw_session session;
    gl::window win(width, height, "zraka 3.2: triangle", 3, 3);
    std::printf("OpenGL %s on %s\n", gl::gl_string(GL_VERSION).c_str(),
                gl::gl_string(GL_RENDERER).c_str());

    // 3-6. the shader program, from files (the log and the file name on error)
    const GLuint program =
        points ? gl::link_program({{GL_VERTEX_SHADER, vertex_file},
                                   {GL_GEOMETRY_SHADER, "kernels/points.geom"},
                                   {GL_FRAGMENT_SHADER, "kernels/points.frag"}})
               : gl::link_program({{GL_VERTEX_SHADER, vertex_file},
                                   {GL_FRAGMENT_SHADER, fragment_file}});

    // [listing buffers]
    // 2, 7-10. a VAO that records the layout, a VBO with the interleaved data
    GLuint vao = 0, vbo = 0;
    glGenVertexArrays(1, &vao);
    glGenBuffers(1, &vbo);
    glBindVertexArray(vao);                // 7. later attribute calls are recorded in it
    glBindBuffer(GL_ARRAY_BUFFER, vbo);    // 8.
    glBufferData(GL_ARRAY_BUFFER, sizeof vertices, vertices.data(), GL_STATIC_DRAW);  // 9.
    // 10. one call per attribute. The stride is the distance from one vertex to the next:
    // 6 floats (position and colour), not 3. The offset is in bytes, passed as a pointer.
    const GLsizei stride = GLsizei((thesis_stride ? 3 : 6) * sizeof(float));
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, stride, reinterpret_cast<void*>(0));
    glEnableVertexAttribArray(0);  // attributes are off until enabled
    glVertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, stride,
                          reinterpret_cast<void*>(3 * sizeof(float)));
    glEnableVertexAttribArray(1);
    // [end]
    if (thesis_stride) std::printf("stride: 3 floats, as in the thesis (wrong, errata B12)\n");

    // [listing loop]
    // 11-16. the render loop: clear, use the program, draw, swap the buffers, handle events
    gl::rgb8_pixels shot;
    int drawn = 0;
    while (win.open() && (frames == 0 || drawn < frames)) {
      glClearColor(0.1f, 0.1f, 0.1f, 1.0f);
      glClear(GL_COLOR_BUFFER_BIT);
      glUseProgram(program);  // 12. (this program has no uniforms to set, step 13)
      glBindVertexArray(vao);
      glDrawArrays(points ? GL_POINTS : GL_TRIANGLES, 0, 3);  // 14.
      if (++drawn == frames) shot = gl::read_pixels(width, height);  // the back buffer
      glfwSwapBuffers(win.get());  // 15. show the finished frame, draw into the other one
      glfwPollEvents();
    }
    // [end]
    const double seconds = clock.seconds();
    if (const GLenum e = glGetError(); e != GL_NO_ERROR)
      throw error("OpenGL error " + std::to_string(e));

    // Check: the colour at a pixel centre is the vertices' colours weighted by its barycentrics.
    int matching = 0, checked = 0, covered = 0;
    if (drawn == frames && frames > 0 && points) {
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const auto c = shot.at(x, y);
          covered += std::abs(c[0] - 26) + std::abs(c[1] - 26) + std::abs(c[2] - 26) > 6 ? 1 : 0;
        }
      std::printf("pixels covered by the lines: %d (3 lines of 0.2 x %d / 2 = %d pixels each)\n",
                  covered, width, width / 10);
    } else if (drawn == frames && frames > 0) {
      const auto ndc_to_pixel = [&](float x, float y) {
        return std::array<double, 2>{(x + 1.0) / 2 * width, (1.0 - y) / 2 * height};
      };
      std::array<std::array<double, 2>, 3> p;
      for (int k = 0; k < 3; ++k) p[k] = ndc_to_pixel(vertices[6 * k], vertices[6 * k + 1]);
      const auto edge = [](const std::array<double, 2>& a, const std::array<double, 2>& b,
                           double x, double y) {
        return (b[0] - a[0]) * (y - a[1]) - (b[1] - a[1]) * (x - a[0]);
      };
      const double area2 = edge(p[0], p[1], p[2][0], p[2][1]);
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const auto c = shot.at(x, y);
          covered += std::abs(c[0] - 26) + std::abs(c[1] - 26) + std::abs(c[2] - 26) > 6 ? 1 : 0;
        }
      // Points with barycentric weights (w0, w1, w2): the centroid and near each vertex.
      const double weights[4][3] = {{1 / 3.0, 1 / 3.0, 1 / 3.0}, {0.8, 0.1, 0.1},
                                    {0.1, 0.8, 0.1}, {0.1, 0.1, 0.8}};
      for (const auto& w : weights) {
        const int x = int(w[0] * p[0][0] + w[1] * p[1][0] + w[2] * p[2][0]);
        const int y = int(w[0] * p[0][1] + w[1] * p[1][1] + w[2] * p[2][1]);
        const double cx = x + 0.5, cy = y + 0.5;  // the pixel centre's own barycentrics
        const double b[3] = {edge(p[1], p[2], cx, cy) / area2, edge(p[2], p[0], cx, cy) / area2,
                             edge(p[0], p[1], cx, cy) / area2};
        std::array<int, 3> expected{};
        for (int ch = 0; ch < 3; ++ch)
          expected[ch] = int(std::lround(255 * (b[0] * vertices[3 + ch] + b[1] * vertices[9 + ch] +
                                                b[2] * vertices[15 + ch])));
        const auto got = shot.at(x, y);
        bool ok = true;  // 2/255: rasterizers interpolate in float and may round either way
        for (int ch = 0; ch < 3; ++ch) ok = ok && std::abs(got[ch] - expected[ch]) <= 2;
        matching += ok;
        ++checked;
        std::printf("pixel (%d, %d): %d %d %d, expected %d %d %d%s\n", x, y, got[0], got[1],
                    got[2], expected[0], expected[1], expected[2], ok ? "" : "  <- differs");
      }
      std::printf("pixels with the interpolated colour: %d of %d (within 2/255)\n", matching,
                  checked);
      std::printf("pixels covered: %d; the triangle's area: %.0f pixels\n", covered,
                  std::abs(area2) / 2);
    }

    // [listing cleanup]
    // 17-19. delete the buffers and the program; the window and context go with their owners
    glDeleteBuffers(1, &vbo);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);
    // [end]

    if (!screenshot.empty()) {
      write_png(gl::to_image(shot), screenshot);
      std::printf("wrote %s\n", screenshot.c_str());
    }
    std::printf("summary: %d frame(s) of %dx%d in %.3f s (%.1f frames/s)", drawn, width, height,
                seconds, drawn / seconds);
    if (checked) std::printf(", %d of %d pixels as interpolated", matching, checked);
    std::printf("\n");
    return 0;
  });
}

#pragma once
// The `realtime` program (book 4.3) as a function: chapter 4.3's main.cpp calls it without a
// registry, and a course's own program calls it with the registry of its shapes and materials
// (scene_registry.hpp), so that its binary offers the real-time path tracer on its scene files
// too. The kernel cannot run C++ code: a scene with a course's shape or material is refused before
// the first frame, by the object's or material's name and the kind's, with the program that can
// render it (gpu_scene.hpp's pack_scene, render_it_with.hpp).
//
// What it does: the thesis's third program, path tracing in OpenCL, shown by OpenGL. The scene is
// packed into flat arrays (gpu_scene.hpp), the kernel (kernels/pathtrace.cl) is compiled for the
// features the scene uses, and every frame adds samples to a per-pixel sum on the device
// (progressive accumulation). The running mean comes back to the host and goes into a texture
// drawn over the whole window (PoCL, the CPU OpenCL this course runs on, cannot share buffers with
// OpenGL). Moving the camera starts the sum again.
//
// --headless renders with the same kernel and writes --out, without a window. A scene file's
// settings (width, height, spp, max_depth, seed) are used unless given on the command line.
// --integrator naive|nee|mis picks path.hpp's method, compiled into the kernel. What the kernel
// cannot render (a user shape, a custom BSDF, participating media) is an error before the
// first frame. The program prints the device, the kernel options, size, spp, depth and time
// together (errata C12), and in window mode the viewer's frame rate next to the kernel's alone.
//
// Compiled once into zraka::compiled where zraka was built with yaml-cpp, OpenCL, GLFW and libepoxy
// (ZRAKA_COMPILED_SCENE_FILE, ZRAKA_COMPILED_OPENCL, ZRAKA_COMPILED_GL), in a unit of its own
// (src/realtime_main.cpp), so only a program that calls it links OpenCL and GLFW; header-only,
// inline (the program then links OpenCL, glfw and epoxy itself). The resource root is the calling
// program's (compiled.hpp), passed by the inline wrapper.
#include <zraka/core/compiled.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/scene/scene_registry.hpp>

#include <filesystem>

#if defined(ZRAKA_COMPILED_SCENE_FILE) && defined(ZRAKA_COMPILED_OPENCL) && defined(ZRAKA_COMPILED_GL)
#define ZRAKA_REALTIME_MAIN_FN
#define ZRAKA_REALTIME_MAIN_COMPILED 1
#else
#define ZRAKA_REALTIME_MAIN_FN inline
#define ZRAKA_REALTIME_MAIN_COMPILED 0
#endif
#if !ZRAKA_REALTIME_MAIN_COMPILED || defined(ZRAKA_COMPILING_REALTIME_MAIN)
#define ZRAKA_REALTIME_MAIN_DEFINITIONS 1
#else
#define ZRAKA_REALTIME_MAIN_DEFINITIONS 0
#endif
// Header-only without OpenCL's, GLFW's or libepoxy's headers: the program refuses to run, by name.
#if ZRAKA_REALTIME_MAIN_DEFINITIONS && !ZRAKA_REALTIME_MAIN_COMPILED && \
    !(__has_include(<CL/cl.h>) && __has_include(<epoxy/gl.h>) && __has_include(<GLFW/glfw3.h>))
#define ZRAKA_REALTIME_MAIN_MISSING 1
#else
#define ZRAKA_REALTIME_MAIN_MISSING 0
#endif

#if ZRAKA_REALTIME_MAIN_MISSING
#include <cstdio>
#elif ZRAKA_REALTIME_MAIN_DEFINITIONS
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/gpu/cl.hpp>
#include <zraka/gpu/gl.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/gpu/realtime.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/integrator_door.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/scene/named_scenes.hpp>
#include <zraka/scene/scene_query.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>
#endif

namespace zraka {

namespace detail {
#if ZRAKA_REALTIME_MAIN_DEFINITIONS && !ZRAKA_REALTIME_MAIN_MISSING
namespace realtime_app {

inline rgb mean_colour(const image& img) {
  vec3 sum(0);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) sum += vec3(img.at(x, y));
  return rgb(sum / double(img.width * img.height));
}

// [listing orbit]
// The viewer's camera: it orbits look_at (yaw about +y, pitch), moves with look_at, and keeps
// the field of view and the aperture; every change gives a new prepared camera for the kernel.
struct orbit_camera {
  camera base;
  double yaw = 0, pitch = 0, distance = 1;

  explicit orbit_camera(const camera& c) : base(c) {
    const vec3 d = c.position - c.look_at;
    distance = glm::length(d);
    yaw = std::atan2(d.x, d.z);
    pitch = std::asin(std::clamp(d.y / distance, -1.0, 1.0));
  }
  camera current() const {
    camera c = base;
    c.position = c.look_at + distance * vec3(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                                             std::cos(pitch) * std::cos(yaw));
    return c;
  }
  void move(const vec3& local) {  // x right, y up, z forward, in the camera's frame
    const camera c = current();
    const vec3 forward = glm::normalize(c.look_at - c.position);
    const vec3 right = glm::normalize(glm::cross(forward, c.up));
    base.look_at += local.x * right + local.y * c.up + local.z * forward;
  }
};
// [end]

struct viewer_input {
  orbit_camera* cam;
  bool changed = false, dragging = false;
  double last_x = 0, last_y = 0, step = 0.1;
};

inline void print_controls() {
  std::printf("controls: drag with the left mouse button to orbit; W/S forward/back, A/D left/"
              "right, Q/E down/up; scroll or +/- field of view; [ ] aperture; R reset; Esc quit\n");
}

// Keys and mouse change the orbit camera; the loop then uploads it and resets the sums.
inline void install_callbacks(GLFWwindow* w, viewer_input& in) {
  glfwSetWindowUserPointer(w, &in);
  glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
    if (action == GLFW_RELEASE) return;
    auto& s = *static_cast<viewer_input*>(glfwGetWindowUserPointer(win));
    auto& c = *s.cam;
    const double step = s.step * c.distance;
    switch (key) {
      case GLFW_KEY_ESCAPE: glfwSetWindowShouldClose(win, GLFW_TRUE); return;
      case GLFW_KEY_W: c.move({0, 0, step}); break;
      case GLFW_KEY_S: c.move({0, 0, -step}); break;
      case GLFW_KEY_A: c.move({-step, 0, 0}); break;
      case GLFW_KEY_D: c.move({step, 0, 0}); break;
      case GLFW_KEY_Q: c.move({0, -step, 0}); break;
      case GLFW_KEY_E: c.move({0, step, 0}); break;
      case GLFW_KEY_EQUAL: case GLFW_KEY_KP_ADD: c.base.vfov_degrees = std::max(5.0, c.base.vfov_degrees - 2); break;
      case GLFW_KEY_MINUS: case GLFW_KEY_KP_SUBTRACT: c.base.vfov_degrees = std::min(120.0, c.base.vfov_degrees + 2); break;
      case GLFW_KEY_LEFT_BRACKET: c.base.aperture = std::max(0.0, c.base.aperture - 0.02); break;
      case GLFW_KEY_RIGHT_BRACKET: c.base.aperture += 0.02; break;
      case GLFW_KEY_R: c = orbit_camera(c.base); break;
      default: return;
    }
    s.changed = true;
  });
  glfwSetMouseButtonCallback(w, [](GLFWwindow* win, int button, int action, int) {
    auto& s = *static_cast<viewer_input*>(glfwGetWindowUserPointer(win));
    if (button != GLFW_MOUSE_BUTTON_LEFT) return;
    s.dragging = action == GLFW_PRESS;
    glfwGetCursorPos(win, &s.last_x, &s.last_y);
  });
  glfwSetCursorPosCallback(w, [](GLFWwindow* win, double x, double y) {
    auto& s = *static_cast<viewer_input*>(glfwGetWindowUserPointer(win));
    if (!s.dragging) return;
    s.cam->yaw -= 0.01 * (x - s.last_x);
    s.cam->pitch = std::clamp(s.cam->pitch + 0.01 * (y - s.last_y), -1.5, 1.5);
    s.last_x = x;
    s.last_y = y;
    s.changed = true;
  });
  glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
    auto& s = *static_cast<viewer_input*>(glfwGetWindowUserPointer(win));
    s.cam->base.vfov_degrees = std::clamp(s.cam->base.vfov_degrees - 2 * dy, 5.0, 120.0);
    s.changed = true;
  });
}

}  // namespace realtime_app
#endif

ZRAKA_REALTIME_MAIN_FN int realtime_main_in(int argc, char** argv, const scene_registry& registry,
                                            const std::filesystem::path& root)
#if ZRAKA_REALTIME_MAIN_MISSING
{
  (void)argc, (void)argv, (void)registry, (void)root;
  std::fprintf(stderr, "error: realtime needs OpenCL, GLFW and libepoxy, and their headers were not found\n");
  return 1;
}
#elif ZRAKA_REALTIME_MAIN_DEFINITIONS
{
  using namespace realtime_app;
  program_options opt{"Chapter 4.3: real-time path tracing with OpenCL, shown with OpenGL",
                      take::scene | take::size | take::spp | take::depth | take::seed | take::out};
  opt.scene = "spheres", opt.out = "realtime.png";
  opt.scene_names = named_scene_list();
  opt.scene_settings = true;  // a scene file's width, height, spp, max_depth and seed (else below)
  opt.min_depth = 0;
  std::string screenshot, kernel_file = "kernels/pathtrace.cl", method = "mis";
  std::optional<int> frames_opt, spf_opt;
  int device_index = 0, rr_depth = 3;
  bool headless = false, weak_seed = false, all_features = false;
  zraka::cli_app& app = opt.app;
  app.add_option("--frames", frames_opt, "frames to render, then stop (window mode: 0 = until closed)")
      ->default_str("window: 0; headless: --spp's worth");
  app.add_option("--spp-per-frame", spf_opt, "samples per pixel added by each frame")
      ->default_str("window: 1; headless: from the image size");
  app.add_option("--rr-depth", rr_depth, "Russian roulette from this many bounces on");
  app.add_option("--integrator", method, "naive, nee or mis (path.hpp's methods)");
  app.add_option("--device", device_index, "OpenCL device number (chapter 3.3's --list)");
  app.add_flag("--headless", headless, "no window: render --frames frames (or --spp) and write --out");
  app.add_option("--screenshot", screenshot, "window mode: save the window after --frames frames (.png, .ppm, .pfm; "
                                              "a bare name run inside the checkout goes to build/out/)");
  app.add_flag("--weak-seed", weak_seed, "seed each pixel with its raw coordinates, as the thesis's "
                                         "tutorial did (errata C7), to see the pattern noise");
  app.add_flag("--all-features", all_features, "compile every code path, not just the scene's");
  app.add_option("--kernel", kernel_file, "the kernel file, built after kernels/rng.cl (resource "
                                          "root or working directory)");
  if (const auto done = opt.parse(argc, argv, root)) return *done;

  return guarded([&] {
    const stopwatch clock;
    refuse_course_integrator(method, registry, "realtime", "the OpenCL kernel");  // before the scene and device
    // A scene file brings its own settings; the built-in scenes use this program's: 512x512,
    // depth 8, seed 1, and headless 8 frames' worth of samples.
    int spf = spf_opt.value_or(1);
    if (spf < 1 || spf > 4096) throw error("--spp-per-frame must be in 1..4096, got " + std::to_string(spf));
    loaded_scene loaded = load_scene_argument_in(opt.scene, root, registry);  // the course's kinds too
    scene& sc = loaded.sc;
    const named_scene* built_in = is_scene_path(opt.scene) ? nullptr : find_named_scene(opt.scene);
    if (built_in && built_in->build) {
      sc.settings.width = sc.settings.height = 512;
      sc.settings.max_depth = 8, sc.settings.seed = 1, sc.settings.spp = 8 * spf;
    }
    opt.apply_to(sc.settings);  // the command line over the scene's settings, checked
    method = chosen_integrator(method, opt.given("--integrator"), sc, opt.scene, registry);  // or the scene's
    refuse_course_integrator(method, registry, "realtime", "the OpenCL kernel");
    const int width = opt.width, height = opt.height, depth = opt.depth;
    const std::uint64_t seed = opt.seed;
    const std::string& out = opt.out;
    int frames = frames_opt.value_or(0);
    if (width > 4096 || height > 4096)
      throw error("image size " + std::to_string(width) + "x" + std::to_string(height) +
                  " is out of range (1..4096)");
    if (frames < 0) throw error("--frames must not be negative, got " + std::to_string(frames));
    if (rr_depth < 0) throw error("--rr-depth must not be negative, got " + std::to_string(rr_depth));
    if (frames_opt && opt.given("--spp")) throw error("give --frames or --spp, not both");
    if (!headless && opt.given("--spp")) throw error("--spp is for --headless; in window mode use --frames");
    if (headless && !screenshot.empty()) throw error("--screenshot is for window mode; use --out with --headless");
    if (!headless && opt.given("--out")) throw error("--out is for --headless; in window mode use --screenshot");
    if (!screenshot.empty() && frames == 0) throw error("--screenshot needs --frames N");
    if (!screenshot.empty()) {  // the same convention as --out
      check_output_name(screenshot);
      const std::string ext = std::filesystem::path(screenshot).extension().string();
      if (ext != ".png" && ext != ".ppm" && ext != ".pfm")
        throw error("--screenshot " + screenshot + ": unknown image type '" + ext + "' (use .png, .ppm, .pfm)");
      screenshot = output_file_under(screenshot, root).string();
    }
    if (headless && frames_opt && frames == 0) throw error("--frames must be positive with --headless");
    // Headless: the samples per pixel in all, in frames of spf (the last one may be smaller).
    int total_spp = frames * spf;
    std::string spf_note;
    if (headless && !frames_opt) {
      total_spp = opt.spp;
      // No window to keep responsive: a frame of about 4 M paths (16 spp at 512x512) costs its
      // launch and wait once, not per sample (one sample a frame took twice as long on PoCL).
      // A pixel's sum adds its samples one by one alike in frames of one and in a single frame,
      // so the default (8 spp, one frame) is the image of before bit for bit; frames of 2 or
      // more group the float sums differently, which changes the last bits.
      if (!spf_opt) {
        constexpr double paths_per_frame = 1 << 22;
        spf = int(std::clamp(std::floor(paths_per_frame / (double(width) * height)), 1.0, double(total_spp)));
        spf_note = " (chosen: about 4 M paths a frame; --spp-per-frame sets it)";
      }
      frames = (total_spp + spf - 1) / spf;
    }
    path_options po;
    po.method = parse_integrator(method);
    po.max_depth = depth;
    po.rr_depth = rr_depth;

    // The window first: without a display there is nothing to build the kernel for.
    std::optional<gl::glfw_session> glfw;
    std::optional<gl::window> window;
    if (!headless) {
      try {
        glfw.emplace();
      } catch (const error& e) {
        throw error(std::string(e.what()) + "; or render without a window: --headless --frames 8 "
                                            "--out image.png");
      }
      window.emplace(width, height, "zraka realtime", 3, 3);
    }

    // [listing setup]
    gpu_scene packed = pack_scene(sc, width, height, po);  // or an error naming what it cannot render
    packed.features.weak_seed = weak_seed;
    if (!headless) packed.features.thin_lens = true;  // the viewer can open the aperture
    std::optional<cl::context> ctx;
    try {
      ctx.emplace(cl::pick_device(device_index));
    } catch (const cl::no_platform& e) {
      throw error(std::string("the real-time path tracer needs an OpenCL device: ") + e.what());
    }
    gpu_renderer renderer(*ctx, packed, width, height, seed, all_features, kernel_file);
    // [end]
    std::printf("device: %s (%s, %s, %u compute units)\n", ctx->device.device_name.c_str(),
                ctx->device.platform_name.c_str(), ctx->device.c_version.c_str(),
                ctx->device.compute_units);
    std::printf("scene %s: %s\n", opt.scene.c_str(), describe_built(sc).c_str());
    std::printf("%s\n", packed.light_summary.c_str());
    std::printf("kernel options: %s\n", renderer.options().c_str());
    std::printf("kernel build: %.2f s (PoCL caches binaries; POCL_KERNEL_CACHE=0 while editing kernels)\n",
                renderer.build_seconds());
    std::printf("image %dx%d, %d spp per frame%s, depth %d, integrator %s, Russian roulette from bounce %d, "
                "seed %llu%s\n", width, height, spf, spf_note.c_str(), depth, name(po.method), rr_depth,
                static_cast<unsigned long long>(seed), weak_seed ? ", weak per-pixel seed (errata C7)" : "");

    if (headless) {
      // [listing headless]
      stopwatch run;
      for (int f = 0; f < frames; ++f) renderer.launch(std::uint32_t(std::min(spf, total_spp - f * spf)));
      const image img = renderer.read_image();  // waits for the queue
      const double secs = run.seconds();
      // [end]
      write_image(img, out);
      const rgb m = mean_colour(img);
      const double paths = double(width) * height * total_spp;
      std::printf("frames: %d, %u spp, %.1f ms per frame, %.2f M paths/s\n", frames,
                  renderer.samples(), 1e3 * secs / frames, paths / secs * 1e-6);
      std::printf("mean colour: %.4f %.4f %.4f\n", double(m.x), double(m.y), double(m.z));
      std::printf("wrote %s\n", out.c_str());
      std::printf("summary: %d frames of %dx%d at %d spp each (%d spp, %s) on %s in %.2f s (%.1f ms per "
                  "frame); %.2f s in total\n", frames, width, height, spf, total_spp, name(po.method),
                  ctx->device.device_name.c_str(), secs, 1e3 * secs / frames, clock.seconds());
      return 0;
    }

    // [listing viewer]
    gl::window& win = *window;
    std::printf("OpenGL %s\n", gl::gl_string(GL_VERSION).c_str());
    print_controls();
    const GLuint program = gl::link_program({{GL_VERTEX_SHADER, resource_path_in("kernels/realtime.vert", root)},
                                             {GL_FRAGMENT_SHADER, resource_path_in("kernels/realtime.frag", root)}});
    GLuint vao = 0, texture = 0;
    glGenVertexArrays(1, &vao);  // empty: the vertex shader makes the triangle from gl_VertexID
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, width, height, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    glUseProgram(program);
    glUniform1i(gl::uniform(program, "image"), 0);

    orbit_camera orbit(sc.camera);
    viewer_input input{&orbit};
    install_callbacks(win.get(), input);
    // Two host copies of the frame: the device renders into one while the other is drawn.
    std::vector<std::uint8_t> shown, next;
    renderer.launch(1);  // PoCL compiles the work-group function on the first launch: not timed
    renderer.finish();
    const int n_alone_before = std::min(frames, 60) / 2;  // the kernel alone, first half
    stopwatch before;
    for (int f = 0; f < n_alone_before; ++f) {
      renderer.launch(std::uint32_t(spf));
      renderer.finish();
    }
    const double alone_before_secs = before.seconds();
    renderer.reset();
    stopwatch run, title_clock;
    int frame = 0, title_frames = 0;
    renderer.launch(std::uint32_t(spf));
    renderer.read_display_async(next);
    std::uint32_t shown_spp = 0, next_spp = renderer.samples();
    while (win.open() && (frames == 0 || frame < frames)) {
      glfwPollEvents();
      renderer.wait_display();  // frame k is in `next`
      std::swap(shown, next);
      shown_spp = next_spp;
      if (input.changed) {  // a new view: upload the camera, start the sums again
        camera c = orbit.current();
        c.aspect = double(width) / height;
        renderer.set_camera(to_gpu(c.prepare()));
        input.changed = false;
      }
      if (frames == 0 || frame + 1 < frames) {  // frame k + 1 runs while frame k is drawn
        renderer.launch(std::uint32_t(spf));
        renderer.read_display_async(next);
        next_spp = renderer.samples();
      }
      glTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, shown.data());
      const auto [fw, fh] = win.framebuffer_size();
      glViewport(0, 0, fw, fh);
      glBindVertexArray(vao);
      glDrawArrays(GL_TRIANGLES, 0, 3);
      ++frame;
      ++title_frames;
      if (title_clock.seconds() > 0.5 || (frames > 0 && frame == frames)) {
        const double dt = title_clock.seconds() / title_frames;
        char title[160];
        std::snprintf(title, sizeof title, "zraka realtime - %.1f fps, %u spp, %.1f ms/frame",
                      1.0 / dt, shown_spp, 1e3 * dt);
        glfwSetWindowTitle(win.get(), title);
        title_clock = stopwatch();
        title_frames = 0;
      }
      if (!screenshot.empty() && frame == frames) {  // before the swap: the back buffer
        const image shot = gl::to_image(gl::read_pixels(fw, fh));
        write_image(shot, screenshot);
        const rgb m = mean_colour(shot);
        std::printf("screenshot %s: mean colour %.4f %.4f %.4f\n", screenshot.c_str(), double(m.x),
                    double(m.y), double(m.z));
      }
      glfwSwapBuffers(win.get());
    }
    const double viewer_secs = run.seconds();
    // [end]
    renderer.wait_display();
    glDeleteTextures(1, &texture);
    glDeleteVertexArrays(1, &vao);
    glDeleteProgram(program);

    // [listing kernel-alone]
    // The same launches without the window: what the display costs on top of the kernel. With
    // --frames, half of them run before the window's frames and half after, so that a change
    // in the machine's load during the run affects both rates alike.
    const int n_after = std::max(std::clamp(frame, 2, 60) / 2 * 2 - n_alone_before, 1);
    const int n_alone = n_alone_before + n_after;
    renderer.reset();
    stopwatch alone;
    for (int f = 0; f < n_after; ++f) {
      renderer.launch(std::uint32_t(spf));
      renderer.finish();
    }
    const double alone_secs = alone.seconds() + alone_before_secs;
    // [end]
    const double viewer_fps = frame / viewer_secs, kernel_fps = n_alone / alone_secs;
    std::printf("viewer: %d frames in %.2f s, %.2f frames/s (%.1f ms per frame)\n", frame,
                viewer_secs, viewer_fps, 1e3 / viewer_fps);
    std::printf("kernel alone: %d launches in %.2f s, %.2f launches/s (%.1f ms per launch)\n",
                n_alone, alone_secs, kernel_fps, 1e3 / kernel_fps);
    std::printf("viewer rate / kernel rate: %.0f %%\n", 100.0 * viewer_fps / kernel_fps);
    std::printf("summary: %d frames of %dx%d at %d spp each in a window on %s, %.1f ms per frame; "
                "%.2f s in total\n", frame, width, height, spf, ctx->device.device_name.c_str(),
                1e3 / viewer_fps, clock.seconds());
    return 0;
  });
}
#else
    ;
#endif
}  // namespace detail

// The whole `realtime` program: parses argv, renders (a window, or --headless), writes; returns
// main's exit code (0, or 1 with "error: ..." on stderr for bad input or a scene the kernel cannot
// render). `registry`: the program's own kinds for --scene files.
inline int realtime_main(int argc, char** argv, const scene_registry& registry = {}) {
  return detail::realtime_main_in(argc, argv, registry, resource_root());
}

}  // namespace zraka

// Chapter 2.1 — shaders. A "shader" here is a function of one pixel: it gets the pixel (i, j)
// and a read-only copy of the scene, and returns that pixel's colour. Nothing it computes
// depends on another pixel, so every pixel can run at once: on a GPU's many cores, or here on
// the CPU's threads through render.hpp. The thesis's example (Listing 2.1, fixed per erratum B9)
// paints a pixel black if its ray hits any object and white otherwise.
//
// The program runs a shader over the image on all threads and again on one thread, checks that
// the two images are the same bits (the shader depends on its pixel alone), and counts the
// black pixels against the area the spheres cover on the image plane.
#include <zraka/app/program_options.hpp>
#include <zraka/cameras/camera.hpp>
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/geometry/sphere.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/render.hpp>

#include <cstdio>
#include <vector>

using namespace zraka;

namespace {

const rgb black(0.0f), white(1.0f);

// [listing mask-shader]
// Listing 2.1 corrected (B9): the loop variable is initialised and is the one that indexes the
// objects, so every object is tested; white only after none was hit.
rgb mask_shader(const std::vector<sphere>& objects, const ray& r) {
  for (std::size_t k = 0; k < objects.size(); ++k) {
    hit h;
    if (intersect(objects[k], r, 0.0, infinity<double>, h)) return black;
  }
  return white;
}
// [end]

// Another shader over the same input: the normal of the nearest hit, mapped from [-1, 1] to
// [0, 1] per channel (the nearest, so a sphere in front hides the one behind).
rgb normal_shader(const std::vector<sphere>& objects, const ray& r) {
  hit nearest;
  bool found = false;
  double t_max = infinity<double>;
  for (const sphere& s : objects)
    if (intersect(s, r, 0.0, t_max, nearest)) found = true, t_max = nearest.t;
  return found ? rgb(0.5 * (nearest.normal + 1.0)) : white;
}

// --shader's names, read by parse_enum (enum_names.hpp).
enum class shader_kind { mask, normal };
constexpr enum_name<shader_kind> shader_kind_names[] = {{shader_kind::mask, "mask"}, {shader_kind::normal, "normal"}};
constexpr std::span<const enum_name<shader_kind>> enum_names(shader_kind) { return shader_kind_names; }

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 2.1: a per-pixel shader run over an image on all threads", take::size | take::threads | take::out};
  cli.width = 320, cli.height = 240, cli.out = "shaders.png";
  std::string shader = "mask";
  render_options ro;
  ro.progress = false;
  cli.app.add_option("--shader", shader, "mask (thesis Listing 2.1) or normal");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height;
  const std::string& out = cli.out;
  ro.threads = cli.threads;

  return guarded([&] {
    image::check_size(width, height);
    const shader_kind kind = parse_enum<shader_kind>(shader, "--shader");
    const int threads = resolve_threads(ro.threads);
    // The scene every pixel gets a copy of: three spheres, one partly behind another.
    const std::vector<sphere> objects = {{{-1.2, 0, -5}, 1.0}, {{1.0, 0.3, -6}, 1.3}, {{0.2, -0.6, -3.5}, 0.4}};
    camera cam_settings;
    cam_settings.vfov_degrees = 45;
    cam_settings.aspect = double(width) / height;
    const camera::prepared cam = cam_settings.prepare();

    // [listing run-shader]
    // The shader's input is the pixel (i, j); the ray through its centre is the first thing it
    // computes. render() calls it once per pixel (1 sample), from any thread, in any order.
    auto run = [&](int thread_count) {
      image img(width, height);
      render_options o = ro;
      o.threads = thread_count;
      const render_stats st = render(img, 1, 0, [&](sample_context& c) {
        const ray r = cam.generate((c.x + 0.5) / width, (c.y + 0.5) / height);
        return kind == shader_kind::mask ? mask_shader(objects, r) : normal_shader(objects, r);
      }, o);
      return std::pair{img, st};
    };
    // [end]
    const auto [img, st] = run(threads);
    const auto [img1, st1] = run(1);
    const bool same = img.pixels == img1.pixels;
    write_image(img, out);

    long long covered = 0;
    for (const rgb& p : img.pixels) covered += p != white;
    std::printf("shader '%s' ran %d x %d = %lld times: %.3f s on %d thread%s, %.3f s on 1 thread\n",
                shader.c_str(), width, height, (long long)width * height, st.seconds, threads,
                threads == 1 ? "" : "s", st1.seconds);
    std::printf("the same bits on %d threads and on 1: %s\n", threads, same ? "yes" : "NO");
    std::printf("pixels whose ray hits a sphere: %lld of %d (%.2f%%)\nwrote %s\n", covered, width * height,
                100.0 * double(covered) / (double(width) * height), out.c_str());
    std::printf("summary: %.3f s; %dx%d pixels shaded independently, %.2f%% covered, identical on 1 and %d threads: %s\n",
                st.seconds + st1.seconds, width, height, 100.0 * double(covered) / (double(width) * height), threads,
                same ? "yes" : "NO");
    return same ? 0 : 1;
  });
}

// Chapter 1.7 — reflection types. Four balls on a grey floor under a rectangular light and a dim
// sky: a mirror, "fuzzy metal" with fuzz 0.3 and 1.0 (the thesis's "diffuse reflection",
// erratum C1: the mirror direction pushed by a random offset), and a true Lambertian surface
// (cosine-weighted scattering). The image is path traced (path.hpp).
//
// Diffuse means: the same radiance towards every viewer. So the program measures, for one fixed
// point on each ball, the radiance towards two camera positions, and prints both. Only the
// Lambertian ball gives the same number twice (within its statistical error); the fuzzy balls
// do not, for any fuzz: a larger offset blurs the reflection but stays centred on the mirror
// direction.
#include <zraka/core/error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/sampling/pixel_sampling.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>

using namespace zraka;

namespace {

struct ball {
  const char* label;
  material m;
};

scene reflection_scene(int width, int height) {
  scene sc;
  const int floor_mat = sc.add_material(material::lambertian(rgb(0.5f)));
  const int lamp = sc.add_material(material::emitter(rgb(5.0f)));
  sc.add(quad{{-6, 0, 6}, {12, 0, 0}, {0, 0, -12}}, floor_mat);      // y = 0, up
  sc.add(quad{{-1.5, 3.2, -1.5}, {3, 0, 0}, {0, 0, 1.2}}, lamp);     // above and behind, down
  sc.background = rgb(0.12f, 0.16f, 0.25f);                           // a dim sky
  sc.camera.position = {0, 1.3, 5.2};
  sc.camera.look_at = {0, 0.5, 0};
  sc.camera.vfov_degrees = 30;
  sc.settings.width = width;
  sc.settings.height = height;
  return sc;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 1.7: mirror, fuzzy metal and Lambertian reflection; view dependence measured", take::image | take::depth};
  cli.width = 240, cli.height = 120, cli.spp = 32, cli.depth = 6, cli.out = "reflection.png";
  int probe_samples = 4096;
  cli.app.add_option("--probe-samples", probe_samples, "paths per measured radiance");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height, spp = cli.spp, depth = cli.depth;
  const std::uint64_t seed = cli.seed;
  const render_options opt = cli.render();
  const std::string& out = cli.out;

  return guarded([&] {
    if (probe_samples < 2) throw error("--probe-samples must be at least 2");
    scene sc = reflection_scene(width, height);
    // [listing balls]
    const rgb albedo(0.8f);
    const ball balls[] = {{"mirror (fuzz 0)", material::mirror(albedo)},
                          {"fuzzy metal 0.3", material::fuzzy_metal(albedo, 0.3)},
                          {"fuzzy metal 1.0", material::fuzzy_metal(albedo, 1.0)},
                          {"Lambertian", material::lambertian(albedo)}};
    // [end]
    for (int i = 0; i < 4; ++i) sc.add(sphere{{-1.65 + 1.1 * i, 0.5, 0}, 0.5}, sc.add_material(balls[i].m));
    path_options po;
    po.max_depth = depth;
    const path_tracer tracer(sc, po);
    stopwatch total;

    image img(width, height);
    const auto cam = sc.prepared_camera();
    const render_stats st = render(img, spp, seed, [&](sample_context& c) {
      const vec2 o = pixel_sample(pixel_pattern::stratified, c.sample, c.spp, c.random);
      return tracer(cam.generate((c.x + o.x) / width, (c.y + o.y) / height), c.random, c.rays);
    }, opt);
    write_image(img, out);
    std::printf("%s\nwrote %s\n", summary(img, spp, st).c_str(), out.c_str());

    // [listing probe]
    // The radiance leaving point x towards eye e: paths along the ray from e through x (the
    // first hit must be x itself).
    auto radiance_towards = [&](const vec3& x, const vec3& e, std::uint32_t probe) {
      const ray r(e, x - e);
      scene_hit sh;
      if (!nearest_hit(sc, r, sh) || glm::length(sh.h.p - x) > 1e-6)
        throw error("a probe point is hidden from a camera");
      estimator e_mean;
      std::uint64_t rays = 0;
      for (int s = 0; s < probe_samples; ++s) {
        rng g(seed, 1000000u + probe, std::uint32_t(s));
        e_mean.add(luminance(tracer(r, g, rays)));
      }
      return e_mean;
    };
    // [end]
    // View A looks straight down the normal at x (a mirror there shows the sky above). View B
    // looks at x from where a mirror at x shows the light's centre.
    const vec3 light_centre(0, 3.2, -0.9);
    std::printf("\nradiance (luminance) leaving one point on each ball, +- standard error, %d paths each\n",
                probe_samples);
    std::printf("point x = centre + r n, n = (0, 2, 1)/sqrt 5; view A: 3 units from x along n; view B: 3 units from\n"
                "x along the mirror direction of the light's centre (a mirror at x shows the light to B)\n");
    std::printf("%-18s %18s %18s %10s %8s\n", "ball", "towards A", "towards B", "B / A", "|B-A|/se");
    double lambert_z = 0, fuzzy_min_z = 1e300;
    for (int i = 0; i < 4; ++i) {
      const vec3 n = glm::normalize(vec3(0, 2, 1)), x = sc.spheres[std::size_t(i)].shape.center + 0.5 * n;
      const vec3 eye_a = x + 3.0 * n, eye_b = x + 3.0 * reflect(glm::normalize(x - light_centre), n);
      const estimator a = radiance_towards(x, eye_a, std::uint32_t(2 * i));
      const estimator b = radiance_towards(x, eye_b, std::uint32_t(2 * i + 1));
      const double z = std::abs(b.mean() - a.mean()) /
                       std::sqrt(a.standard_error() * a.standard_error() + b.standard_error() * b.standard_error());
      std::printf("%-18s %9.4f +-%6.4f %9.4f +-%6.4f %10.3f %8.1f\n", balls[i].label, a.mean(), a.standard_error(),
                  b.mean(), b.standard_error(), b.mean() / a.mean(), z);
      if (i == 3) lambert_z = z;
      else if (i > 0) fuzzy_min_z = std::min(fuzzy_min_z, z);
    }
    std::printf("view-dependent (|B-A| > 4 standard errors): fuzzy metal %s, Lambertian %s\n",
                fuzzy_min_z > 4 ? "yes" : "no", lambert_z > 4 ? "yes" : "no");
    std::printf("summary: %.2f s; image %dx%d at %d spp; Lambertian B/A differs by %.1f standard errors, "
                "fuzzy metal by at least %.1f; %llu NaN/inf samples\n",
                total.seconds(), width, height, spp, lambert_z, fuzzy_min_z,
                static_cast<unsigned long long>(st.nonfinite));
    return 0;
  });
}

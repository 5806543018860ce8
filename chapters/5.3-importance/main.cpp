// Chapter 5.3 — importance sampling. The light leaving a diffuse point towards the camera is
//     L_o = L_e + integral over the hemisphere of f(wi, wo) L_i(wi) cos(theta_i) dwi,
// estimated by one direction wi drawn with density p: f L_i cos / p. Any p that is positive
// where the integrand is gives the right mean; the choice of p decides the noise. Four choices
// for a Lambertian floor and ball lit by one small quad light:
//   uniform   p = 1/(2 pi) over the hemisphere (what "no importance sampling" means);
//   cosine    p = cos/pi, the BRDF's own shape (f cos / p = albedo);
//   light     directions towards a uniform point on the light (next-event estimation, C4);
//   mixture   light with probability w, else cosine, divided by the mixture density (one-sample
//             multiple importance sampling with the balance heuristic).
// Direct lighting only: one bounce, so L_i is what the first surface along wi emits. The pixel
// position is fixed at the centre, so the only error is this integral's. Every strategy is
// rendered at 1, 4, 16, 64 spp, timed, and compared with a stratified light-sampling reference
// rendered in the same run (with another seed, so its noise is independent).
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/scene/lights.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>
#include <filesystem>

using namespace zraka;

namespace {

scene lit_scene(int width, int height) {
  scene sc;
  const int floor_mat = sc.add_material(material::lambertian(rgb(0.7f)));
  const int ball_mat = sc.add_material(material::lambertian(rgb(0.75f, 0.35f, 0.2f)));
  const int lamp = sc.add_material(material::emitter(rgb(40.0f)));
  sc.add(quad{{-4, 0, 4}, {8, 0, 0}, {0, 0, -8}}, floor_mat);        // y = 0, facing up
  sc.add(sphere{{0, 0.6, 0}, 0.6}, ball_mat);
  sc.add(quad{{-0.8, 2.2, -0.4}, {0.6, 0, 0}, {0, 0, 0.6}}, lamp);   // 0.6 x 0.6, facing down
  sc.background = rgb(0);
  sc.camera.position = {0, 1.6, 4.2};
  sc.camera.look_at = {0, 0.5, 0};
  sc.camera.vfov_degrees = 40;
  sc.settings.width = width;
  sc.settings.height = height;
  return sc;
}

enum class strategy { uniform, cosine, light, mixture };
constexpr enum_name<strategy> strategy_names[] = {
    {strategy::uniform, "uniform"}, {strategy::cosine, "cosine"}, {strategy::light, "light"}, {strategy::mixture, "mixture"}};
constexpr std::span<const enum_name<strategy>> enum_names(strategy) { return strategy_names; }  // name(s): enum_names.hpp

// [listing direct]
// L_o at the first hit of camera ray r, from one direction sampled by strategy s. u_light and
// u are the sample's random numbers (stratified for the reference, plain otherwise).
rgb direct(const scene& sc, const light_set& lights, const ray& r, strategy s, double w_light,
           double u_choice, double u_light, vec2 u, std::uint64_t& rays) {
  scene_hit sh;
  ++rays;
  if (!nearest_hit(sc, r, sh)) return sc.background;
  const material& m = sc.materials[std::size_t(sh.material)];
  const rgb Le = emitted(m, sh.h);
  if (m.is<material_kinds::emitter>()) return Le;
  const vec3 n = sh.h.facing_normal(), wo = -r.direction, x = sh.h.p;

  vec3 wi;
  int sampled = -1;  // the light a light sample aimed at
  switch (s) {
    case strategy::uniform: wi = uniform_hemisphere_dist(n).sample(u); break;
    case strategy::cosine: wi = cosine_hemisphere_dist(n).sample(u); break;
    case strategy::light:
    case strategy::mixture:  // pick one technique, divide by the density of both
      if (s == strategy::light || u_choice < w_light) {
        const auto ls = lights.sample(sh.h, u_light, u);
        if (!ls) return Le;
        wi = ls->wi;
        sampled = ls->light;
      } else {
        wi = cosine_hemisphere_dist(n).sample(u);
      }
      break;
  }
  // L_i(wi): what the first surface along wi emits (black sky, no further bounces).
  scene_hit lh;
  ++rays;
  const bool found = nearest_hit(sc, spawn_ray(sh.h, wi), lh);
  if (sampled >= 0 && (!found || lights.index_of(lh.object) != sampled)) return Le;  // in the shadow
  const rgb Li = found ? emitted(sc.materials[std::size_t(lh.material)], lh.h) : sc.background;
  // The density of wi: the light sampler's is that of the light the ray finds first (lights.hpp).
  const double p_light = found ? lights.pdf(lh.object, x, wi, lh.h) : 0.0;
  double pdf = 0;
  switch (s) {
    case strategy::uniform: pdf = uniform_hemisphere_dist(n).pdf(wi); break;
    case strategy::cosine: pdf = cosine_hemisphere_dist(n).pdf(wi); break;
    case strategy::light: pdf = p_light; break;
    case strategy::mixture: pdf = w_light * p_light + (1 - w_light) * cosine_hemisphere_dist(n).pdf(wi); break;
  }
  if (!(pdf > 0)) return Le;
  return Le + brdf_cos(m, sh.h, wo, wi) * Li / float(pdf);
}
// [end]

double mean_value(const image& a) {
  double sum = 0;
  for (const rgb& p : a.pixels) sum += (double(p.x) + p.y + p.z) / 3;
  return sum / double(a.pixels.size());
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 5.3: importance sampling - uniform, cosine, light and mixture sampling of direct light", take::image};
  cli.width = 96, cli.height = 72, cli.spp = 64, cli.out = "importance.png";
  int ref_spp = 256, figure_spp = 16;
  double w_light = 0.5, target = 0.01;
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference (stratified light sampling)");
  cli.app.add_option("--mix", w_light, "mixture: probability of sampling the light");
  cli.app.add_option("--target", target, "RMSE to report the time to reach");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height, max_spp = cli.spp;
  const std::uint64_t seed = cli.seed;
  const render_options opt = cli.render();
  const std::string& out = cli.out;

  return guarded([&] {
    if (max_spp < 1 || max_spp > (1 << 16) || (max_spp & (max_spp - 1)) || (max_spp & 0xAAAAAAAA))
      throw error("--spp must be a power of 4 from 1 to 65536, got " + std::to_string(max_spp));
    if (ref_spp < 1) throw error("--ref-spp must be at least 1, got " + std::to_string(ref_spp));
    if (!(w_light > 0 && w_light < 1)) throw error("--mix must be strictly between 0 and 1");
    if (!(target > 0)) throw error("--target must be positive");
    figure_spp = std::min(figure_spp, max_spp);
    const scene sc = lit_scene(width, height);
    const light_set lights(sc);
    const auto cam = sc.prepared_camera();
    stopwatch total;
    std::uint64_t bad = 0;

    auto camera_ray = [&](const sample_context& c) {  // through the pixel centre: no anti-aliasing
      return cam.generate((c.x + 0.5) / width, (c.y + 0.5) / height);
    };

    // The reference: light sampling with the sample's (u, u_light) stratified over the pixel's
    // samples, and a seed of its own.
    image reference(width, height);
    const render_stats rs = render(reference, ref_spp, seed ^ 0x5eed5eed5eedull, [&](sample_context& c) {
      const vec2 u = pixel_sample(pixel_pattern::stratified, c.sample, c.spp, c.random);
      return direct(sc, lights, camera_ray(c), strategy::light, w_light, 0.0, c.random.uniform(), u, c.rays);
    }, opt);
    bad += rs.nonfinite;
    std::printf("reference: %d spp, stratified light sampling, %.2f s, mean value %.5f\n", ref_spp, rs.seconds,
                mean_value(reference));

    const strategy strategies[] = {strategy::uniform, strategy::cosine, strategy::light, strategy::mixture};
    std::vector<convergence_log> logs;
    std::vector<image> figure_images;
    std::vector<double> final_mean;
    for (strategy s : strategies) {
      logs.emplace_back(std::string("direct light, ") + name(s) + " sampling", std::vector<std::string>{"rmse"},
                        "rmse", "spp");
      for (int spp = 1; spp <= max_spp; spp *= 4) {
        image img(width, height);
        // [listing estimate]
        const render_stats st = render(img, spp, seed, [&](sample_context& c) {
          const double u_choice = c.random.uniform(), u_light = c.random.uniform();
          return direct(sc, lights, camera_ray(c), s, w_light, u_choice, u_light, c.random.uniform2(), c.rays);
        }, opt);
        // [end]
        bad += st.nonfinite;
        logs.back().add(std::uint64_t(spp), st.seconds, {rmse(img, reference)});
        if (spp == figure_spp) figure_images.push_back(img);
        if (spp == max_spp) final_mean.push_back(mean_value(img));
      }
    }

    std::printf("\nRMSE against the reference (seconds in brackets)\n%6s", "spp");
    for (strategy s : strategies) std::printf(" %21s", name(s));
    std::printf("\n");
    for (std::size_t row = 0; row < logs[0].rows().size(); ++row) {
      std::printf("%6llu", static_cast<unsigned long long>(logs[0].rows()[row].n));
      for (const auto& log : logs)
        std::printf("     %.5f [%6.3f s]", log.rows()[row].values[0], log.rows()[row].seconds);
      std::printf("\n");
    }
    std::printf("mean value at %d spp:", max_spp);
    for (std::size_t i = 0; i < 4; ++i) std::printf(" %s %.5f", name(strategies[i]), final_mean[i]);
    std::printf(" (reference %.5f)\n", mean_value(reference));

    // [listing efficiency]
    // Unbiased estimators: MSE ~ c / spp and time ~ spp, so MSE x seconds = c is the cost of the
    // strategy. From the largest run: RMSE in T seconds = sqrt(c / T); seconds to RMSE e = c / e^2.
    std::vector<double> cost;
    for (const auto& log : logs) {
      const auto& r = log.rows().back();
      cost.push_back(r.values[0] * r.values[0] * std::max(r.seconds, 1e-6));
    }
    // [end]
    const double T = 1.0;
    std::printf("\nequal time (%.0f s) and time to RMSE %.3g, from MSE x seconds at %d spp:\n", T, target, max_spp);
    std::size_t best = 0;
    for (std::size_t i = 0; i < 4; ++i) {
      if (cost[i] < cost[best]) best = i;
      std::printf("  %-8s RMSE in %.0f s: %.5f   seconds to RMSE %.3g: %10.3f   %s\n", name(strategies[i]), T,
                  std::sqrt(cost[i] / T), target, cost[i] / (target * target), logs[i].slope_line().c_str());
    }
    std::size_t second = best == 0 ? 1 : 0;
    for (std::size_t i = 0; i < 4; ++i)
      if (i != best && cost[i] < cost[second]) second = i;

    // Figure: the four strategies side by side at the same spp.
    const int gap = 4;
    image fig(4 * width + 3 * gap, height, rgb(1));
    for (int i = 0; i < static_cast<int>(figure_images.size()); ++i)
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) fig.at(i * (width + gap) + x, y) = figure_images[i].at(x, y);
    write_image(fig, out);
    write_image(reference, cli.sibling("-reference"));
    for (std::size_t i = 0; i < 4; ++i) logs[i].write_csv(cli.sibling("-" + std::string(name(strategies[i])), ".csv"));
    std::printf("wrote %s (uniform, cosine, light, mixture at %d spp), %s, %s, ...\n",
                out.c_str(), figure_spp, cli.sibling("-reference").c_str(),
                cli.sibling("-" + std::string(name(strategies[0])), ".csv").c_str());

    std::printf("winner: %s sampling: in equal time its RMSE is %.1fx lower than %s (next best) and %.1fx lower "
                "than uniform; it reaches RMSE %.3g %.1fx sooner than %s\n",
                name(strategies[best]), std::sqrt(cost[second] / cost[best]), name(strategies[second]),
                std::sqrt(cost[0] / cost[best]), target, cost[second] / cost[best], name(strategies[second]));
    std::printf("summary: %.2f s; RMSE at %d spp: uniform %.5f, cosine %.5f, light %.5f, mixture %.5f; "
                "%llu NaN/inf samples\n",
                total.seconds(), max_spp, logs[0].rows().back().values[0], logs[1].rows().back().values[0],
                logs[2].rows().back().values[0], logs[3].rows().back().values[0],
                static_cast<unsigned long long>(bad));
    return 0;
  });
}

// Chapter 5.1 — anti-aliasing. A pixel's colour is the average of the scene over the pixel's
// square, an integral; one ray through the centre is a one-point estimate of it, and edges
// come out jagged. Here the scene is unlit (each surface shows its own colour: a black/white
// checkered floor, a white ball, a grey sky), so the only error is this pixel integral. We
// render it with 1, 4, 16 and 64 samples per pixel placed three ways (regular grid, uniform
// random, stratified = one random point per grid cell), measure the RMSE against a reference
// with many stratified samples rendered in the same run, and time each image. A fourth column
// places the samples by a sampler's first pair of coordinates (--sampler, samplers.hpp; sobol by
// default): the low-discrepancy points of the page's last section.
// Writes <out>.png (crops for the book), <out>-reference.png and <out>-<pattern>.csv.
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/scene.hpp>
#include <zraka/scene/scene_query.hpp>

#include <zraka/app/program_options.hpp>

#include <cstdio>
#include <filesystem>

using namespace zraka;

namespace {

// A floor of 0.5-unit checks, black and white, and a white ball, under a pinhole camera.
scene edge_scene(int width, int height) {
  scene sc;
  const int checks = sc.add_material(material::lambertian(texture::checker(rgb(1), rgb(0), 0.5)));
  const int white = sc.add_material(material::lambertian(rgb(1)));
  sc.add(quad{{-40, 0, 40}, {80, 0, 0}, {0, 0, -80}}, checks);  // y = 0, normal +y
  sc.add(sphere{{0.3, 0.7, -0.4}, 0.7}, white);
  sc.background = rgb(0.25f);
  sc.camera.position = {1.6, 1.4, 4.5};
  sc.camera.look_at = {0, 0.5, 0};
  sc.camera.vfov_degrees = 35;
  sc.settings.width = width;
  sc.settings.height = height;
  return sc;
}

// [listing shade-unlit]
// What a camera ray sees: the colour of the nearest surface, no lighting, no randomness.
rgb unlit(const scene& sc, const ray& r) {
  scene_hit sh;
  if (!nearest_hit(sc, r, sh)) return sc.background;
  return evaluate(sc.materials[sh.material].get<material_kinds::lambertian>()->albedo, sh.h.p, sh.h.facing_normal(), sh.h.uv);
}
// [end]

// Copies a size x size crop at (x0, y0), magnified `zoom` times, into `out` at (ox, oy).
void paste_crop(const image& src, int x0, int y0, int size, int zoom, image& out, int ox, int oy) {
  for (int y = 0; y < size * zoom; ++y)
    for (int x = 0; x < size * zoom; ++x)
      out.at(ox + x, oy + y) = src.at(std::min(src.width - 1, x0 + x / zoom), std::min(src.height - 1, y0 + y / zoom));
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 5.1: anti-aliasing - RMSE of regular, uniform and stratified pixel sampling", take::image | take::sampler};
  cli.width = 160, cli.height = 120, cli.spp = 64, cli.out = "antialiasing.png", cli.sampler = "sobol";
  int ref_spp = 512;
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the stratified reference");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int width = cli.width, height = cli.height, max_spp = cli.spp;
  const std::uint64_t seed = cli.seed;
  const render_options opt = cli.render();
  const std::string& out = cli.out;

  return guarded([&] {
    if (max_spp < 1 || max_spp > (1 << 16) || (max_spp & (max_spp - 1)) || (max_spp & 0xAAAAAAAA))
      throw error("--spp must be a power of 4 from 1 to 65536, got " + std::to_string(max_spp));
    if (ref_spp < max_spp) throw error("--ref-spp must be at least --spp (" + std::to_string(max_spp) + ")");
    const scene sc = edge_scene(width, height);
    const auto cam = sc.prepared_camera();
    stopwatch total;

    // [listing pixel-integral]
    // One sample: a position inside pixel (x, y) by the chosen pattern, one ray through it.
    auto render_with = [&](pixel_pattern pattern, int spp, image& img) {
      return render(img, spp, seed, [&](sample_context& c) {
        const vec2 o = pixel_sample(pattern, c.sample, c.spp, c.random);
        c.rays += 1;
        return unlit(sc, cam.generate((c.x + o.x) / width, (c.y + o.y) / height));
      }, opt);
    };
    // [end]

    // [listing pixel-sampler]
    // The same integral with the positions of a sampler's first pair of coordinates.
    const sampler_kind sampler = cli.sampler_choice();
    auto render_sampler = [&](int spp, image& img) {
      return render(img, spp, seed, [&](sample_context& c) {
        sample_point point(sampler, seed, std::uint32_t(c.y * width + c.x), std::uint32_t(c.sample),
                           std::uint32_t(c.spp));
        point.drive(c.random);
        const vec2 o = c.random.uniform2();
        c.rays += 1;
        return unlit(sc, cam.generate((c.x + o.x) / width, (c.y + o.y) / height));
      }, opt);
    };
    // [end]

    image reference(width, height);
    const render_stats ref_stats = render_with(pixel_pattern::stratified, ref_spp, reference);
    std::printf("reference: %d spp stratified, %.2f s\n", ref_spp, ref_stats.seconds);
    std::printf("%s\n", summary(reference, ref_spp, ref_stats).c_str());

    const pixel_pattern patterns[] = {pixel_pattern::regular, pixel_pattern::uniform, pixel_pattern::stratified};
    std::vector<convergence_log> logs;
    std::vector<image> crops[3];
    std::uint64_t bad = ref_stats.nonfinite;
    for (int p = 0; p < 3; ++p) {
      logs.emplace_back(std::string("pixel sampling: ") + name(patterns[p]), std::vector<std::string>{"rmse"},
                        "rmse", "spp");
      for (int spp = 1; spp <= max_spp; spp *= 4) {
        image img(width, height);
        const render_stats s = render_with(patterns[p], spp, img);
        bad += s.nonfinite;
        logs.back().add(std::uint64_t(spp), s.seconds, {rmse(img, reference)});
        crops[p].push_back(std::move(img));
      }
    }
    logs.emplace_back(std::string("sampler: ") + name(sampler), std::vector<std::string>{"rmse"}, "rmse", "spp");
    for (int spp = 1; spp <= max_spp; spp *= 4) {
      image img(width, height);
      const render_stats s = render_sampler(spp, img);
      bad += s.nonfinite;
      logs.back().add(std::uint64_t(spp), s.seconds, {rmse(img, reference)});
    }

    std::printf("\nRMSE against the reference (linear units; seconds in brackets)\n%6s", "spp");
    for (auto p : patterns) std::printf(" %22s", name(p));
    std::printf(" %22s\n", (std::string("sampler ") + name(sampler)).c_str());
    for (std::size_t row = 0; row < logs[0].rows().size(); ++row) {
      std::printf("%6llu", static_cast<unsigned long long>(logs[0].rows()[row].n));
      for (const auto& log : logs)
        std::printf("      %.5f [%6.3f s]", log.rows()[row].values[0], log.rows()[row].seconds);
      std::printf("\n");
    }
    for (int p = 0; p < 3; ++p) std::printf("%-10s %s\n", name(patterns[p]), logs[p].slope_line().c_str());
    std::printf("%-10s %s\n", name(sampler), logs[3].slope_line().c_str());
    const loglog_fit strat = logs[2].fit();
    if (!std::isnan(strat.slope))
      std::printf("the reference's own RMSE, extrapolating the stratified fit to %d spp: about %.5f\n", ref_spp,
                  std::exp(strat.intercept + strat.slope * std::log(double(ref_spp))));

    // The book's figure: the same crop at 1, 4, 16, 64 spp; regular above, stratified below.
    const int crop = std::max(8, std::min(48, std::min(width, height) / 3)), zoom = 2, gap = 4;
    const int cx = std::min(width - crop, width * 34 / 100), cy = std::min(height - crop, height * 42 / 100);
    const int columns = static_cast<int>(crops[0].size());
    image fig(columns * crop * zoom + (columns - 1) * gap, 2 * crop * zoom + gap, rgb(1));
    for (int c = 0; c < columns; ++c) {
      paste_crop(crops[0][c], cx, cy, crop, zoom, fig, c * (crop * zoom + gap), 0);
      paste_crop(crops[2][c], cx, cy, crop, zoom, fig, c * (crop * zoom + gap), crop * zoom + gap);
    }
    write_image(fig, out);
    write_image(reference, cli.sibling("-reference"));
    for (int p = 0; p < 3; ++p) logs[p].write_csv(cli.sibling(std::string("-").append(name(patterns[p])), ".csv"));
    logs[3].write_csv(cli.sibling(std::string("-sampler-").append(name(sampler)), ".csv"));
    std::printf("wrote %s (crop at %d,%d, %dx%d px, x%d; top regular, bottom stratified), %s, "
                "%s, ...\n",
                out.c_str(), cx, cy, crop, crop, zoom, cli.sibling("-reference").c_str(),
                cli.sibling("-" + std::string(name(patterns[0])), ".csv").c_str());
    const auto& last = [&](int p) { return logs[p].rows().back().values[0]; };
    std::printf("summary: %.2f s; RMSE at %d spp: regular %.5f, uniform %.5f, stratified %.5f; %llu NaN/inf samples\n",
                total.seconds(), max_spp, last(0), last(1), last(2), static_cast<unsigned long long>(bad));
    std::printf("sampler %s: RMSE at %d spp %.5f\n", name(sampler), max_spp, last(3));
    return 0;
  });
}

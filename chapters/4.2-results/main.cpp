// Chapter 4.2 — results. The thesis's two path-tracing figures, redone with numbers:
//   Figure 4.3, samples per pixel at a fixed depth: the Cornell box with a glass ball rendered
//     by the naive path tracer (top row) and by mis (bottom row) at each --spp-sweep count, each
//     tile's RMSE against a reference printed beside it;
//   Figure 4.4, depth at a fixed sample count: the Cornell box with a mirror and a glass ball at
//     the thesis's depths n = 1..4 (rays per path; n - 1 bounces): lights only, first
//     reflections, reflections inside the mirror, light through the glass;
// and the error against run time of naive, nee and mis on the first scene (CSV files for
// tools/plot_convergence.py), with the time each takes to reach naive's final error.
// Every pixel is sampled at its centre (no anti-aliasing): the error against the reference is
// then the light transport's alone. With jittered pixels the edges of the directly seen light
// (radiance 17 next to 0.5) would add a noise no integrator can remove, the same for all three.
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/scene/cornell.hpp>

#include <zraka/app/cli.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <vector>

using namespace zraka;

namespace {

// Tiles side by side in rows, with a gap of `gap` black pixels.
image montage(const std::vector<std::vector<image>>& rows, int gap = 2) {
  const int tw = rows.at(0).at(0).width, th = rows[0][0].height;
  const int cols = int(rows[0].size());
  image out(cols * tw + (cols - 1) * gap, int(rows.size()) * th + (int(rows.size()) - 1) * gap);
  for (std::size_t r = 0; r < rows.size(); ++r)
    for (std::size_t c = 0; c < rows[r].size(); ++c)
      for (int y = 0; y < th; ++y)
        for (int x = 0; x < tw; ++x)
          out.at(int(c) * (tw + gap) + x, int(r) * (th + gap) + y) = rows[r][c].at(x, y);
  return out;
}

struct renderer {
  scene sc;
  int size;
  render_options ro;
  std::uint64_t seed;

  image draw(integrator m, int depth, int spp, std::uint64_t s, render_stats* stats = nullptr) const {
    path_options o;
    o.method = m;
    o.max_depth = depth;
    const path_tracer t(sc, o);
    const auto cam = sc.prepared_camera();
    image img(size, size);
    const render_stats st = render(img, spp, s, [&](sample_context& c) {
      return t(cam.generate((c.x + 0.5) / size, (c.y + 0.5) / size), c.random, c.rays);  // centre
    }, ro);
    if (stats) *stats = st;
    return img;
  }
};

renderer make(cornell_variant v, int size, const render_options& ro, std::uint64_t seed) {
  renderer r{cornell_box<double>(v), size, ro, seed};
  r.sc.settings.width = r.sc.settings.height = size;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Chapter 4.2: the thesis's Figures 4.3 and 4.4 with numbers, and error against run time", take::depth | take::seed | take::threads};
  cli.depth = 8, cli.min_depth = 0, cli.max_depth = 1000;
  int tile = 40, depth_spp = 16, conv_spp = 32, ref_spp = 128;
  std::string out_dir = output_dir();
  std::vector<int> sweep{1, 4, 16};
  render_options ro;
  ro.progress = false;
  cli.app.add_option("--tile", tile, "side of each square image in pixels");
  cli.app.add_option("--spp-sweep", sweep, "Figure 4.3: samples per pixel of each column")->delimiter(',');
  cli.app.add_option("--depth-spp", depth_spp, "Figure 4.4: samples per pixel");
  cli.app.add_option("--conv-spp", conv_spp, "error against run time: samples per pixel of the last pass");
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the reference (mis, seed + 1000)");
  cli.app.add_option("--out-dir", out_dir, "folder for 4.2-samples.png, 4.2-depth.png and 4.2-<method>.csv (from inside the checkout: build/out)");
  if (const auto done = cli.parse(argc, argv)) return *done;
  const int depth = cli.depth;
  const std::uint64_t seed = cli.seed;
  ro.threads = cli.threads;

  return guarded([&] {
    const stopwatch clock;
    image::check_size(tile, tile);
    for (int n : sweep)
      if (n < 1 || n > 65536) throw error("--spp-sweep counts must be in 1..65536, got " + std::to_string(n));
    if (sweep.empty() || sweep.size() > 8) throw error("--spp-sweep needs 1 to 8 counts");
    if (depth_spp < 1 || conv_spp < 1 || ref_spp < 1) throw error("sample counts must be at least 1");
    if (!std::filesystem::is_directory(out_dir)) throw error("--out-dir " + out_dir + " is not a folder");
    const std::filesystem::path dir(out_dir);

    // The reference for the glass scene: mis with many samples and a seed of its own, so its
    // noise is independent of the images measured against it.
    const renderer glass = make(cornell_variant::glass, tile, ro, seed);
    render_stats rs;
    const image ref = glass.draw(integrator::mis, depth, ref_spp, seed + 1000, &rs);
    std::printf("reference: Cornell box with a glass ball, %dx%d, mis, %d spp, %.2f s\n", tile, tile, ref_spp,
                rs.seconds);

    // [listing figure-4-3]
    std::printf("\nFigure 4.3: samples per pixel at %d bounces (RMSE against the reference)\n%8s %12s %12s\n", depth,
                "spp", "naive", "mis");
    std::vector<std::vector<image>> rows(2);
    for (int n : sweep) {
      rows[0].push_back(glass.draw(integrator::naive, depth, n, seed));
      rows[1].push_back(glass.draw(integrator::mis, depth, n, seed));
      std::printf("%8d %12.5f %12.5f\n", n, rmse(rows[0].back(), ref), rmse(rows[1].back(), ref));
    }
    write_png(montage(rows), dir / "4.2-samples.png");
    // [end]

    // [listing figure-4-4]
    std::printf("\nFigure 4.4: depth n (rays per path = bounces + 1), mis, %d spp\n%8s %8s %12s\n", depth_spp, "n",
                "bounces", "mean");
    const renderer spheres = make(cornell_variant::spheres, tile, ro, seed);
    std::vector<std::vector<image>> depth_row(1);
    double last_mean = -1;
    bool grows = true;
    for (int n = 1; n <= 4; ++n) {
      depth_row[0].push_back(spheres.draw(integrator::mis, n - 1, depth_spp, seed));
      const vec3 m = channel_mean(depth_row[0].back());
      const double mean = (m.x + m.y + m.z) / 3;
      grows = grows && mean > last_mean;  // every extra bounce adds light, never removes it
      last_mean = mean;
      std::printf("%8d %8d %12.5f\n", n, n - 1, mean);
    }
    write_png(montage(depth_row), dir / "4.2-depth.png");
    std::printf("the mean grows with every bounce: %s\n", grows ? "yes" : "NO");
    // [end]

    // [listing error-time]
    std::printf("\nerror against run time, %d bounces, up to %d spp\n", depth, conv_spp);
    double target = 0, naive_seconds = 0;
    for (integrator m : {integrator::naive, integrator::nee, integrator::mis}) {
      path_options o;
      o.method = m;
      o.max_depth = depth;
      const path_tracer t(glass.sc, o);
      const auto cam = glass.sc.prepared_camera();
      progressive_options po;
      po.max_spp = conv_spp;
      po.seed = seed;
      po.render = ro;
      convergence_log log(std::string(name(m)), {"rmse", "relmse"}, "rmse", "spp");
      render_progressive(tile, tile, po, [&](sample_context& c) {
        return t(cam.generate((c.x + 0.5) / tile, (c.y + 0.5) / tile), c.random, c.rays);
      }, [&](const image& mean, const progressive_totals& tot) {
        log.add(std::uint64_t(tot.spp), tot.seconds, {rmse(mean, ref), relmse(mean, ref)});
      });
      std::printf("%s%s\n", log.table().c_str(), log.slope_line().c_str());
      log.write_csv(dir / ("4.2-" + std::string(name(m)) + ".csv"));
      if (m == integrator::naive) target = log.rows().back().values[0], naive_seconds = log.rows().back().seconds;
      const double secs = m == integrator::naive ? naive_seconds : seconds_to_reach(log, target);
      std::printf("%s reaches naive's final RMSE %.5f in %.3f s (%.1fx naive's time)\n\n", name(m), target, secs,
                  secs / naive_seconds);
    }
    // [end]
    std::printf("wrote 4.2-samples.png, 4.2-depth.png, 4.2-naive.csv, 4.2-nee.csv, 4.2-mis.csv in %s\n",
                out_dir.c_str());
    std::printf("summary: %dx%d tiles, Figure 4.3 (%zu sample counts), Figure 4.4 (depths 1-4), error against "
                "time of 3 integrators in %.1f s\n", tile, tile, sweep.size(), clock.seconds());
    return 0;
  });
}

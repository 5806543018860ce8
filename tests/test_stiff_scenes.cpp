// links: yaml-cpp
// The stiff scenes (scenes/caustic-box, ajar-door, tiny-light, smallpt-walls; book 6.2): each
// loads, and the path tracer and BDPT render it with no NaN/inf sample; smallpt's walls, spheres
// of radius 1e5, give the same image in float as in double (region means within 5 standard
// errors of independent batches) and not a black one.
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/estimator.hpp>
#include <zraka/scene/scene_precision.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <string>

using namespace zraka;

namespace {

template <class T> image render_mis(const scene_t<T>& sc, int spp, std::uint64_t seed, std::uint64_t& bad) {
  path_options po;
  const path_tracer_t<T> pt(sc, po);
  const auto cam = sc.prepared_camera();
  image img(sc.settings.width, sc.settings.height);
  render_options ro;
  ro.progress = false;
  ro.threads = 2;
  const int W = img.width, H = img.height;
  bad += render(img, spp, seed, [&](sample_context& c) {
    const vec2 u = c.random.uniform2();
    return pt(cam.generate(T((c.x + u.x) / W), T((c.y + u.y) / H)), c.random, c.rays);
  }, ro).nonfinite;
  return img;
}

}  // namespace

TEST_CASE("stiff scenes: each loads and renders with mis and bdpt, no NaN/inf sample") {
  for (const char* name : {"caustic-box", "ajar-door", "tiny-light", "smallpt-walls"}) {
    INFO(name);
    scene sc = load_scene_argument(name).sc;
    sc.settings.width = 12, sc.settings.height = 9;
    sc.build_acceleration();
    std::uint64_t bad = 0;
    const image m = render_mis(sc, 16, 1, bad);
    bdpt_options o;
    o.threads = 2;
    const auto b = render_bdpt(sc, 8, 1, o);
    CHECK(bad == 0);
    CHECK(b.stats.nonfinite == 0);
    CHECK(m.count_nonfinite() == 0);
    CHECK(b.img.count_nonfinite() == 0);
    double mean_m = 0, mean_b = 0;
    for (std::size_t i = 0; i < m.pixels.size(); ++i) mean_m += max_component(m.pixels[i]), mean_b += max_component(b.img.pixels[i]);
    CHECK(mean_m > 0);  // lit
    CHECK(mean_b > 0);
  }
}

TEST_CASE("smallpt-walls: float and double give the same image") {
  scene sd = load_scene_argument("smallpt-walls").sc;
  sd.settings.width = 16, sd.settings.height = 12;
  sd.build_acceleration();
  const scene_t<float> sf = scene_in<float>(sd);
  constexpr int R = 2;  // 2 x 2 regions, 3 channels
  std::vector<estimator_t<double>> ed(R * R * 3), ef(R * R * 3);
  std::uint64_t bad_d = 0, bad_f = 0;
  auto add = [&](const image& img, std::vector<estimator_t<double>>& e) {
    std::vector<double> m(R * R * 3, 0.0);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < 3; ++c) m[std::size_t(((y * R / img.height) * R + x * R / img.width) * 3 + c)] += img.at(x, y)[c];
    for (std::size_t i = 0; i < m.size(); ++i) e[i].add(m[i] / (img.width * img.height / (R * R)));
  };
  for (int b = 0; b < 10; ++b) {
    add(render_mis(sd, 48, std::uint64_t(10 + b), bad_d), ed);
    add(render_mis(sf, 48, std::uint64_t(100 + b), bad_f), ef);
  }
  CHECK(bad_d == 0);
  CHECK(bad_f == 0);
  for (std::size_t i = 0; i < ed.size(); ++i) {
    INFO("region " << i / 3 << " channel " << i % 3 << ": double " << ed[i].mean() << " +- " << ed[i].standard_error()
                   << ", float " << ef[i].mean() << " +- " << ef[i].standard_error());
    CHECK(ed[i].mean() > 0.05);  // the walls are lit: not black, not holes
    CHECK(std::abs(ed[i].mean() - ef[i].mean()) < 5 * std::hypot(ed[i].standard_error(), ef[i].standard_error()));
  }
}

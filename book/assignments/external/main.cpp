// An outside project's assignment program: checks its own shape (a disk) with zraka's
// instructor checks and renders it. Usage: disk [out.png]. Exit code 0 only if every check
// passes and the image is written.
#include "disk.hpp"

#include <zraka/camera.hpp>
#include <zraka/error.hpp>
#include <zraka/image_io.hpp>
#include <zraka/sampling.hpp>
#include <zraka/testing.hpp>

#include <cstdio>

int main(int argc, char** argv) {
  return zraka::guarded([&] {
    using namespace zraka;
    namespace zt = zraka::testing;
    const std::string out = argc > 1 ? argv[1] : "disk.png";

    // 1. The spawn rule keeps rays off the disk at every scale (testing.hpp).
    std::vector<zt::result> checks;
    for (const double s : {1e-3, 1.0, 1e3}) {
      const mycourse::disk_t<double> d{vec3(2, -1, 3) * s, glm::normalize(vec3(1, 2, 2)), 0.5 * s};
      const onb frame(d.normal);
      auto isect = [&](const ray& r, double t0, double t1, hit& h) { return mycourse::intersect(d, r, t0, t1, h); };
      auto aim = [&](rng& g) {
        const vec2 q = sample_disk_concentric(g.uniform2()) * (0.9 * d.radius);
        const vec3 target = d.center + q.x * frame.t + q.y * frame.b;
        vec3 from = d.center + 3 * d.radius * sample_uniform_sphere(g.uniform2());
        return ray(from, target - from);
      };
      checks.push_back(zt::no_self_hits<double>(isect, aim, 500));
    }
    const zt::result acne = zt::all_of(checks);
    std::printf("%s\n", acne.message.c_str());

    // 2. A picture: the disk, tilted, coloured by its (u, v), white where the rays miss.
    const int width = 120, height = 90;
    const mycourse::disk_t<double> d{vec3(0), glm::normalize(vec3(0, 1, 0.6)), 1.0};
    camera settings;
    settings.position = {0, 0.5, 3};
    settings.look_at = {0, 0, 0};
    settings.aspect = double(width) / height;
    const auto cam = settings.prepare();
    image img(width, height, rgb(1.0f));
    long hits = 0;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        hit h;
        if (mycourse::intersect(d, cam.generate((x + 0.5) / width, (y + 0.5) / height), 0.0, infinity<double>, h)) {
          ++hits;
          img.at(x, y) = rgb(float(h.uv.x), float(h.uv.y), 0.6f);
        }
      }
    write_png(img, out);
    std::printf("wrote %s (%dx%d), %ld pixels on the disk\n", out.c_str(), width, height, hits);
    std::printf("summary: external assignment %s\n", acne.ok && hits > 0 ? "passed" : "FAILED");
    return acne.ok && hits > 0 ? 0 : 1;
  });
}

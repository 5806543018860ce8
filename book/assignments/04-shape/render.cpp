// Assignment 04: the student's ring as an area light (facing down) over a floor with a ball,
// and a second ring standing on the floor, path-traced with MIS, as a PNG (the target image is
// this program built against solution/: `assignment-04-shape-render --out target.png`).
#include "ring.hpp"

#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/render.hpp>
#include <zraka/scene/scene.hpp>

#include <cstdio>
#include <memory>

int main(int argc, char** argv) {
  using namespace zraka;
  int width = 160, height = 120, spp = 64;
  std::uint64_t seed = 1;
  std::string out = "ring.png";
  zraka::cli_app app{"Assignment 04: the student's ring as an area light and as an object, path-traced, as a PNG"};
  app.add_option("--width", width, "image width in pixels");
  app.add_option("--height", height, "image height in pixels");
  app.add_option("--spp", spp, "samples per pixel");
  app.add_option("--seed", seed, "random seed");
  app.add_option("--out", out, "output file (.png, .ppm or .pfm)");
  if (const auto done = parse_command_line(app, argc, argv)) return *done;
  return guarded([&] {
    const stopwatch clock;
    image::check_size(width, height);
    scene sc;
    const int floor = sc.add_material(material::lambertian(texture::checker(rgb(0.7f), rgb(0.3f), 0.5)));
    const int red = sc.add_material(material::lambertian(rgb(0.7f, 0.15f, 0.1f)));
    const int lamp = sc.add_material(material::emitter(rgb(10.0f)));
    sc.add(plane::from_point_normal(vec3(0), vec3(0, 1, 0)), floor);
    sc.add(std::make_shared<const course::ring_t<double>>(vec3(0, 2.5, 0), vec3(0, -1, 0), 0.4, 0.9), lamp);
    sc.add(std::make_shared<const course::ring_t<double>>(vec3(0.3, 0.8, -0.8), glm::normalize(vec3(0.3, 0.1, 1)),
                                                           0.35, 0.8),
           red);
    sc.add(sphere{vec3(-1.1, 0.45, 0.3), 0.45}, red);
    sc.camera.position = {0, 1.4, 4};
    sc.camera.look_at = {0, 0.7, 0};
    sc.settings.width = width;
    sc.settings.height = height;
    sc.build_acceleration();
    path_options o;
    o.method = integrator::mis;
    const path_tracer tracer(sc, o);
    const auto cam = sc.prepared_camera();
    image img(width, height);
    const render_stats st = render(img, spp, seed, [&](sample_context& c) {
      const vec2 u = c.random.uniform2();
      return tracer(cam.generate((c.x + u.x) / width, (c.y + u.y) / height), c.random, c.rays);
    });
    write_image(img, out);
    std::printf("wrote %s (%dx%d, %d spp); %s\n", out.c_str(), width, height, spp, tracer.lights.describe().c_str());
    std::printf("summary: %.3f s, %llu rays\n", clock.seconds(), (unsigned long long)st.rays);
    return 0;
  });
}

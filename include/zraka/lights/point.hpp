#pragma once
// The point light (book 2.2, 2.3): radiant intensity I in every direction from one point, so
// the irradiance at distance d, facing it, is I / d^2. A ray never hits it: it is found only by
// sampling it (a delta). Every light kind that is not a shape is a file of this form; light.hpp
// lists the kinds, builtin.hpp registers them by name (README.md, "Adding a light").
#include <zraka/core/hit.hpp>
#include <zraka/core/vec.hpp>
#include <zraka/image/image.hpp>  // rgb
#include <zraka/lights/kernel_light.hpp>
#include <zraka/lights/light_sample.hpp>
#include <zraka/sampling/sampling.hpp>

#include <optional>
#include <string>
#include <vector>

namespace zraka::light_kinds {

struct point {
  static constexpr const char* name = "point";  // in scene files and messages
  static constexpr int kernel_kind = 3;         // gpu_light_point (gpu_scene.hpp, pathtrace.cl)
  vec3 position{0};
  rgb intensity{20.0f};

  // The light at hit h: one direction, a delta (pdf 1), Le = I / d^2.
  template <class T> std::optional<light_sample_t<T>> sample(const hit_t<T>& h) const {
    return sample_light_at_point(vec3_t<T>(position), intensity, h);
  }
  // Emitted flux, the mean over the channels: lights are chosen in proportion to it.
  double power() const {
    return 4.0 * pi<double> * ((double(intensity.x) + double(intensity.y) + double(intensity.z)) / 3.0);
  }
  // Emission sampling: a delta in position, uniform over the sphere of directions (the caller
  // sets pdf_position, the choice of the light).
  template <class T> emission_sample_t<T> sample_emission(const vec2_t<T>& u_dir) const {
    emission_sample_t<T> e;
    e.point = vec3_t<T>(position);
    e.direction = sample_uniform_sphere(u_dir);
    e.Le = intensity;
    e.pdf_direction = uniform_sphere_pdf<T>();
    e.delta_position = true;
    return e;
  }
  template <class T> T pdf_emission_direction(const vec3_t<T>&) const { return uniform_sphere_pdf<T>(); }
  template <class T> rgb intensity_towards(const vec3_t<T>&) const { return intensity; }

  // Scene file: {type: point, position: [x, y, z], intensity: colour} (scenes/README.md).
  // Node is the scene file's scene_node (io/scene_file.hpp), Writer the --export writer.
  static std::vector<std::string> keys() { return {"position", "intensity"}; }
  template <class Node> static point read(const Node& n) {
    point p;
    p.position = n.point("position");
    p.intensity = n.colour("intensity", p.intensity);
    return p;
  }
  template <class Writer> void write(Writer& w) const {
    w.point("position", position);
    w.colour("intensity", intensity);
  }
  // The OpenCL kernel renders it (pathtrace.cl, HAS_POINT_LIGHTS).
  void pack(kernel_light& k) const {
    k.kind = kernel_kind;
    for (int i = 0; i < 3; ++i) k.position[i] = float(position[i]), k.intensity[i] = intensity[i];
  }
};

}  // namespace zraka::light_kinds

namespace zraka {
// The name programs and tests have used since book 2.2: point_light_t<double>{position, I}.
template <class T> using point_light_t = light_kinds::point;
}  // namespace zraka

#pragma once
// The ray sets of chapter 5.2, shared with bench/bvh_embree.cpp so that both measure the same
// rays: camera rays (coherent: neighbours take nearly the same path through the tree),
// incoherent rays (random origins in and around the model, uniformly random directions, like
// the bounces of a path tracer) and incoherent rays from a bounding sphere through the box.
#include <zraka/cameras/camera.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/aabb.hpp>
#include <zraka/geometry/mesh.hpp>

#include <cstdint>
#include <vector>

namespace chapter_5_2 {

using namespace zraka;

// A camera that frames the (z-up) model, seen from the front, above and right.
inline camera::prepared framing_camera(const aabb& box, int width, int height) {
  const vec3 c = box.center();
  const double radius = 0.5 * glm::length(box.extent());
  camera cam;
  cam.vfov_degrees = 30;
  cam.aspect = double(width) / height;
  cam.up = {0, 0, 1};
  cam.look_at = c;
  cam.position = c + 0.8 * radius / std::sin(cam.vfov_degrees * pi<double> / 360) *
                         normalize_or_zero(vec3(0.6, -1.0, 0.55));
  return cam.prepare();
}

// One ray through each pixel centre, row by row from the top left.
inline std::vector<rayf> camera_rays(const aabb& box, int width, int height) {
  const auto cam = framing_camera(box, width, height);
  std::vector<rayf> rays;
  rays.reserve(std::size_t(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const ray r = cam.generate((x + 0.5) / width, (y + 0.5) / height);
      rays.emplace_back(vec3f(r.origin), vec3f(r.direction));
    }
  return rays;
}

// n rays with origins uniform in the box grown by 20% about its centre and uniform directions.
inline std::vector<rayf> random_rays(const aabb& box, int n, std::uint64_t seed) {
  const vec3 c = box.center(), half = 0.6 * box.extent();
  std::vector<rayf> rays;
  rays.reserve(n);
  for (int i = 0; i < n; ++i) {
    rng g(seed, std::uint32_t(i));
    const vec3 o = c + half * (2.0 * vec3(g.uniform(), g.uniform(), g.uniform()) - 1.0);
    const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
    const double s = std::sqrt(std::max(0.0, 1 - z * z));
    rays.emplace_back(vec3f(o), vec3f(vec3(s * std::cos(phi), s * std::sin(phi), z)));
  }
  return rays;
}

// n rays from a sphere around the model into it: origins uniform on the sphere that bounds the
// box (radius: half its diagonal), each aimed at a point uniform in the box. Incoherent like
// random_rays, but every ray comes from outside and crosses the whole model, as in the usual
// "rays from a bounding sphere" benchmark.
inline std::vector<rayf> sphere_rays(const aabb& box, int n, std::uint64_t seed) {
  const vec3 c = box.center(), e = box.extent();
  const double radius = 0.5 * glm::length(e);
  std::vector<rayf> rays;
  rays.reserve(n);
  for (int i = 0; i < n; ++i) {
    rng g(seed, std::uint32_t(i), 7);
    const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
    const double s = std::sqrt(std::max(0.0, 1 - z * z));
    const vec3 o = c + radius * vec3(s * std::cos(phi), s * std::sin(phi), z);
    const vec3 target = box.lo + vec3(g.uniform(), g.uniform(), g.uniform()) * e;
    rays.emplace_back(vec3f(o), vec3f(target - o));
  }
  return rays;
}

}  // namespace chapter_5_2

#pragma once
// The default scene (book 2.2, README: `whitted` renders it to whitted.png), built in C++ so that
// chapter 2.2 needs no scene file: one ball of each material on a checkered floor, a rotated
// cube mesh, a soft area light and a point light. scenes/default.yaml (book 4.1) writes the
// same scene as a file; a test renders both and finds the same image, bit for bit.
#include <zraka/core/affine.hpp>
#include <zraka/core/compiled.hpp>
#include <zraka/geometry/mesh.hpp>
#include <zraka/materials/material.hpp>
#include <zraka/scene/scene.hpp>

#include <array>
#include <cstdint>
#include <utility>

namespace zraka {

// A cube of side 1 centred at the origin: six faces of two triangles, one normal per face, wound
// counter-clockwise seen from outside (scenes/meshes/cube.obj has the same cube).
ZRAKA_COMPILED_FN mesh unit_cube_mesh();

ZRAKA_COMPILED_FN scene default_scene();

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN mesh unit_cube_mesh() {
  mesh m;
  // Each face: a corner, two edges (their cross product points out), the outward normal.
  struct face { vec3 corner, u, v, n; };
  const std::array<face, 6> faces{{
      {{-0.5, -0.5, -0.5}, {0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  // -z
      {{-0.5, -0.5, 0.5}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}},    // +z
      {{-0.5, -0.5, -0.5}, {0, 0, 1}, {0, 1, 0}, {-1, 0, 0}},  // -x
      {{0.5, -0.5, -0.5}, {0, 1, 0}, {0, 0, 1}, {1, 0, 0}},    // +x
      {{-0.5, -0.5, -0.5}, {1, 0, 0}, {0, 0, 1}, {0, -1, 0}},  // -y
      {{-0.5, 0.5, -0.5}, {0, 0, 1}, {1, 0, 0}, {0, 1, 0}},    // +y
  }};
  for (const face& f : faces) {
    const auto base = std::uint32_t(m.positions.size());
    for (const vec3& p : {f.corner, f.corner + f.u, f.corner + f.u + f.v, f.corner + f.v}) {
      m.positions.push_back(p);
      m.normals.push_back(f.n);
    }
    m.triangles.push_back({base, base + 1, base + 2});  // the square as a fan of two triangles
    m.triangles.push_back({base, base + 2, base + 3});
  }
  return m;
}

// [listing default-scene]
ZRAKA_COMPILED_FN scene default_scene() {
  scene sc;
  sc.settings.width = 400, sc.settings.height = 240, sc.settings.spp = 16;
  sc.background = rgb(0.55f, 0.7f, 0.95f);
  sc.ambient = rgb(0.08f);  // Whitted's ambient term (book 2.2)
  sc.camera.position = {0, 1.6, 6.5};
  sc.camera.look_at = {0, 0.8, 0};
  sc.camera.vfov_degrees = 38;

  const int floor = sc.add_material(material::lambertian(texture::checker(rgb(0.85f), rgb(0.25f), 0.75)));
  const int glass = sc.add_material(material::dielectric(1.5));
  const int mirror = sc.add_material(material::fuzzy_metal(rgb(0.9f), 0.0));
  const int brushed = sc.add_material(material::fuzzy_metal(rgb(0.9f, 0.75f, 0.5f), 0.25));
  const int red = sc.add_material(material::phong(rgb(0.7f, 0.1f, 0.08f), rgb(0.25f), 60));
  const int blue = sc.add_material(material::lambertian(rgb(0.15f, 0.3f, 0.75f)));

  // The lights: a soft one (a glowing quad facing down, u x v = -y) and a point light.
  sc.add(quad{{-1, 5, 1}, {0, 0, -2}, {2, 0, 0}}, sc.add_material(material::emitter(rgb(6.0f))));
  sc.add(point_light_t<double>{{-5, 6, 6}, rgb(60.0f)});

  sc.add(plane::from_point_normal({0, 0, 0}, {0, 1, 0}), floor);
  sc.add(sphere{{-2.1, 0.8, 0}, 0.8}, mirror);
  sc.add(sphere{{0, 0.9, 0.6}, 0.9}, glass);
  sc.add(sphere{{2.1, 0.8, 0}, 0.8}, red);
  sc.add(sphere{{1.0, 0.4, 2.2}, 0.4}, blue);
  sc.add(sphere{{-1.2, 0.35, 2.3}, 0.35}, brushed);

  // The cube: scaled, then rotated 30 degrees about y, then moved (affine.hpp).
  const affine place = affine::translate({0.3, 0.55, -2.2}) *
                       (affine::rotate({0, 1, 0}, 30 * pi<double> / 180) * affine::scale(vec3(1.1)));
  mesh cube = unit_cube_mesh();
  for (vec3& p : cube.positions) p = place.point(p);
  for (vec3& n : cube.normals) n = place.normal(n);
  sc.add(std::move(cube), blue);

  sc.build_acceleration();  // an object BVH over the eight bounded objects
  return sc;
}
// [end]
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

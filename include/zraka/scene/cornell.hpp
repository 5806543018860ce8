#pragma once
// The Cornell box in code (book 2.3, 4.2): a room 2 units wide, high and deep, open towards the
// camera, with a white floor, ceiling and back wall, a red left and a green right wall, and one
// quad light hanging 2 cm under the ceiling. Three variants fill it:
//   boxes   a short and a tall white box (the classic scene; diffuse only);
//   glass   the tall box and a glass sphere (IOR 1.5);
//   spheres a mirror sphere and a glass sphere (the depth sweep of the thesis's Figure 4.4).
// Coordinates: y up, the room spans x and z in [-1, 1], y in [0, 2]; the camera looks down -z.
// scenes/cornell*.yaml describe the same scenes for the scene-file loader.
#include <zraka/core/compiled.hpp>
#include <zraka/core/enum_names.hpp>
#include <zraka/core/error.hpp>
#include <zraka/scene/scene.hpp>

#include <cmath>
#include <string>
#include <string_view>

namespace zraka {

// [listing box]
// A box as six quads with outward normals: centre c, full sizes, turned by `degrees` about +y.
template <class T>
void add_box(scene_t<T>& sc, const vec3_t<T>& c, const vec3_t<T>& size, T degrees, int mat) {
  const T a = degrees * pi<T> / T(180);
  const vec3_t<T> ex = size.x * vec3_t<T>(std::cos(a), T(0), -std::sin(a));
  const vec3_t<T> ey(T(0), size.y, T(0));
  const vec3_t<T> ez = size.z * vec3_t<T>(std::sin(a), T(0), std::cos(a));  // ex x ey ~ ez
  const vec3_t<T> o = c - (ex + ey + ez) / T(2);
  // u x v points out of the box on every face.
  sc.add(parallelogram_t<T>{o, ey, ex}, mat);        // -z
  sc.add(parallelogram_t<T>{o + ez, ex, ey}, mat);   // +z
  sc.add(parallelogram_t<T>{o, ez, ey}, mat);        // -x
  sc.add(parallelogram_t<T>{o + ex, ey, ez}, mat);   // +x
  sc.add(parallelogram_t<T>{o, ex, ez}, mat);        // -y
  sc.add(parallelogram_t<T>{o + ey, ez, ex}, mat);   // +y
}
// [end]

enum class cornell_variant { boxes, glass, spheres };

inline constexpr enum_name<cornell_variant> cornell_variant_names[] = {
    {cornell_variant::boxes, "boxes"}, {cornell_variant::glass, "glass"}, {cornell_variant::spheres, "spheres"}};
constexpr std::span<const enum_name<cornell_variant>> enum_names(cornell_variant) { return cornell_variant_names; }  // enum_names.hpp
inline cornell_variant parse_cornell_variant(std::string_view s) {
  return parse_enum<cornell_variant>(s, "Cornell box variant");
}

// [listing cornell]
template <class T> scene_t<T> cornell_box(cornell_variant variant = cornell_variant::glass) {
  using v3 = vec3_t<T>;
  scene_t<T> sc;
  const int white = sc.add_material(material::lambertian(rgb(0.73f)));
  const int red = sc.add_material(material::lambertian(rgb(0.65f, 0.05f, 0.05f)));
  const int green = sc.add_material(material::lambertian(rgb(0.12f, 0.45f, 0.15f)));
  const int light = sc.add_material(material::emitter(rgb(17, 12, 4)));  // one-sided, facing down
  sc.add(parallelogram_t<T>{v3(-1, 0, -1), v3(0, 0, 2), v3(2, 0, 0)}, white);  // floor, up
  sc.add(parallelogram_t<T>{v3(-1, 2, -1), v3(2, 0, 0), v3(0, 0, 2)}, white);  // ceiling, down
  sc.add(parallelogram_t<T>{v3(-1, 0, -1), v3(2, 0, 0), v3(0, 2, 0)}, white);  // back, +z
  sc.add(parallelogram_t<T>{v3(-1, 0, -1), v3(0, 2, 0), v3(0, 0, 2)}, red);    // left, +x
  sc.add(parallelogram_t<T>{v3(1, 0, -1), v3(0, 0, 2), v3(0, 2, 0)}, green);   // right, -x
  sc.add(parallelogram_t<T>{v3(-0.25, 1.98, -0.2), v3(0.5, 0, 0), v3(0, 0, 0.4)}, light);

  const int glass = sc.add_material(material::dielectric(1.5));
  const int mirror = sc.add_material(material::mirror(rgb(0.9f)));
  if (variant == cornell_variant::boxes)
    add_box(sc, v3(0.33, 0.3, 0.35), v3(0.6, 0.6, 0.6), T(-18), white);
  if (variant != cornell_variant::spheres)
    add_box(sc, v3(-0.35, 0.6, -0.35), v3(0.6, 1.2, 0.6), T(17), white);
  if (variant == cornell_variant::glass) sc.add(sphere_t<T>{v3(0.38, 0.35, 0.35), T(0.35)}, glass);
  if (variant == cornell_variant::spheres) {
    sc.add(sphere_t<T>{v3(-0.42, 0.4, -0.35), T(0.4)}, mirror);
    sc.add(sphere_t<T>{v3(0.4, 0.35, 0.3), T(0.35)}, glass);
  }
  sc.background = rgb(0);
  sc.camera.position = v3(0, 1, 3.94);
  sc.camera.look_at = v3(0, 1, 0);
  sc.camera.vfov_degrees = T(38);
  sc.settings.width = 200;
  sc.settings.height = 200;
  sc.settings.spp = 64;
  sc.settings.max_depth = 8;
  sc.build_acceleration();  // an object BVH: 13 to 20 objects
  return sc;
}
// [end]

// Compiled once at double (compiled.hpp).
ZRAKA_INSTANCE(void add_box(scene_t<double>&, const vec3_t<double>&, const vec3_t<double>&, double, int))
ZRAKA_INSTANCE(scene_t<double> cornell_box(cornell_variant))

}  // namespace zraka

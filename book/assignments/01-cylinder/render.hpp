#pragma once
// The picture for assignment 01: one cylinder, tilted, shaded by its normal as in chapter 1.2
// (white where the rays miss). Shared by render.cpp, which writes target.png, and by the test,
// which compares the student's picture against target.png.
#include "cylinder.hpp"

#include <zraka/cameras/camera.hpp>
#include <zraka/image/image.hpp>

namespace course {

inline cylinder demo_cylinder() {
  return {{0.0, -0.8, 0.0}, glm::normalize(zraka::vec3(0.35, 1.0, 0.25)), 0.6, 1.6};
}

// Returns the image; `hits` counts the pixels whose ray hit.
inline zraka::image render_normals(const cylinder& cyl, int width, int height, long& hits) {
  zraka::image img(width, height);
  zraka::camera settings;
  settings.position = {0.0, 1.2, 4.0};
  settings.look_at = {0.0, 0.0, 0.0};
  settings.aspect = double(width) / height;
  const auto cam = settings.prepare();
  hits = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const zraka::ray r = cam.generate((x + 0.5) / width, (y + 0.5) / height);
      zraka::hit h;
      if (intersect(cyl, r, 0.0, zraka::infinity<double>, h)) {
        ++hits;
        img.at(x, y) = zraka::rgb(0.5f * (zraka::vec3f(h.normal) + 1.0f));
      } else {
        img.at(x, y) = zraka::rgb(1.0f);
      }
    }
  return img;
}

}  // namespace course

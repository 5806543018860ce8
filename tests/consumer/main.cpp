// Uses the installed headers and the installed resource root.
#include <zraka/core/resources.hpp>
#include <zraka/geometry/sphere.hpp>

#include <cstdio>

int main() {
  const zraka::sphere s{{0, 0, -3}, 1};
  zraka::hit h;
  const bool hit = intersect(s, zraka::ray({0, 0, 0}, {0, 0, -1}), 0.0, 1e9, h);
  std::printf("hit %d at t = %g; resource root %s\n", hit, h.t,
              zraka::resource_root().string().c_str());
  return hit && h.t == 2.0 ? 0 : 1;
}

#pragma once
// What a material's scatter() returns (material.hpp): the sampled direction and the path weight.
#include <zraka/core/vec.hpp>
#include <zraka/image/image.hpp>  // rgb

namespace zraka {

template <class T> struct scatter_t {
  vec3_t<T> direction;  // unit, away from the surface
  rgb weight;           // f |cos| / pdf, what the path throughput is multiplied by
  T pdf = T(0);         // density of direction; 0 for specular (a delta, not evaluable)
  bool specular = false;
};

// The fields every material has besides its kind (material.hpp): light it gives off and the
// medium it encloses. A kind's reader and writer may set and read them (emitter, dielectric).
struct material_common {
  rgb radiance{0};        // emitted from the front face (an emitter, or any glowing surface)
  bool two_sided = false; // emit from the back face too
  int interior = -1;      // media (book 6.1): scene.media index inside this closed shape; -1 no change
};

// Whitted's local model (whitted.hpp) at a hit, for the kinds it shades that way (lambertian,
// phong): the diffuse colour kd, the specular colour ks and the exponent p.
struct local_model_terms {
  rgb kd, ks;
  double shininess;
};

}  // namespace zraka

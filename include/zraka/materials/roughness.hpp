#pragma once
// The roughness of the microfacet kinds (book 5.4; rough_conductor.hpp, rough_dielectric.hpp):
// the GGX alpha as Mitsuba's (not squared), a number in (0, 1] or a texture over the surface.
#include <zraka/core/hit.hpp>
#include <zraka/textures/texture.hpp>

#include <algorithm>
#include <optional>
#include <string>

namespace zraka {

struct ggx_roughness {
  double alpha = 0.1;          // the GGX alpha, (0, 1]
  std::optional<texture> map;  // set: alpha varies over the surface (at)

  // [listing roughness-texture]
  // The GGX alpha at a hit: the number, or the roughness texture there (the mean of the
  // texture's three channels). A texel of 0 would be a mirror that the microfacet samplers cannot
  // evaluate, so alpha is kept at 0.001 or more, the sharpest the chi-square tests cover.
  template <class T> T at(const hit_t<T>& h) const {
    if (!map) return T(alpha);
    const rgb c = evaluate(*map, h.p, h.facing_normal(), h.uv);
    return T(std::clamp((double(c.x) + double(c.y) + double(c.z)) / 3, 1e-3, 1.0));
  }
  // [end]

  // The kernel's record: alpha, or the index of the texture record of its map.
  template <class Packer> void pack(Packer& p) const {
    p.record.roughness = float(alpha);
    if (map) p.record.roughness_texture = p.texture(*map);
  }

  // `roughness:` a number, or a texture as for albedo whose channels' mean is alpha.
  template <class Node> static ggx_roughness read(const Node& n) {
    ggx_roughness r;
    if (!n.has("roughness")) return r;
    if (n.is_map("roughness")) {
      const texture t = n.texture("roughness");
      // An image's texels are in [0, 1] already; checker and noise colours must be alphas too.
      if (t.type != texture::kind::image)
        for (const rgb& c : {t.a, t.b})
          if (!(c.x > 0 && c.y > 0 && c.z > 0) || max_component(c) > 1)
            n.fail("roughness", "the texture's values are GGX alphas and must be in (0, 1]");
      r.map = t;
      return r;
    }
    r.alpha = n.number("roughness");
    if (!(r.alpha > 0 && r.alpha <= 1))
      n.fail("roughness", "must be in (0, 1] (the GGX alpha), got " + n.scalar("roughness"));
    return r;
  }
  template <class Writer> void write(Writer& w) const {
    if (map) w.texture("roughness", *map);
    else w.number("roughness", alpha);
  }
};

}  // namespace zraka

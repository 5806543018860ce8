// The real-time path tracer (book 4.3): path.hpp's algorithm as an OpenCL C 1.2 kernel, one work
// item per pixel. Build it after kernels/rng.cl (zraka::cl::build_program_files), with the -D
// switches of zraka::build_options() (include/zraka/gpu_scene.hpp):
//   HAS_SPHERES HAS_QUADS HAS_PLANES HAS_TRIANGLES   which shapes exist (triangles: with the BVH)
//   HAS_METAL HAS_DIELECTRIC HAS_CHECKER HAS_EMITTERS which material features are used
//   HAS_THIN_LENS   the camera has an aperture       NEE   next-event estimation (path.hpp's default)
//   MAX_DEPTH=n     bounces                           WEAK_SEED   the thesis's per-pixel seed (C7)
// Code for a feature the scene does not use is not compiled at all.
//
// What changed from the CPU code: no recursion (OpenCL C forbids it; the loop carries the
// throughput beta and the sum L, errata C6), no pointers between objects (indices into flat
// arrays), float instead of double (except where triangle.hpp's float test itself uses double:
// two sign decisions of the watertight triangle test, so triangles need cl_khr_fp64), and a
// fixed-size stack for the BVH walk. What did not: every
// formula (the same intersection routines, error bounds and ray offsets as sphere.hpp, quad.hpp,
// plane.hpp, triangle_bvh.hpp and spawn.hpp; the same materials as material.hpp), and the random
// numbers: rng.cl keyed by (seed, pixel, sample) with path.hpp's draws in path.hpp's order, so a
// kernel sample starts from the same numbers as the CPU's.

#ifndef MAX_DEPTH
#define MAX_DEPTH 8
#endif
#define RR_DEPTH 3
#define PI_F 3.14159265358979323846f
// gamma(n) = n u / (1 - n u), u = 2^-24 (spawn.hpp in float)
#define GAMMA(n) (((float)(n) * 0x1p-24f) / (1.0f - (float)(n) * 0x1p-24f))

#ifdef HAS_TRIANGLES
// The watertight triangle test (triangle.hpp) decides two signs in double: an edge function
// near 0, and t > 0 through the plane's equation. A device without doubles cannot run it.
#ifdef cl_khr_fp64
#pragma OPENCL EXTENSION cl_khr_fp64 : enable
#define GAMMA_D(n) (((double)(n) * 0x1p-53) / (1.0 - (double)(n) * 0x1p-53))
#else
#error "the watertight triangle test needs double precision (cl_khr_fp64) on the OpenCL device"
#endif
#endif

// ---------------------------------------------------------------- the shared structs (gpu_scene.hpp)
// [listing cl-structs]
typedef struct { float4 center_radius; int material, p0, p1, p2; } sphere_t;
typedef struct { float4 corner, u, v, normal_area; int material, p0, p1, p2; } quad_t;
typedef struct { float4 point, normal; int material, p0, p1, p2; } plane_t;
typedef struct { float4 a, b, c; uint id; int material, p0, p1; } triangle_t;
typedef struct { float box[6][4]; uint child[4], count[4]; } node4_t;
typedef struct {
  float4 albedo_a, albedo_b, radiance;
  int kind, checker, two_sided, pad;
  float fuzz, ior, cell, pad2;
} material_t;
typedef struct { int kind, index; } light_t;
typedef struct { float4 origin, u, v, corner, horizontal, vertical; float lens_radius, p0, p1, p2; } camera_t;
// [end]
#define KIND_LAMBERTIAN 0
#define KIND_METAL 1
#define KIND_DIELECTRIC 2
#define KIND_EMITTER 3

// The scene, as the kernel's arguments give it.
typedef struct {
  global const sphere_t* spheres;
  global const quad_t* quads;
  global const plane_t* planes;
  global const triangle_t* tris;
  global const node4_t* nodes;
  global const material_t* materials;
  global const light_t* lights;
  int n_spheres, n_quads, n_planes, n_lights, n_nodes;
  float3 background;
} scene_t;

typedef struct {
  float t;
  float3 p, p_error, normal;  // normal: unit, outward
  bool front_face;
  int material;
} hit_t;

// ---------------------------------------------------------------- random numbers
// [listing stream]
#ifdef WEAK_SEED
// The thesis's tutorial (errata C7): Marsaglia's multiply-with-carry pair seeded with the raw
// pixel coordinates, the same numbers again in every frame. Kept only to show the pattern.
typedef struct { uint s0, s1; } stream_t;
stream_t stream_make(ulong seed, uint x, uint y, uint width, uint sample) {
  stream_t s;
  s.s0 = x;
  s.s1 = y;
  return s;
}
float uniform(stream_t* r) {
  r->s0 = 36969u * (r->s0 & 65535u) + (r->s0 >> 16);
  r->s1 = 18000u * (r->s1 & 65535u) + (r->s1 >> 16);
  return (float)(((r->s0 << 16) + r->s1) >> 8) * 0x1p-24f;
}
#else
// rng.cl's stream for (seed, pixel, sample). rng::uniform() on the CPU takes two words for its
// 53 bits; this takes the top 24 bits of the first and steps over the second (a counter-based
// stream can skip a number without computing it), so both sides use the same numbers in the
// same order and agree to 2^-24.
typedef rng_t stream_t;
stream_t stream_make(ulong seed, uint x, uint y, uint width, uint sample) {
  return rng_make(seed, y * width + x, sample);
}
float uniform(stream_t* r) {
  const uint hi = rng_next_u32(r);
  r->dimension++;
  return (float)(hi >> 8) * 0x1p-24f;
}
#endif
// [end]

// The largest float below one (sampling.hpp's clamp_unit).
float clamp_unit(float u) { return clamp(u, 0.0f, 0x1.fffffep-1f); }

// ---------------------------------------------------------------- spawning rays (spawn.hpp)
float nudge(float x, float off) {
  return off > 0.0f ? nextafter(x, INFINITY) : (off < 0.0f ? nextafter(x, -INFINITY) : x);
}
float3 offset_origin(float3 p, float3 p_error, float3 n, float3 w) {
  const float d = dot(fabs(n), p_error);
  float3 off = d * n;
  if (dot(w, n) < 0.0f) off = -off;
  const float3 po = p + off;
  return (float3)(nudge(po.x, off.x), nudge(po.y, off.y), nudge(po.z, off.z));
}

// ---------------------------------------------------------------- shapes
#ifdef HAS_SPHERES
// [listing cl-sphere]
bool hit_sphere(const sphere_t s, float3 o, float3 D, float t_max, hit_t* h) {
  const float3 c = s.center_radius.xyz;
  const float r = s.center_radius.w;
  const float3 f = o - c;
  const float a = dot(D, D);
  if (!(a > 0.0f)) return false;
  const float b = dot(f, D);
  const float cc = dot(f, f) - r * r;
  const float3 l = f - (b / a) * D;  // centre-to-line offset: no cancellation in the discriminant
  const float ll = length(l);
  const float disc = a * (r - ll) * (r + ll);
  if (!(disc >= 0.0f)) return false;
  const float q = -(b + copysign(sqrt(disc), b));
  float t0 = cc / q, t1 = q / a;
  if (t0 > t1) { const float x = t0; t0 = t1; t1 = x; }
  float t = t0;
  if (!(t > 0.0f && t < t_max)) {
    t = t1;
    if (!(t > 0.0f && t < t_max)) return false;
  }
  if (h) {
    float3 radial = f + t * D;
    const float len = length(radial);
    if (!(len > 0.0f) || !isfinite(len)) radial = (t == t0 ? -D : D);
    const float3 on = radial * (r / length(radial));
    h->t = t;
    h->p = c + on;
    h->p_error = GAMMA(6) * (fabs(on) + fabs(h->p));
    h->normal = on / r;
    h->material = s.material;
  }
  return true;
}
// [end]
#endif

#ifdef HAS_QUADS
bool hit_quad(const quad_t q, float3 o, float3 D, float t_max, hit_t* h) {
  const float3 u = q.u.xyz, v = q.v.xyz, Q = q.corner.xyz;
  const float3 n_raw = cross(u, v);
  const float3 N = q.normal_area.xyz;
  const float denom = dot(N, D);
  if (!(fabs(denom) > GAMMA(3) * dot(fabs(N), fabs(D)))) return false;
  const float3 QO = Q - o;
  const float s = dot(N, QO);
  const float s_error = GAMMA(4) * dot(fabs(N), fabs(Q) + fabs(o)) + GAMMA(4) * length(QO);
  if (!(fabs(s) > s_error)) return false;
  const float t = s / denom;
  if (!(t > 0.0f && t < t_max)) return false;
  const float3 d = (o + t * D) - Q;
  const float3 w = n_raw / dot(n_raw, n_raw);
  const float a = dot(w, cross(d, v));
  const float b = dot(w, cross(u, d));
  if (!(a >= 0.0f && a <= 1.0f && b >= 0.0f && b <= 1.0f)) return false;
  if (h) {
    h->t = t;
    h->p = Q + a * u + b * v;
    h->p_error = GAMMA(4) * (fabs(Q) + fabs(a * u) + fabs(b * v));
    h->normal = N;
    h->material = q.material;
  }
  return true;
}
#endif

#ifdef HAS_PLANES
bool hit_plane(const plane_t pl, float3 o, float3 D, float t_max, hit_t* h) {
  const float3 N = pl.normal.xyz, P0 = pl.point.xyz;
  const float3 to_plane = P0 - o;
  const float num = dot(to_plane, N), den = dot(D, N);
  if (!(fabs(den) > GAMMA(3) * dot(fabs(D), fabs(N)))) return false;
  if (!(fabs(num) > GAMMA(5) * dot(fabs(to_plane), fabs(N)))) return false;
  const float t = num / den;
  if (!(t > 0.0f && t < t_max)) return false;
  if (h) {
    const float3 x = o + t * D;
    h->t = t;
    h->p = x - dot(x - P0, N) * N;  // reprojected onto the plane
    h->p_error = (float3)(GAMMA(16) * dot(fabs(x) + fabs(P0), fabs(N)));
    h->normal = N;
    h->material = pl.material;
  }
  return true;
}
#endif

#ifdef HAS_TRIANGLES
// [listing cl-bvh]
// triangle_bvh.hpp's walk: a stack of (child, count, entry t), nearest child on top.
#define STACK_SIZE 196
#define CULL_MARGIN (1.0f + 0x1p-18f)
typedef struct { uint child, count; float t_enter; } entry_t;

// Slab test of a node's four boxes; returns a mask of the boxes hit and their entry t.
uint hit_boxes(global const node4_t* n, float3 o, float3 inv, float t_max, float* t_enter) {
  const float widen = 1.0f + 2.0f * GAMMA(3);
  const float oa[3] = {o.x, o.y, o.z}, ia[3] = {inv.x, inv.y, inv.z};
  uint mask = 0;
  for (int k = 0; k < 4; ++k) {
    float t0 = 0.0f, t1 = INFINITY;
    for (int a = 0; a < 3; ++a) {
      const bool neg = signbit(ia[a]);
      const float tn = (n->box[neg ? 3 + a : a][k] - oa[a]) * ia[a];
      const float tf = (n->box[neg ? a : 3 + a][k] - oa[a]) * ia[a];
      t0 = tn > t0 ? tn : t0;  // a NaN leaves t0
      t1 = tf < t1 ? tf : t1;
    }
    t_enter[k] = t0;
    if (t0 <= t1 * widen && t0 <= t_max) mask |= 1u << k;
  }
  return mask;
}

// [listing cl-watertight]
// triangle.hpp's watertight test, line for line: its per-ray half (watertight_ray), its
// per-triangle half (watertight_test) with the exact-sign edge functions, and the certainty
// of t > 0 (t_certainly_positive). OpenCL C may fuse a*b - c*d into an FMA, as a C++ compiler
// may: the filter in edge_function is there for exactly that.
typedef struct { float3 origin, direction; int kx, ky, kz; float sx, sy, sz; } watertight_ray_t;

float component(float3 v, int k) { return k == 0 ? v.x : (k == 1 ? v.y : v.z); }

watertight_ray_t watertight_ray(float3 o, float3 D) {
  watertight_ray_t r;
  r.origin = o;
  r.direction = D;
  const float3 ad = fabs(D);
  r.kz = ad.x > ad.y ? (ad.x > ad.z ? 0 : 2) : (ad.y > ad.z ? 1 : 2);
  r.kx = (r.kz + 1) % 3;
  r.ky = (r.kx + 1) % 3;
  if (component(D, r.kz) < 0.0f) {  // keep the winding
    const int k = r.kx;
    r.kx = r.ky;
    r.ky = k;
  }
  r.sx = component(D, r.kx) / component(D, r.kz);
  r.sy = component(D, r.ky) / component(D, r.kz);
  r.sz = 1.0f / component(D, r.kz);
  return r;
}

float difference_of_products(float a, float b, float c, float d) {
  return (float)((double)a * (double)b - (double)c * (double)d);  // the products are exact
}
float edge_function(float a, float b, float c, float d) {
  const float e = a * b - c * d;
  if (fabs(e) > GAMMA(3) * (fabs(a * b) + fabs(c * d))) return e;  // sign certain
  return difference_of_products(a, b, c, d);
}

// q = p - O, permuted, then sheared: (x, y) and q[kz]; z = sz q[kz] only if t is wanted.
float3 to_ray_space(const watertight_ray_t* r, float3 p) {
  const float3 q = p - r->origin;
  return (float3)(component(q, r->kx) - r->sx * component(q, r->kz),
                  component(q, r->ky) - r->sy * component(q, r->kz), component(q, r->kz));
}

bool watertight_test(const watertight_ray_t* r, float3 A, float3 B, float3 C, float* t,
                     float* u, float* v) {
  const float3 a = to_ray_space(r, A), b = to_ray_space(r, B), c = to_ray_space(r, C);
  const float e_a = edge_function(c.x, b.y, c.y, b.x);
  const float e_b = edge_function(a.x, c.y, a.y, c.x);
  if (fmin(e_a, e_b) < 0.0f && fmax(e_a, e_b) > 0.0f) return false;  // early out
  const float e_c = edge_function(b.x, a.y, b.y, a.x);
  if (fmin(e_c, fmin(e_a, e_b)) < 0.0f && fmax(e_c, fmax(e_a, e_b)) > 0.0f)
    return false;  // the ray passes outside an edge: weights of both signs
  const float det = e_a + e_b + e_c;  // 0: seen edge-on
  if (!(fabs(det) > 0.0f)) return false;
  const float inv_det = 1.0f / det;
  *t = (e_a * (r->sz * a.z) + e_b * (r->sz * b.z) + e_c * (r->sz * c.z)) * inv_det;
  *u = e_b * inv_det;
  *v = e_c * inv_det;
  return true;
}

// t = s / (n.D), s = n.(A - O): accepted when both signs are beyond their rounding errors.
bool t_certainly_positive(float3 A, float3 B, float3 C, float3 O, float3 D) {
  const double3 a = convert_double3(A), e1 = convert_double3(B) - a, e2 = convert_double3(C) - a;
  const double3 w = a - convert_double3(O), d = convert_double3(D);
  const double3 n = (double3)(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                              e1.x * e2.y - e1.y * e2.x);
  const double3 n_abs = (double3)(fabs(e1.y * e2.z) + fabs(e1.z * e2.y),
                                  fabs(e1.z * e2.x) + fabs(e1.x * e2.z),
                                  fabs(e1.x * e2.y) + fabs(e1.y * e2.x));
  const double s = n.x * w.x + n.y * w.y + n.z * w.z;
  const double n_dot_d = n.x * d.x + n.y * d.y + n.z * d.z;
  const double3 aw = fabs(w), ad = fabs(d);
  return fabs(s) > GAMMA_D(9) * (n_abs.x * aw.x + n_abs.y * aw.y + n_abs.z * aw.z) &&
         fabs(n_dot_d) > GAMMA_D(8) * (n_abs.x * ad.x + n_abs.y * ad.y + n_abs.z * ad.z) &&
         (s > 0.0) == (n_dot_d > 0.0);
}

// triangle_bvh.hpp's leaf test: ties at equal t go to the lower input index.
bool test_triangle(global const triangle_t* tri, const watertight_ray_t* r, float t_max,
                   float* best_t, uint* best_id, float* bu, float* bv) {
  const float3 A = tri->a.xyz, B = tri->b.xyz, C = tri->c.xyz;
  float t, u, v;
  if (!watertight_test(r, A, B, C, &t, &u, &v)) return false;
  if (!(t > 0.0f && (t < t_max || (t == *best_t && tri->id < *best_id)))) return false;
  if (!t_certainly_positive(A, B, C, r->origin, r->direction)) return false;
  *best_t = t;
  *best_id = tri->id;
  *bu = u;
  *bv = v;
  return true;
}
// [end]

// Nearest hit (h != 0) or any hit (h == 0) with t in (0, t_max).
bool hit_bvh(const scene_t* sc, float3 o, float3 D, float t_max, hit_t* h) {
  if (sc->n_nodes == 0) return false;  // the all-features kernel on a scene without triangles
  const float3 inv = 1.0f / D;
  const watertight_ray_t wr = watertight_ray(o, D);
  entry_t stack[STACK_SIZE];
  int top = 0;
  stack[top++] = (entry_t){0u, 0u, 0.0f};
  bool found = false;
  float best_t = INFINITY, bu = 0.0f, bv = 0.0f;
  uint best_id = 0xffffffffu, best_leaf = 0;
  while (top > 0) {
    const entry_t e = stack[--top];
    if (e.t_enter > t_max * CULL_MARGIN) continue;  // triangle_bvh::cull_margin
    if (e.count) {
      for (uint k = 0; k < e.count; ++k)
        if (test_triangle(&sc->tris[e.child + k], &wr, t_max, &best_t, &best_id, &bu, &bv)) {
          if (!h) return true;
          found = true;
          t_max = best_t;
          best_leaf = e.child + k;
        }
      continue;
    }
    global const node4_t* n = &sc->nodes[e.child];
    float t[4];
    uint mask = hit_boxes(n, o, inv, t_max * CULL_MARGIN, t);
    const int first = top;
    for (int k = 0; k < 4 && top < STACK_SIZE; ++k) {
      if (!(mask & (1u << k))) continue;
      int j = top++;  // insertion keeps [first, top) sorted by t, nearest last
      for (; j > first && stack[j - 1].t_enter < t[k]; --j) stack[j] = stack[j - 1];
      stack[j] = (entry_t){n->child[k], n->count[k], t[k]};
    }
  }
  if (found) {
    global const triangle_t* tri = &sc->tris[best_leaf];
    const float3 A = tri->a.xyz, B = tri->b.xyz, C = tri->c.xyz;
    const float w = 1.0f - bu - bv;
    h->t = best_t;
    h->p = w * A + bu * B + bv * C;
    // The float test's own rounding, as scene.hpp widens it for meshes: gamma(64).
    h->p_error = GAMMA(64) * (fabs(w * A) + fabs(bu * B) + fabs(bv * C));
    h->normal = normalize(cross(B - A, C - A));
    h->material = tri->material;
  }
  return found;
}
// [end]
#endif

// [listing cl-nearest]
bool nearest_hit(const scene_t* sc, float3 o, float3 D, hit_t* h) {
  float t_max = INFINITY;
  bool found = false;
#ifdef HAS_PLANES
  for (int i = 0; i < sc->n_planes; ++i)
    if (hit_plane(sc->planes[i], o, D, t_max, h)) { found = true; t_max = h->t; }
#endif
#ifdef HAS_SPHERES
  for (int i = 0; i < sc->n_spheres; ++i)
    if (hit_sphere(sc->spheres[i], o, D, t_max, h)) { found = true; t_max = h->t; }
#endif
#ifdef HAS_QUADS
  for (int i = 0; i < sc->n_quads; ++i)
    if (hit_quad(sc->quads[i], o, D, t_max, h)) { found = true; t_max = h->t; }
#endif
#ifdef HAS_TRIANGLES
  if (hit_bvh(sc, o, D, t_max, h)) found = true;
#endif
  if (found) h->front_face = dot(D, h->normal) < 0.0f;
  return found;
}

bool occluded(const scene_t* sc, float3 o, float3 D, float t_max) {
#ifdef HAS_PLANES
  for (int i = 0; i < sc->n_planes; ++i)
    if (hit_plane(sc->planes[i], o, D, t_max, 0)) return true;
#endif
#ifdef HAS_SPHERES
  for (int i = 0; i < sc->n_spheres; ++i)
    if (hit_sphere(sc->spheres[i], o, D, t_max, 0)) return true;
#endif
#ifdef HAS_QUADS
  for (int i = 0; i < sc->n_quads; ++i)
    if (hit_quad(sc->quads[i], o, D, t_max, 0)) return true;
#endif
#ifdef HAS_TRIANGLES
  if (hit_bvh(sc, o, D, t_max, 0)) return true;
#endif
  return false;
}
// [end]

// ---------------------------------------------------------------- materials (material.hpp)
float3 facing(const hit_t* h) { return h->front_face ? h->normal : -h->normal; }

float3 albedo(global const material_t* m, const hit_t* h) {
#ifdef HAS_CHECKER
  if (m->checker) {  // texture.hpp: the axis nearest the normal is dropped
    const float3 an = fabs(h->normal);
    const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    const float p[3] = {h->p.x, h->p.y, h->p.z};
    long sum = 0;
    for (int i = 0; i < 3; ++i)
      if (i != drop) sum += (long)floor(p[i] / m->cell);
    return (sum & 1) ? m->albedo_b.xyz : m->albedo_a.xyz;
  }
#endif
  return m->albedo_a.xyz;
}

float3 emitted(global const material_t* m, const hit_t* h) {
  return h->front_face || m->two_sided ? m->radiance.xyz : (float3)(0.0f);
}

// onb.hpp's frame around a unit n (Duff et al.), local (x, y, z) to world.
float3 to_world(float3 n, float3 v) {
  const float sign = copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  const float3 t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  const float3 b = (float3)(c, sign + n.y * n.y * a, -n.y);
  return v.x * t + v.y * b + v.z * n;
}

#ifdef HAS_DIELECTRIC
float cos2_transmitted(float cos_i, float eta) {
  const float c = clamp(cos_i, 0.0f, 1.0f);
  if (eta <= 1.0f) return (1.0f - eta) * (1.0f + eta) + (eta * c) * (eta * c);
  return 1.0f - eta * eta * ((1.0f - c) * (1.0f + c));
}
// [listing cl-fresnel]
float fresnel_dielectric(float cos_i, float eta) {
  if (eta == 1.0f) return 0.0f;
  const float ci = clamp(cos_i, 0.0f, 1.0f);
  const float cos2_t = cos2_transmitted(ci, eta);
  if (cos2_t <= 0.0f) return 1.0f;  // total internal reflection
  const float ct = sqrt(cos2_t);
  const float r_s = (eta * ci - ct) / (eta * ci + ct);
  const float r_p = (ci - eta * ct) / (ci + eta * ct);
  return clamp((r_s * r_s + r_p * r_p) / 2.0f, 0.0f, 1.0f);
}
// [end]
bool refract_dir(float3 d, float3 n, float eta, float3* t) {
  const float cos_i = clamp(-dot(d, n), 0.0f, 1.0f);
  const float3 d_perp = d + cos_i * n;
  const float cos2_t = eta > 1.0f ? 1.0f - eta * eta * dot(d_perp, d_perp) : cos2_transmitted(cos_i, eta);
  if (cos2_t < 0.0f) return false;
  *t = normalize(eta * d_perp - sqrt(cos2_t) * n);
  return true;
}
#endif

// Scatter (material.hpp's scatter()): false when absorbed; *weight is f cos / pdf.
// [listing cl-scatter]
bool scatter(global const material_t* m, float3 d, const hit_t* h, stream_t* g, float3* wi,
             float3* weight, bool* specular) {
  const float3 n = facing(h);
#ifdef HAS_METAL
  if (m->kind == KIND_METAL) {  // mirror direction plus fuzz times a point in the unit ball
    const float u0 = uniform(g), u1 = uniform(g), u2 = uniform(g);
    const float z = 1.0f - 2.0f * clamp_unit(u0), s = 2.0f * sqrt(clamp_unit(u0) * (1.0f - clamp_unit(u0)));
    const float phi = 2.0f * PI_F * clamp_unit(u1);
    const float3 ball = cbrt(clamp_unit(u2)) * (float3)(s * cos(phi), s * sin(phi), z);
    const float3 w = d - 2.0f * dot(d, n) * n + m->fuzz * ball;
    const float len = length(w);
    if (!(len > 0.0f)) return false;
    *wi = w / len;
    if (!(dot(*wi, n) > 0.0f)) return false;  // pushed below the surface: absorbed
    *weight = albedo(m, h);
    *specular = true;
    return true;
  }
#endif
#ifdef HAS_DIELECTRIC
  if (m->kind == KIND_DIELECTRIC) {  // reflect with probability R (exact Fresnel), else refract
    const float eta = h->front_face ? 1.0f / m->ior : m->ior;
    float3 t;
    if (refract_dir(d, n, eta, &t) && uniform(g) >= fresnel_dielectric(-dot(d, n), eta)) *wi = t;
    else *wi = d - 2.0f * dot(d, n) * n;
    *weight = (float3)(1.0f);
    *specular = true;
    return true;
  }
#endif
  if (m->kind == KIND_EMITTER) return false;
  // Lambertian, cosine-weighted: f cos / pdf = albedo (errata C1, C6)
  const float u0 = clamp_unit(uniform(g)), u1 = clamp_unit(uniform(g));
  uniform(g);  // material.hpp draws a third number (a lobe) for every surface with a density
  if (!(dot(-d, n) > 0.0f)) return false;
  const float r = sqrt(u0), phi = 2.0f * PI_F * u1;
  *wi = to_world(n, (float3)(r * cos(phi), r * sin(phi), sqrt(1.0f - u0)));
  if (!(dot(*wi, n) > 0.0f)) return false;  // rounding put it on the horizon
  *weight = albedo(m, h);
  *specular = false;
  return true;
}
// [end]

#ifdef NEE
// scene.hpp's sample_light(): one light uniformly, a point on it; pdf per steradian.
bool sample_light(const scene_t* sc, float3 x, stream_t* g, float3* point, float3* wi, float* pdf,
                  float3* radiance) {
  const float u_light = uniform(g), u0 = uniform(g), u1 = uniform(g);
  if (sc->n_lights == 0) return false;
  const int n = sc->n_lights;
  const light_t l = sc->lights[clamp((int)(u_light * (float)n), 0, n - 1)];
  float3 Le;
#if defined(HAS_QUADS)
  if (l.kind == 1) {
    const quad_t q = sc->quads[l.index];
    Le = sc->materials[q.material].radiance.xyz;
    *point = q.corner.xyz + clamp_unit(u0) * q.u.xyz + clamp_unit(u1) * q.v.xyz;
    const float3 to = *point - x;
    const float d2 = dot(to, to);
    *wi = normalize(to);
    const float cos_l = -dot(q.normal_area.xyz, *wi);
    *pdf = fabs(cos_l) > 0.0f ? d2 / (q.normal_area.w * fabs(cos_l)) / (float)n : 0.0f;
    *radiance = cos_l > 0.0f ? Le : (float3)(0.0f);
  }
#endif
#if defined(HAS_SPHERES)
  if (l.kind == 0) {  // uniform in the cone of directions that see the sphere (sampling.hpp)
    const sphere_t s = sc->spheres[l.index];
    Le = sc->materials[s.material].radiance.xyz;
    const float3 to_c = s.center_radius.xyz - x;
    const float dist = length(to_c), r = s.center_radius.w;
    float h_max = 2.0f;
    if (dist > r) {
      const float sn = r / dist, sin2 = sn * sn;
      h_max = fmax(sin2 / (1.0f + sqrt(1.0f - sin2)), FLT_MIN);
    }
    const float3 axis = dist > 0.0f ? to_c / dist : (float3)(0.0f, 0.0f, 1.0f);
    const float hh = clamp_unit(u0) * h_max;
    const float sn = sqrt(hh * (2.0f - hh)), phi = 2.0f * PI_F * clamp_unit(u1);
    *wi = to_world(axis, (float3)(sn * cos(phi), sn * sin(phi), 1.0f - hh));
    hit_t lh;
    if (!hit_sphere(s, x, *wi, INFINITY, &lh)) return false;
    *point = lh.p;
    *pdf = 1.0f / (2.0f * PI_F * h_max) / (float)n;
    *radiance = dot(*wi, lh.normal) < 0.0f ? Le : (float3)(0.0f);
  }
#endif
  return *pdf > 0.0f && isfinite(*pdf);
}
#endif

// [listing cl-path]
// path.hpp's loop: L sums the light found, beta is the throughput (f cos / pdf products).
float3 radiance(const scene_t* sc, float3 o, float3 D, stream_t* g) {
  float3 L = (float3)(0.0f), beta = (float3)(1.0f);
  bool count_emission = true;  // camera rays, after a specular bounce, or without NEE
  for (int depth = 0; depth <= MAX_DEPTH; ++depth) {
    hit_t h;
    if (!nearest_hit(sc, o, D, &h)) {
      L += beta * sc->background;
      break;
    }
    global const material_t* m = &sc->materials[h.material];
#ifdef HAS_EMITTERS
    if (count_emission) L += beta * emitted(m, &h);
#endif
    if (m->kind == KIND_EMITTER || depth == MAX_DEPTH) break;
#ifdef NEE
    if (m->kind == KIND_LAMBERTIAN) {  // the next event: a point on a light
      float3 point, wi, Le;
      float pdf = 0.0f;
      if (sample_light(sc, h.p, g, &point, &wi, &pdf, &Le) && any(Le != (float3)(0.0f))) {
        const float3 so = offset_origin(h.p, h.p_error, h.normal, point - h.p);
        const float3 sd = point - so;
        const float dist = length(sd);
        const float3 n = facing(&h);
        const float cos_i = dot(n, wi);
        if (cos_i > 0.0f && dot(-D, n) > 0.0f && !occluded(sc, so, sd / dist, dist * (1.0f - GAMMA(16))))
          L += beta * albedo(m, &h) * (cos_i / PI_F) * Le / pdf;
      }
    }
#endif
    float3 wi, weight;
    bool specular;
    if (!scatter(m, D, &h, g, &wi, &weight, &specular)) break;  // absorbed
    beta *= weight;
#ifdef NEE
    count_emission = specular;
#endif
    if (depth >= RR_DEPTH) {  // Russian roulette: go on with probability q, divide by q
      const float q = fmin(1.0f, fmax(beta.x, fmax(beta.y, beta.z)));
      if (!(uniform(g) < q)) break;
      beta /= q;
    }
    o = offset_origin(h.p, h.p_error, h.normal, wi);
    D = wi;
  }
  return L;
}
// [end]

float srgb_byte(float c) {  // image_io's encoding: linear to sRGB, 8 bits
  c = clamp(c, 0.0f, 1.0f);
  const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * pow(c, 1.0f / 2.4f) - 0.055f;
  return floor(s * 255.0f + 0.5f);
}

// [listing cl-kernel]
// Adds `samples` samples (indices sample_offset, sample_offset + 1, ...) to each pixel's sum in
// accum (sample_offset 0: starts it afresh), and writes the running mean as sRGB bytes for
// display, bottom row first as OpenGL textures are stored.
kernel void render(global const sphere_t* spheres, global const quad_t* quads,
                   global const plane_t* planes, global const triangle_t* tris,
                   global const node4_t* nodes, global const material_t* materials,
                   global const light_t* lights, global const camera_t* camera,
                   global float4* accum, global uchar4* display, int n_spheres, int n_quads,
                   int n_planes, int n_lights, int n_nodes, uint width, uint height, uint sample_offset,
                   uint samples, ulong seed, float4 background) {
  const uint x = get_global_id(0), y = get_global_id(1);
  if (x >= width || y >= height) return;
  const scene_t sc = {spheres, quads, planes, tris, nodes, materials, lights,
                      n_spheres, n_quads, n_planes, n_lights, n_nodes, background.xyz};
  const camera_t cam = *camera;
  float4 sum = (float4)(0.0f);  // w: samples that were finite
#ifdef WEAK_SEED
  stream_t g = stream_make(seed, x, y, width, 0);  // one stream for the pixel, every frame the same
#endif
  for (uint s = sample_offset; s < sample_offset + samples; ++s) {
#ifndef WEAK_SEED
    stream_t g = stream_make(seed, x, y, width, s);
#endif
    const float sx = ((float)x + uniform(&g)) / (float)width;
    const float sy = ((float)y + uniform(&g)) / (float)height;
    const float3 target = cam.corner.xyz + sx * cam.horizontal.xyz + sy * cam.vertical.xyz;
    float3 o = cam.origin.xyz;
#ifdef HAS_THIN_LENS
    if (cam.lens_radius > 0.0f) {
      const float r = cam.lens_radius * sqrt(uniform(&g)), phi = 2.0f * PI_F * uniform(&g);
      o += r * cos(phi) * cam.u.xyz + r * sin(phi) * cam.v.xyz;
    }
#endif
    const float3 c = radiance(&sc, o, normalize(target - o), &g);
    if (isfinite(c.x) && isfinite(c.y) && isfinite(c.z)) sum += (float4)(c, 1.0f);  // render.hpp drops NaN
  }
  const uint i = y * width + x;
  const float4 total = sample_offset == 0 ? sum : accum[i] + sum;
  accum[i] = total;
  const float3 mean = total.xyz / fmax(total.w, 1.0f);
  display[(height - 1 - y) * width + x] =
      (uchar4)((uchar)srgb_byte(mean.x), (uchar)srgb_byte(mean.y), (uchar)srgb_byte(mean.z), 255);
}
// [end]

// The layout the kernel sees, for tests/test_realtime.cpp to compare with gpu_scene.hpp's.
#define SIZE_AND(T, field) sizeof(T), (uint)((char*)&v_##T.field - (char*)&v_##T)
kernel void layout(global uint* out) {
  if (get_global_id(0) != 0) return;
  sphere_t v_sphere_t;
  quad_t v_quad_t;
  plane_t v_plane_t;
  triangle_t v_triangle_t;
  node4_t v_node4_t;
  material_t v_material_t;
  light_t v_light_t;
  camera_t v_camera_t;
  const uint values[16] = {SIZE_AND(sphere_t, material), SIZE_AND(quad_t, material),
                           SIZE_AND(plane_t, material), SIZE_AND(triangle_t, material),
                           SIZE_AND(node4_t, count), SIZE_AND(material_t, fuzz),
                           SIZE_AND(light_t, index), SIZE_AND(camera_t, lens_radius)};
  for (int i = 0; i < 16; ++i) out[i] = values[i];
}

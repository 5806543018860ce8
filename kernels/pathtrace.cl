// The real-time path tracer (book 4.3): path.hpp's loop and lights.hpp's light module as an
// OpenCL C 1.2 kernel, one work item per pixel (or per eight pixels: PATH_LANES). Build it after
// kernels/rng.cl (zraka::cl::build_program_files), with the -D switches of zraka::build_options()
// (include/zraka/gpu/gpu_scene.hpp):
//   METHOD_NAIVE | METHOD_NEE | METHOD_MIS       the algorithm (path.hpp's integrator)
//   MAX_DEPTH=n RR_DEPTH=n                       bounces; Russian roulette from bounce n on
//   HAS_SPHERES HAS_QUADS HAS_PLANES HAS_TRIANGLES   which shapes exist (triangles: with the BVH)
//   HAS_METAL HAS_DIELECTRIC HAS_PHONG HAS_CHECKER   which materials are used
//   HAS_EMITTERS                                 some material glows (emission is looked up)
//   HAS_ROUGH_CONDUCTOR HAS_ROUGH_DIELECTRIC     microfacet.hpp's GGX materials
//   HAS_TEXTURES    texture records (image or noise albedo, roughness maps), with
//   HAS_IMAGE_TEXTURES (bilinear lookups by uv) and HAS_NOISE_TEXTURES (Perlin noise, marble)
//   HAS_UV_CHECKER  a checker in surface coordinates (hits then carry (u, v), as for image textures)
//   HAS_ENVIRONMENT the environment light (environment.hpp): seen by rays that leave, sampled
//   HAS_SPHERE_LIGHTS HAS_QUAD_LIGHTS HAS_TRIANGLE_LIGHTS HAS_POINT_LIGHTS   which lights are sampled
//   HAS_THIN_LENS   the camera has an aperture   WEAK_SEED   the thesis's per-pixel seed (C7)
//   PATH_LANES=8    eight paths per work item in float8 lanes, for the scenes that loop covers
// Code for a feature the scene does not use is not compiled at all.
//
// What changed from the CPU code: no recursion, no pointers between objects (indices into flat
// arrays, the light table packed from lights.hpp's light_set_t), float instead of double
// (except two sign decisions of the watertight triangle test, which triangle.hpp makes in
// double: triangles need cl_khr_fp64), and a fixed-size stack for the BVH walk. What did not:
// every formula (the same intersection routines, error bounds and ray offsets as sphere.hpp, quad.hpp, plane.hpp, triangle_bvh.hpp
// and spawn.hpp; the same materials as material.hpp and bxdf.hpp; the same light sampling and
// densities as lights.hpp), and the random numbers: rng.cl keyed by (seed, pixel, sample) with
// path.hpp's draws in path.hpp's order, so a kernel sample starts from the same numbers as the
// CPU's.

#ifndef MAX_DEPTH
#define MAX_DEPTH 8
#endif
#ifndef RR_DEPTH
#define RR_DEPTH 3
#endif
#define PI_F 3.14159265358979323846f
#if defined(HAS_ROUGH_CONDUCTOR) || defined(HAS_ROUGH_DIELECTRIC)
#define HAS_MICROFACETS
#endif
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
// light: the object's index in the light table, or -1 (not a sampled light)
typedef struct { float4 center_radius; int material, light, p1, p2; } sphere_t;
typedef struct { float4 corner, u, v, normal_area; int material, light, p1, p2; } quad_t;
typedef struct { float4 nx, ny, nz, qx, qy, qz, ux, uy, uz, vx, vy, vz, wx, wy, wz; } quad4_t;  // lane i: quad 4k+i
typedef struct { float4 point, normal; int material, p0, p1, p2; } plane_t;
typedef struct { float4 a, b, c; uint id; int material, light, p1; } triangle_t;
typedef struct { float box[6][4]; uint child[4], count[4]; } node4_t;
typedef struct {
  float4 albedo_a, albedo_b, radiance;  // phong: kd, ks
  int kind, checker, two_sided, schlick;  // checker: 1 world, 2 uv; schlick: the conductor's F0 is in eta
  float fuzz, ior, cell, shininess;
  float4 eta, k;                        // rough_conductor: complex index per channel (or F0)
  int albedo_texture, roughness_texture, p0, p1;  // index in textures, or -1
  float roughness, p2, p3, p4;          // rough_*: the GGX alpha without a roughness texture
} material_t;
typedef struct {  // texture.hpp's texture: image texels from texels[first], row 0 at the top
  float4 a, b;
  int kind, width, height, first;
  int repeat, octaves, marble, p0;
  float cell, frequency, p1, p2;
} texture_t;
typedef struct {  // environment.hpp's map: texels from texels[first]; its distribution in env_tables
  float4 radiance;                    // a constant sky's
  int is_constant, width, height, first;
  int light, present, p0, p1;         // light: its index in the light table, or -1
  float cos_rotation, sin_rotation, marginal_total, p2;
} environment_t;
typedef struct {
  float4 position, intensity;       // point lights
  int kind, object, material, first;  // object: sphere or quad; first: triangles in light_tris
  uint count;                       // triangles: how many
  float cdf, pdf, area;             // selection CDF up to this light, its probability, area
} light_t;
typedef struct { float4 a, b, c; } light_triangle_t;  // a.w, b.w: area CDF before and after it
typedef struct { float4 origin, u, v, corner, horizontal, vertical; float lens_radius, p0, p1, p2; } camera_t;
// [end]
#define KIND_LAMBERTIAN 0
#define KIND_METAL 1
#define KIND_DIELECTRIC 2
#define KIND_EMITTER 3
#define KIND_PHONG 4
#define KIND_ROUGH_CONDUCTOR 5
#define KIND_ROUGH_DIELECTRIC 6
#define TEX_SOLID 0
#define TEX_CHECKER 1
#define TEX_IMAGE 2
#define TEX_NOISE 3
#define TEX_CHECKER_UV 4
#if defined(HAS_IMAGE_TEXTURES) || defined(HAS_UV_CHECKER)
#define HAS_SURFACE_UV  // hits carry the shape's (u, v)
#endif
#define LIGHT_SPHERE 0
#define LIGHT_QUAD 1
#define LIGHT_TRIANGLES 2
#define LIGHT_POINT 3
#define LIGHT_ENVIRONMENT 4

// The scene, as the kernel's arguments give it.
typedef struct {
  global const sphere_t* spheres;
  global const quad_t* quads;
  global const quad4_t* quad_groups;
  global const plane_t* planes;
  global const triangle_t* tris;
  global const node4_t* nodes;
  global const material_t* materials;
  global const light_t* lights;
  global const light_triangle_t* light_tris;
  int n_spheres, n_quads, n_planes, n_lights, n_nodes;
  float3 background;
#ifdef HAS_TEXTURES
  global const texture_t* textures;
  global const int* noise_permutation;
#endif
#if defined(HAS_TEXTURES) || defined(HAS_ENVIRONMENT)
  global const float4* texels;
#endif
#ifdef HAS_SURFACE_UV
  global const float4* tri_uvs;  // 2 per triangle, in the BVH's order; none: uv = barycentrics
  int has_tri_uvs;
#endif
#ifdef HAS_ENVIRONMENT
  global const environment_t* env;
  global const float* env_tables;
#endif
} scene_t;

typedef struct {
  float t;
  float3 p, p_error, normal;  // normal: unit, outward
  bool front_face;
  int material;
  int light;  // the light table's index of the object hit, or -1
#ifdef HAS_SURFACE_UV
  float2 uv;  // the shape's surface coordinates, as its C++ intersect() gives them
#endif
#ifdef HAS_TEXTURES
  const scene_t* sc;  // where a texture lookup finds its texels
#endif
} hit_t;

typedef struct { float3 t, b, n; } onb_t;

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
    h->light = s.light;
#ifdef HAS_SURFACE_UV  // sphere.hpp: longitude, latitude from -y (0) to +y (1)
    const float phi = atan2(-h->normal.z, h->normal.x) + PI_F;
    h->uv = (float2)(phi / (2.0f * PI_F), acos(clamp(-h->normal.y, -1.0f, 1.0f)) / PI_F);
#endif
  }
  return true;
}
// [end]
#endif

#ifdef HAS_QUADS
#pragma OPENCL FP_CONTRACT OFF
// [listing cl-quad4]
// quad.hpp's quad_root, line for line, on lanes of type T (comparisons give M): each name is a T
// or a float. Four quads and one ray (quad4_roots below): the quads' numbers are float4, the
// ray's float; one quad and eight rays (the lanes loop's quad8_roots): the other way round. The
// lanes (-1) that meet their quad with t in (0, t_max), and t, a, b. All lanes run every test:
// leaving early when no t is in range was no faster on PoCL (the branch costs what it saves).
// Used where products are not fused into multiply-adds, so that each lane rounds as quad_root
// does: the same quad, t, a and b, bit for bit.
#define QUAD_ROOT_LANES(T, M, nx, ny, nz, qx, qy, qz, ux, uy, uz, vx, vy, vz, wx, wy, wz, o, D, t_max)          \
  const T denom = nx * D.x + ny * D.y + nz * D.z;                                                              \
  const T qox = qx - o.x, qoy = qy - o.y, qoz = qz - o.z;                                                      \
  const T s = nx * qox + ny * qoy + nz * qoz;                                                                  \
  const T t = s / denom;                                                                                       \
  M hit = (t > 0.0f) & (t < t_max);                                                                            \
  const T nax = fabs(nx), nay = fabs(ny), naz = fabs(nz);                                                      \
  hit &= fabs(denom) > GAMMA(3) * (nax * fabs(D.x) + nay * fabs(D.y) + naz * fabs(D.z)); /* parallel */      \
  const T s_error = GAMMA(4) * (nax * (fabs(qx) + fabs(o.x)) + nay * (fabs(qy) + fabs(o.y)) +                 \
                                naz * (fabs(qz) + fabs(o.z))) +                                                \
                    GAMMA(4) * sqrt(qox * qox + qoy * qoy + qoz * qoz);                                        \
  hit &= fabs(s) > s_error; /* the origin on the plane */                                                      \
  const T dx = (o.x + t * D.x) - qx, dy = (o.y + t * D.y) - qy, dz = (o.z + t * D.z) - qz;                    \
  const T a = wx * (dy * vz - dz * vy) + wy * (dz * vx - dx * vz) + wz * (dx * vy - dy * vx);                 \
  const T b = wx * (uy * dz - uz * dy) + wy * (uz * dx - ux * dz) + wz * (ux * dy - uy * dx);                 \
  hit &= (a >= 0.0f) & (a <= 1.0f) & (b >= 0.0f) & (b <= 1.0f);                                                \
  *t_out = t;                                                                                                  \
  *a_out = a;                                                                                                  \
  *b_out = b;                                                                                                  \
  return hit

int4 quad4_roots(const quad4_t q, float3 o, float3 D, float t_max, float4* t_out, float4* a_out, float4* b_out) {
  QUAD_ROOT_LANES(float4, int4, q.nx, q.ny, q.nz, q.qx, q.qy, q.qz, q.ux, q.uy, q.uz, q.vx, q.vy, q.vz, q.wx, q.wy,
                  q.wz, o, D, t_max);
}
// [end]
#pragma OPENCL FP_CONTRACT ON

// The nearest quad with t in (0, t_max): its index and (t, a, b), or -1. Ties go to the lower
// index, as in a loop quad by quad.
int nearest_quad(const scene_t* sc, float3 o, float3 D, float t_max, float* t_hit, float* a_hit, float* b_hit) {
  int best = -1;
  const int groups = (sc->n_quads + 3) / 4;
  for (int k = 0; k < groups; ++k) {
    float4 t, a, b;
    const int4 hit = quad4_roots(sc->quad_groups[k], o, D, t_max, &t, &a, &b);
    if (!any(hit)) continue;
    float lt[4], la[4], lb[4];
    vstore4(select((float4)(INFINITY), t, hit), 0, lt);
    vstore4(a, 0, la);
    vstore4(b, 0, lb);
    for (int i = 0; i < 4; ++i)
      if (lt[i] < t_max) { t_max = lt[i]; best = 4 * k + i; *t_hit = lt[i]; *a_hit = la[i]; *b_hit = lb[i]; }
  }
  return best;
}

bool any_quad(const scene_t* sc, float3 o, float3 D, float t_max) {
  const int groups = (sc->n_quads + 3) / 4;
  float4 t, a, b;
  for (int k = 0; k < groups; ++k)
    if (any(quad4_roots(sc->quad_groups[k], o, D, t_max, &t, &a, &b))) return true;
  return false;
}

// quad.hpp's intersect: the hit record of quad q at (t, a, b).
void quad_hit(const quad_t q, float t, float a, float b, hit_t* h) {
  const float3 u = q.u.xyz, v = q.v.xyz, Q = q.corner.xyz;
  h->t = t;
  h->p = Q + a * u + b * v;
  h->p_error = GAMMA(4) * (fabs(Q) + fabs(a * u) + fabs(b * v));
  h->normal = q.normal_area.xyz;
  h->material = q.material;
  h->light = q.light;
#ifdef HAS_SURFACE_UV
  h->uv = (float2)(a, b);
#endif
}
#endif

#ifdef HAS_PLANES
#ifdef HAS_SURFACE_UV
onb_t onb(float3 n);
#endif
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
    h->light = -1;  // an infinite plane is never sampled: hit only (lights.hpp)
#ifdef HAS_SURFACE_UV  // plane.hpp: along onb(N) from the plane's point
    const onb_t f = onb(N);
    h->uv = (float2)(dot(h->p - P0, f.t), dot(h->p - P0, f.b));
#endif
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
  r.sz = 1.0f / component(D, r.kz);
  r.sx = component(D, r.kx) * r.sz;
  r.sy = component(D, r.ky) * r.sz;
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
bool t_certainly_positive_in_double(float3 A, float3 B, float3 C, float3 O, float3 D) {
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

// Asked in float first (1 yes, 0 no, -1 don't know): triangle.hpp's t_positive_in_float.
int t_positive_in_float(float3 A, float3 B, float3 C, float3 O, float3 D) {
  const float3 e1 = B - A, e2 = C - A, w = A - O;
  const float3 n = (float3)(e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z, e1.x * e2.y - e1.y * e2.x);
  const float3 n_abs = (float3)(fabs(e1.y * e2.z) + fabs(e1.z * e2.y), fabs(e1.z * e2.x) + fabs(e1.x * e2.z),
                                fabs(e1.x * e2.y) + fabs(e1.y * e2.x));
  const float3 aw = fabs(w), ad = fabs(D);
  const float s = n.x * w.x + n.y * w.y + n.z * w.z;
  const float n_dot_d = n.x * D.x + n.y * D.y + n.z * D.z;
  const float scale = 0x1p32f, underflow = 0x1p-91f;  // 2^-123 at scale: flushed products too
  const float s_bound = (2.0f * GAMMA(10) * scale) * (n_abs.x * aw.x + n_abs.y * aw.y + n_abs.z * aw.z) +
                        underflow * (aw.x + aw.y + aw.z + 1.0f);
  const float d_bound = (2.0f * GAMMA(9) * scale) * (n_abs.x * ad.x + n_abs.y * ad.y + n_abs.z * ad.z) +
                        underflow * (ad.x + ad.y + ad.z + 1.0f);
  if (!(fabs(s) * scale > s_bound && fabs(n_dot_d) * scale > d_bound)) return -1;
  return (s > 0.0f) == (n_dot_d > 0.0f);
}

bool t_certainly_positive(float3 A, float3 B, float3 C, float3 O, float3 D) {
  const int sure = t_positive_in_float(A, B, C, O, D);
  return sure >= 0 ? sure == 1 : t_certainly_positive_in_double(A, B, C, O, D);
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
    h->light = tri->light;
#ifdef HAS_SURFACE_UV  // mesh.hpp's texcoord(): the vertices' (u, v) by barycentrics, or these
    if (sc->has_tri_uvs) {
      const float4 p = sc->tri_uvs[2 * best_leaf], q = sc->tri_uvs[2 * best_leaf + 1];
      h->uv = w * p.xy + bu * p.zw + bv * q.xy;
    } else {
      h->uv = (float2)(bu, bv);
    }
#endif
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
  float tq, a, b;
  const int q = nearest_quad(sc, o, D, t_max, &tq, &a, &b);
  if (q >= 0) { quad_hit(sc->quads[q], tq, a, b, h); found = true; t_max = tq; }
#endif
#ifdef HAS_TRIANGLES
  if (hit_bvh(sc, o, D, t_max, h)) found = true;
#endif
  if (found) h->front_face = dot(D, h->normal) < 0.0f;
#ifdef HAS_TEXTURES
  h->sc = sc;
#endif
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
  if (any_quad(sc, o, D, t_max)) return true;
#endif
#ifdef HAS_TRIANGLES
  if (hit_bvh(sc, o, D, t_max, 0)) return true;
#endif
  return false;
}
// [end]

// ---------------------------------------------------------------- small helpers (vec.hpp, sampling.hpp)
float3 normalize_or_zero(float3 v) {
  const float d = dot(v, v);
  if (d >= 0x1p-60f && d <= 0x1p60f) return v / sqrt(d);  // the common range: no scaling needed
  if (!(isfinite(v.x) && isfinite(v.y) && isfinite(v.z))) return (float3)(0.0f);
  const float m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
  if (!(m > 0.0f)) return (float3)(0.0f);
  const float3 s = v / m;
  return s / sqrt(dot(s, s));
}
bool is_black(float3 c) { return !any(c != (float3)(0.0f)); }
float3 reflect(float3 d, float3 n) { return d - 2.0f * dot(d, n) * n; }
float2 uniform2(stream_t* g) {
  const float a = uniform(g);
  return (float2)(a, uniform(g));
}

// onb.hpp's frame around a unit n (Duff et al.): local (x, y, z) to world and back.
onb_t onb(float3 n) {
  const float sign = copysign(1.0f, n.z);
  const float a = -1.0f / (sign + n.z);
  const float c = n.x * n.y * a;
  onb_t f;
  f.t = (float3)(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
  f.b = (float3)(c, sign + n.y * n.y * a, -n.y);
  f.n = n;
  return f;
}
float3 to_world(float3 n, float3 v) {
  const onb_t f = onb(n);
  return v.x * f.t + v.y * f.b + v.z * f.n;
}
float3 to_local(float3 n, float3 v) {
  const onb_t f = onb(n);
  return (float3)(dot(v, f.t), dot(v, f.b), dot(v, f.n));
}

float3 sample_cosine_hemisphere(float2 u) {
  const float u0 = clamp_unit(u.x), v = 2.0f * clamp_unit(u.y), s = sqrt(u0);
  const float sin_phi = sinpi(v), cos_phi = cospi(v);  // phi = pi v: see sample_cone
  return (float3)(s * cos_phi, s * sin_phi, sqrt(1.0f - u0));
}
float cosine_hemisphere_pdf(float cos_theta) { return cos_theta > 0.0f ? cos_theta / PI_F : 0.0f; }

// The cone of directions towards a sphere, in h = 1 - cos (sampling.hpp's cone_t).
float cone_one_minus_cos(float radius, float distance) {
  if (!(distance > radius)) return 2.0f;  // inside the sphere: it fills every direction
  const float s = radius / distance, sin2 = s * s;
  return fmax(sin2 / (1.0f + sqrt(1.0f - sin2)), FLT_MIN);
}
float3 cone_axis(float3 d) {
  const float3 a = normalize_or_zero(d);
  return is_black(a) ? (float3)(0.0f, 0.0f, 1.0f) : a;
}
float3 sample_cone(float2 u, float h_max) {
  const float h = clamp_unit(u.x) * h_max;
  // phi = 2 pi u.y = pi v: sinpi and cospi reduce v exactly and cheaply (PoCL's sin and cos of
  // phi spend their time reducing it; book 4.3), and keep the digits 2 pi's rounding would lose.
  const float s = sqrt(h * (2.0f - h)), v = 2.0f * clamp_unit(u.y);
  const float sin_phi = sinpi(v), cos_phi = cospi(v);
  return (float3)(s * cos_phi, s * sin_phi, 1.0f - h);
}
bool in_cone(float3 w, float h_max) {
  const float len2 = dot(w, w);
  if (!(len2 > 0.0f)) return false;
  const float c = w.z / sqrt(len2);
  const float h = c > 0.0f ? ((w.x * w.x + w.y * w.y) / len2) / (1.0f + c) : 1.0f - c;
  return h <= h_max;
}
float cone_pdf(float3 axis, float h_max, float3 w) {
  return in_cone(to_local(axis, w), h_max) ? 1.0f / (2.0f * PI_F * h_max) : 0.0f;
}
float area_to_solid_angle_pdf(float pdf_area, float distance2, float cos_light) {
  const float c = fabs(cos_light);
  return c > 0.0f ? pdf_area * distance2 / c : 0.0f;
}

// ---------------------------------------------------------------- materials (material.hpp, bxdf.hpp)
float3 facing(const hit_t* h) { return h->front_face ? h->normal : -h->normal; }

#ifdef HAS_CHECKER
// texture.hpp's checker: in uv (uv_space), or in world space with the axis nearest the normal dropped.
float3 checker(float3 a, float3 b, float cell, int uv_space, const hit_t* h) {
#ifdef HAS_UV_CHECKER
  if (uv_space) {  // a NaN or infinite coordinate reads as 0
    const float u = isfinite(h->uv.x) ? h->uv.x : 0.0f, v = isfinite(h->uv.y) ? h->uv.y : 0.0f;
    const float odd = fabs(fmod(floor(u / cell), 2.0f)) + fabs(fmod(floor(v / cell), 2.0f));  // no integer to overflow
    return odd == 1.0f ? b : a;
  }
#endif
  const float3 an = fabs(h->normal);
  const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  const float p[3] = {h->p.x, h->p.y, h->p.z};
  long sum = 0;
  for (int i = 0; i < 3; ++i)
    if (i != drop) sum += (long)floor(p[i] / cell);
  return (sum & 1) ? b : a;
}
#endif

#ifdef HAS_IMAGE_TEXTURES
// [listing cl-image-texture]
// texture.hpp's lookup_bilinear: texel (i, j)'s centre at u = (i + 1/2) / W, v = 1 - (j + 1/2) / H;
// outside [0, 1] the image repeats or its edge texels extend; a NaN or infinite coordinate reads as 0.
float3 texel(global const texture_t* t, global const float4* texels, float i, float j) {
  int x = (int)i, y = (int)j;
  const int w = t->width, h = t->height;
  if (t->repeat) x = ((x % w) + w) % w, y = ((y % h) + h) % h;
  else x = clamp(x, 0, w - 1), y = clamp(y, 0, h - 1);
  return texels[t->first + y * w + x].xyz;
}
float3 lookup_bilinear(global const texture_t* t, global const float4* texels, float2 uv) {
  float u = isfinite(uv.x) ? uv.x : 0.0f, v = isfinite(uv.y) ? uv.y : 0.0f;
  if (t->repeat) u -= floor(u), v -= floor(v);
  else u = clamp(u, -1.0f, 2.0f), v = clamp(v, -1.0f, 2.0f);
  const float x = u * (float)t->width - 0.5f, y = (1.0f - v) * (float)t->height - 0.5f;
  const float x0 = floor(x), y0 = floor(y), fx = x - x0, fy = y - y0;
  const float3 top = (1.0f - fx) * texel(t, texels, x0, y0) + fx * texel(t, texels, x0 + 1.0f, y0);
  const float3 bottom =
      (1.0f - fx) * texel(t, texels, x0, y0 + 1.0f) + fx * texel(t, texels, x0 + 1.0f, y0 + 1.0f);
  return (1.0f - fy) * top + fy * bottom;
}
// [end]
#endif

#ifdef HAS_NOISE_TEXTURES
// noise.hpp's improved Perlin noise, with its permutation packed from the CPU (gpu_scene.hpp).
float noise_gradient(int hash, float x, float y, float z) {
  const int h = hash & 15;
  const float u = h < 8 ? x : y, v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
  return ((h & 1) ? -u : u) + ((h & 2) ? -v : v);
}
float noise_fade(float t) { return t * t * t * (t * (t * 6.0f - 15.0f) + 10.0f); }
float perlin(global const int* p, float3 q) {
  const float fx = floor(q.x), fy = floor(q.y), fz = floor(q.z);
  if (!isfinite(fx + fy + fz)) return 0.0f;
  const int X = (int)(fmod(fx, 256.0f) + 256.0f) & 255, Y = (int)(fmod(fy, 256.0f) + 256.0f) & 255,
            Z = (int)(fmod(fz, 256.0f) + 256.0f) & 255;
  const float x = q.x - fx, y = q.y - fy, z = q.z - fz;
  const float u = noise_fade(x), v = noise_fade(y), w = noise_fade(z);
  const int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z;
  const int B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
  const float n =
      mix(mix(mix(noise_gradient(p[AA], x, y, z), noise_gradient(p[BA], x - 1.0f, y, z), u),
              mix(noise_gradient(p[AB], x, y - 1.0f, z), noise_gradient(p[BB], x - 1.0f, y - 1.0f, z), u), v),
          mix(mix(noise_gradient(p[AA + 1], x, y, z - 1.0f), noise_gradient(p[BA + 1], x - 1.0f, y, z - 1.0f), u),
              mix(noise_gradient(p[AB + 1], x, y - 1.0f, z - 1.0f),
                  noise_gradient(p[BB + 1], x - 1.0f, y - 1.0f, z - 1.0f), u), v),
          w);
  return clamp(n, -1.0f, 1.0f);
}
float turbulence(global const int* p, float3 q, int octaves) {
  float sum = 0.0f, weight = 1.0f, total = 0.0f;
  for (int i = 0; i < octaves; ++i) {
    sum += weight * fabs(perlin(p, q));
    total += weight;
    weight *= 0.5f;
    q *= 2.0f;
  }
  return total > 0.0f ? sum / total : 0.0f;
}
#endif

#ifdef HAS_TEXTURES
// texture.hpp's evaluate() for a texture record.
float3 texture_at(int i, const hit_t* h) {
  global const texture_t* t = &h->sc->textures[i];
#ifdef HAS_IMAGE_TEXTURES
  if (t->kind == TEX_IMAGE) return lookup_bilinear(t, h->sc->texels, h->uv);
#endif
#ifdef HAS_NOISE_TEXTURES
  if (t->kind == TEX_NOISE) {
    global const int* p = h->sc->noise_permutation;
    const float3 q = h->p * t->frequency;
    const float s = t->marble ? 0.5f * (1.0f + sin(q.z + 10.0f * turbulence(p, q, t->octaves)))
                    : t->octaves > 1 ? turbulence(p, q, t->octaves)
                                     : 0.5f * (1.0f + perlin(p, q));
    return (1.0f - s) * t->a.xyz + s * t->b.xyz;
  }
#endif
#ifdef HAS_CHECKER
  if (t->kind == TEX_CHECKER || t->kind == TEX_CHECKER_UV)
    return checker(t->a.xyz, t->b.xyz, t->cell, t->kind == TEX_CHECKER_UV, h);
#endif
  return t->a.xyz;
}
#endif

float3 albedo(global const material_t* m, const hit_t* h) {
#ifdef HAS_TEXTURES
  if (m->albedo_texture >= 0) return texture_at(m->albedo_texture, h);
#endif
#ifdef HAS_CHECKER
  if (m->checker) return checker(m->albedo_a.xyz, m->albedo_b.xyz, m->cell, m->checker == 2, h);
#endif
  return m->albedo_a.xyz;
}

// One-sided emitters shine from their front face only; any material may glow.
float3 emitted(global const material_t* m, const hit_t* h) {
  return h->front_face || m->two_sided ? m->radiance.xyz : (float3)(0.0f);
}
#ifdef HAS_MICROFACETS
bool is_microfacet(global const material_t* m) {
  return m->kind == KIND_ROUGH_CONDUCTOR || m->kind == KIND_ROUGH_DIELECTRIC;
}
#endif
bool has_density(global const material_t* m) {
#ifdef HAS_MICROFACETS
  if (is_microfacet(m)) return true;
#endif
  return m->kind == KIND_LAMBERTIAN || m->kind == KIND_PHONG;
}
bool same_hemisphere(float3 wi, float3 wo, float3 n) { return dot(wi, n) > 0.0f && dot(wo, n) > 0.0f; }

#ifdef HAS_PHONG
// bxdf.hpp's lambert_phong_brdf_t: kd/pi plus the normalised lobe ks (s+2)/(2 pi) cos^s(alpha),
// sampled as the mixture of the lobe (probability sum(ks) / sum(kd + ks)) and the cosine.
float glossy_probability(global const material_t* m) {
  const float d = m->albedo_a.x + m->albedo_a.y + m->albedo_a.z;
  const float g = m->albedo_b.x + m->albedo_b.y + m->albedo_b.z;
  return d + g > 0.0f ? g / (d + g) : 0.0f;
}
float3 phong_mirror(float3 wo, float3 n) { return reflect(-wo, n); }
float3 sample_phong_lobe(float2 u, float s) {
  const float e = log(1.0f - clamp_unit(u.x)) / (s + 1.0f);  // log(cos alpha)
  const float c = exp(e), h = -expm1(e);                      // cos(alpha), 1 - cos(alpha)
  const float sin_a = sqrt(h * (1.0f + c)), phi = 2.0f * PI_F * clamp_unit(u.y);
  return (float3)(sin_a * cos(phi), sin_a * sin(phi), c);
}
float phong_lobe_pdf(float cos_alpha, float s) {
  return cos_alpha > 0.0f ? (s + 1.0f) / (2.0f * PI_F) * pow(cos_alpha, s) : 0.0f;
}
#endif

#if defined(HAS_DIELECTRIC) || defined(HAS_ROUGH_DIELECTRIC)
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

#ifdef HAS_MICROFACETS
// [listing cl-ggx]
// microfacet.hpp's GGX (isotropic: ax = ay = alpha), in the local frame of the facing normal.
float ggx_D(float a, float3 h) {
  if (!(h.z > 0.0f)) return 0.0f;
  const float x = h.x / a, y = h.y / a, k = x * x + y * y + h.z * h.z;
  return 1.0f / (PI_F * a * a * k * k);
}
float ggx_lambda(float a, float3 w) {  // t / (2 (1 + sqrt(1 + t))): no cancellation at small t
  const float z2 = w.z * w.z, s2 = (a * w.x) * (a * w.x) + (a * w.y) * (a * w.y);
  if (!(z2 > 0.0f)) return INFINITY;
  const float t = s2 / z2;
  if (isinf(t)) return INFINITY;
  return t / (2.0f * (1.0f + sqrt(1.0f + t)));
}
float ggx_G1(float a, float3 w, float3 h) {
  if (!(dot(w, h) * w.z > 0.0f)) return 0.0f;
  return 1.0f / (1.0f + ggx_lambda(a, w));
}
float ggx_G2(float a, float3 wo, float3 wi, float3 h) {
  if (!(dot(wo, h) * wo.z > 0.0f) || !(dot(wi, h) * wi.z > 0.0f)) return 0.0f;
  return 1.0f / (1.0f + ggx_lambda(a, wo) + ggx_lambda(a, wi));
}
float g2_over_g1(float a, float3 wo, float3 wi) {
  const float li = ggx_lambda(a, wi);
  if (isinf(li)) return 0.0f;
  return 1.0f / (1.0f + li / (1.0f + ggx_lambda(a, wo)));
}
// A visible normal (Heitz 2018), as ggx_t::sample_visible.
float3 ggx_sample_visible(float a, float3 wo, float2 u) {
  const float3 v = normalize((float3)(a * wo.x, a * wo.y, fmax(wo.z, 0.0f)));
  const float len2 = v.x * v.x + v.y * v.y;
  const float3 t1 = len2 > 0.0f ? (float3)(-v.y, v.x, 0.0f) / sqrt(len2) : (float3)(1.0f, 0.0f, 0.0f);
  const float3 t2 = cross(v, t1);
  const float r = sqrt(clamp_unit(u.x)), phi = 2.0f * PI_F * clamp_unit(u.y);
  const float p1 = r * cos(phi), s = (1.0f + v.z) / 2.0f;
  const float p2 = (1.0f - s) * sqrt(fmax(0.0f, 1.0f - p1 * p1)) + s * (r * sin(phi));
  const float p3 = sqrt(fmax(0.0f, 1.0f - p1 * p1 - p2 * p2));
  const float3 n = p1 * t1 + p2 * t2 + p3 * v;
  return normalize((float3)(a * n.x, a * n.y, fmax(n.z, 0.0f)));
}
// [end]
// material.hpp's alpha_at: the number, or the roughness texture's mean, kept in [0.001, 1];
// then ggx_t's clamp to [1e-4, 1].
float alpha_at(global const material_t* m, const hit_t* h) {
  float a = m->roughness;
#ifdef HAS_TEXTURES
  if (m->roughness_texture >= 0) {
    const float3 c = texture_at(m->roughness_texture, h);
    a = clamp((c.x + c.y + c.z) / 3.0f, 1e-3f, 1.0f);
  }
#endif
  return clamp(a, 1e-4f, 1.0f);
}
#endif

#ifdef HAS_ROUGH_CONDUCTOR
// microfacet.hpp's fresnel_conductor for each channel, or Schlick from F0.
float3 fresnel_conductor(float cos_i, float3 eta, float3 k) {
  const float c = clamp(cos_i, 0.0f, 1.0f);
  if (!(c > 0.0f)) return (float3)(1.0f);  // grazing: every metal is a mirror
  const float c2 = c * c, s2 = (1.0f - c) * (1.0f + c);
  const float3 e2 = eta * eta, k2 = k * k, d = e2 - k2 - s2;
  const float3 a2b2 = sqrt(d * d + 4.0f * e2 * k2);
  const float3 a = sqrt(fmax(0.0f, (a2b2 + d) / 2.0f));
  const float3 rs = (a2b2 + c2 - 2.0f * a * c) / (a2b2 + c2 + 2.0f * a * c);
  const float3 q = c2 * a2b2 + s2 * s2, qa = 2.0f * a * c * s2;
  const float3 rp = rs * (q - qa) / (q + qa);
  return clamp((rs + rp) / 2.0f, 0.0f, 1.0f);
}
float3 conductor_fresnel(global const material_t* m, float cos_i) {
  if (m->schlick) {
    const float x = 1.0f - clamp(cos_i, 0.0f, 1.0f), x2 = x * x;
    return m->eta.xyz + (1.0f - m->eta.xyz) * (x2 * x2 * x);
  }
  return fresnel_conductor(cos_i, m->eta.xyz, m->k.xyz);
}
// [listing cl-rough-conductor]
// rough_conductor_t: f = F D G2 / (4 cos_o cos_i), sampled by visible normals (wo.z > 0).
float3 rough_conductor_f(global const material_t* m, float a, float3 wo, float3 wi) {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return (float3)(0.0f);
  const float3 h = normalize_or_zero(wo + wi);
  const float value = ggx_D(a, h) * ggx_G2(a, wo, wi, h) / (4.0f * wo.z * wi.z);
  return value > 0.0f ? conductor_fresnel(m, dot(wo, h)) * value : (float3)(0.0f);
}
float rough_conductor_pdf(float a, float3 wo, float3 wi) {
  if (!(wo.z > 0.0f) || !(wi.z > 0.0f)) return 0.0f;
  const float3 h = normalize_or_zero(wo + wi);
  return ggx_G1(a, wo, h) * ggx_D(a, h) / (4.0f * wo.z);
}
bool rough_conductor_sample(global const material_t* m, float a, float3 wo, float2 u, float3* wi,
                            float3* weight, float* pdf) {
  if (!(wo.z > 0.0f)) return false;
  const float3 h = ggx_sample_visible(a, wo, u);
  const float cos_oh = dot(wo, h);
  if (!(cos_oh > 0.0f)) return false;
  *wi = reflect(-wo, h);
  *pdf = ggx_G1(a, wo, h) * ggx_D(a, h) / (4.0f * wo.z);
  if (!(wi->z > 0.0f) || !(*pdf > 0.0f) || !isfinite(*pdf)) return false;  // below: lost
  *weight = conductor_fresnel(m, cos_oh) * g2_over_g1(a, wo, *wi);
  return true;
}
// [end]
#endif

#ifdef HAS_ROUGH_DIELECTRIC
// [listing cl-rough-dielectric]
// rough_dielectric_t (Walter et al. 2007); eta = eta_t / eta_i across the surface from wo's side.
float3 rough_half_vector(float eta, float3 wo, float3 wi) {
  const float3 h = normalize_or_zero(wi.z > 0.0f ? wo + wi : wo + eta * wi);
  return h.z < 0.0f ? -h : h;
}
float rough_dielectric_f(float a, float eta, float3 wo, float3 wi) {
  if (!(wo.z > 0.0f) || wi.z == 0.0f) return 0.0f;
  const float3 h = rough_half_vector(eta, wo, wi);
  const float co = dot(wo, h), ci = dot(wi, h);
  const float DG = ggx_D(a, h) * ggx_G2(a, wo, wi, h);
  if (!(DG > 0.0f)) return 0.0f;
  const float F = fresnel_dielectric(co, 1.0f / eta);
  if (wi.z > 0.0f) return F * DG / (4.0f * wo.z * wi.z);
  const float denom = co + eta * ci;
  return (1.0f - F) * DG * eta * eta * fabs(ci) * co / (wo.z * -wi.z * denom * denom);
}
float rough_dielectric_pdf(float a, float eta, float3 wo, float3 wi) {
  if (!(wo.z > 0.0f) || wi.z == 0.0f) return 0.0f;
  const float3 h = rough_half_vector(eta, wo, wi);
  const float co = dot(wo, h), ci = dot(wi, h);
  if (!(co > 0.0f) || !(ci * wi.z > 0.0f)) return 0.0f;  // h must face both directions
  const float visible = ggx_G1(a, wo, h) * ggx_D(a, h) / wo.z;
  const float F = fresnel_dielectric(co, 1.0f / eta);
  if (wi.z > 0.0f) return F * visible / 4.0f;
  const float denom = co + eta * ci;
  return (1.0f - F) * visible * co * eta * eta * fabs(ci) / (denom * denom);
}
bool rough_dielectric_sample(float a, float eta, float3 wo, float2 u, float u_lobe, float3* wi,
                             float3* weight, float* pdf) {
  if (!(wo.z > 0.0f)) return false;
  const float3 h = ggx_sample_visible(a, wo, u);
  const float co = dot(wo, h);
  if (!(co > 0.0f)) return false;
  const float F = fresnel_dielectric(co, 1.0f / eta);
  const float visible = ggx_G1(a, wo, h) * ggx_D(a, h) / wo.z;
  if (u_lobe < F) {
    *wi = reflect(-wo, h);
    if (!(wi->z > 0.0f)) return false;
    *pdf = F * visible / 4.0f;
  } else {
    if (!refract_dir(-wo, h, 1.0f / eta, wi) || !(wi->z < 0.0f)) return false;
    const float ci = dot(*wi, h), denom = co + eta * ci;
    *pdf = (1.0f - F) * visible * co * eta * eta * fabs(ci) / (denom * denom);
  }
  if (!(*pdf > 0.0f) || !isfinite(*pdf)) return false;
  *weight = (float3)(g2_over_g1(a, wo, *wi));
  return true;
}
// [end]
// material.hpp's rough_glass_at: eta_t / eta_i is the inside index entering, its inverse leaving.
float rough_eta(global const material_t* m, const hit_t* h) { return h->front_face ? m->ior : 1.0f / m->ior; }
#endif

#ifdef HAS_MICROFACETS
// material.hpp's microfacet_f_cos and microfacet_pdf, in the frame of the facing normal.
float3 microfacet_f_cos(global const material_t* m, const hit_t* h, float3 wo, float3 wi) {
  const float3 n = facing(h), lo = to_local(n, wo), li = to_local(n, wi);
  const float a = alpha_at(m, h);
#ifdef HAS_ROUGH_CONDUCTOR
  if (m->kind == KIND_ROUGH_CONDUCTOR) return rough_conductor_f(m, a, lo, li) * fabs(li.z);
#endif
#ifdef HAS_ROUGH_DIELECTRIC
  if (m->kind == KIND_ROUGH_DIELECTRIC)
    return (float3)(rough_dielectric_f(a, rough_eta(m, h), lo, li) * fabs(li.z));
#endif
  return (float3)(0.0f);
}
float microfacet_pdf(global const material_t* m, const hit_t* h, float3 wo, float3 wi) {
  const float3 n = facing(h), lo = to_local(n, wo), li = to_local(n, wi);
  const float a = alpha_at(m, h);
#ifdef HAS_ROUGH_CONDUCTOR
  if (m->kind == KIND_ROUGH_CONDUCTOR) return rough_conductor_pdf(a, lo, li);
#endif
#ifdef HAS_ROUGH_DIELECTRIC
  if (m->kind == KIND_ROUGH_DIELECTRIC) return rough_dielectric_pdf(a, rough_eta(m, h), lo, li);
#endif
  return 0.0f;
}
#endif

// material.hpp's brdf_at(...).eval: f(wo, wi), zero for the materials without a density.
float3 brdf(global const material_t* m, const hit_t* h, float3 wo, float3 wi) {
  const float3 n = facing(h);
  if (!same_hemisphere(wi, wo, n)) return (float3)(0.0f);
#ifdef HAS_PHONG
  if (m->kind == KIND_PHONG) {
    const float s = m->shininess;
    const float c = clamp(dot(wi, phong_mirror(wo, n)), 0.0f, 1.0f);
    return m->albedo_a.xyz / PI_F + m->albedo_b.xyz * ((s + 2.0f) / (2.0f * PI_F) * pow(c, s));
  }
#endif
  if (m->kind == KIND_LAMBERTIAN) return albedo(m, h) / PI_F;
  return (float3)(0.0f);
}
// [listing cl-brdf-cos]
float3 brdf_cos(global const material_t* m, const hit_t* h, float3 wo, float3 wi) {
#ifdef HAS_MICROFACETS
  if (is_microfacet(m)) return microfacet_f_cos(m, h, wo, wi);  // glass: wi may be below
#endif
  return brdf(m, h, wo, wi) * fmax(0.0f, dot(facing(h), wi));
}
// The density scatter() samples wi with (the mixture's; Lambert: the lobe's weight is 0).
float scatter_pdf(global const material_t* m, const hit_t* h, float3 wo, float3 wi) {
  if (!has_density(m)) return 0.0f;
#ifdef HAS_MICROFACETS
  if (is_microfacet(m)) return microfacet_pdf(m, h, wo, wi);
#endif
  const float3 n = facing(h);
  if (!same_hemisphere(wi, wo, n)) return 0.0f;
  float w_lobe = 0.0f, lobe = 0.0f;
#ifdef HAS_PHONG
  if (m->kind == KIND_PHONG) {
    w_lobe = glossy_probability(m);
    lobe = phong_lobe_pdf(fmin(dot(wi, phong_mirror(wo, n)), 1.0f), m->shininess);
  }
#endif
  return w_lobe * lobe + (1.0f - w_lobe) * cosine_hemisphere_pdf(dot(wi, n));
}
// [end]


typedef struct {
  float3 direction;  // unit, away from the surface
  float3 weight;     // f |cos| / pdf
  float pdf;         // density of direction; 0 for specular
  bool specular;
} scatter_t;

// material.hpp's scatter(): false when absorbed (or a light, which does not reflect).
// [listing cl-scatter]
bool scatter(global const material_t* m, float3 d, const hit_t* h, stream_t* g, scatter_t* s) {
  const float3 n = facing(h);  // on the side the ray came from
  if (m->kind == KIND_EMITTER) return false;
  if (has_density(m)) {
    // Three numbers, two for the direction and one for a lobe, whether used or not: the
    // path's later numbers do not depend on the material it met (material.hpp).
    const float2 u = uniform2(g);
    const float u_lobe = uniform(g);
    (void)u_lobe;
    s->specular = false;
    if (m->kind == KIND_LAMBERTIAN) {  // cosine-weighted: f cos / pdf = albedo exactly
      if (!(dot(-d, n) > 0.0f)) return false;  // grazing
      s->direction = to_world(n, sample_cosine_hemisphere(u));
      s->pdf = cosine_hemisphere_pdf(dot(s->direction, n));
      if (!(s->pdf > 0.0f)) return false;  // rounding put it on the horizon
      s->weight = albedo(m, h);
      return true;
    }
#ifdef HAS_MICROFACETS
    if (is_microfacet(m)) {  // a visible GGX normal (u); the glass picks its lobe with u_lobe
      const float3 wo = to_local(n, -d);
      const float a = alpha_at(m, h);
      float3 wi = (float3)(0.0f);
      bool ok = false;
#ifdef HAS_ROUGH_CONDUCTOR
      if (m->kind == KIND_ROUGH_CONDUCTOR) ok = rough_conductor_sample(m, a, wo, u, &wi, &s->weight, &s->pdf);
#endif
#ifdef HAS_ROUGH_DIELECTRIC
      if (m->kind == KIND_ROUGH_DIELECTRIC)
        ok = rough_dielectric_sample(a, rough_eta(m, h), wo, u, u_lobe, &wi, &s->weight, &s->pdf);
#endif
      if (!ok) return false;  // sent below the surface by a facet: absorbed
      s->direction = to_world(n, wi);
      return true;
    }
#endif
#ifdef HAS_PHONG
    // phong: Lambert + normalised Phong, sampled as their mixture (u.x chooses, then is reused)
    const float3 wo = -d;
    if (!(dot(wo, n) > 0.0f)) return false;
    const float w_lobe = glossy_probability(m), u0 = clamp_unit(u.x);
    if (u0 < w_lobe)
      s->direction = to_world(phong_mirror(wo, n), sample_phong_lobe((float2)(u0 / w_lobe, u.y), m->shininess));
    else
      s->direction = to_world(n, sample_cosine_hemisphere((float2)((u0 - w_lobe) / (1.0f - w_lobe), u.y)));
    const float cos_i = dot(s->direction, n);
    s->pdf = scatter_pdf(m, h, wo, s->direction);
    if (!(cos_i > 0.0f) || !(s->pdf > 0.0f)) return false;  // sampled below the surface: absorbed
    s->weight = brdf(m, h, wo, s->direction) * (cos_i / s->pdf);
    return true;
#else
    return false;
#endif
  }
  s->pdf = 0.0f;
  s->specular = true;
#ifdef HAS_METAL
  if (m->kind == KIND_METAL) {  // mirror direction plus fuzz times a point in the unit ball
    const float u0 = uniform(g), u1 = uniform(g), u2 = uniform(g);
    const float z = 1.0f - 2.0f * clamp_unit(u0), sn = 2.0f * sqrt(clamp_unit(u0) * (1.0f - clamp_unit(u0)));
    const float phi = 2.0f * PI_F * clamp_unit(u1);
    const float3 ball = cbrt(clamp_unit(u2)) * (float3)(sn * cos(phi), sn * sin(phi), z);
    s->direction = normalize_or_zero(reflect(d, n) + m->fuzz * ball);
    if (!(dot(s->direction, n) > 0.0f)) return false;  // pushed below the surface: absorbed
    s->weight = albedo(m, h);
    return true;
  }
#endif
#ifdef HAS_DIELECTRIC
  if (m->kind == KIND_DIELECTRIC) {  // reflect with probability R (exact Fresnel), else refract
    const float eta = h->front_face ? 1.0f / m->ior : m->ior;
    float3 t;
    if (refract_dir(d, n, eta, &t) && uniform(g) >= fresnel_dielectric(-dot(d, n), eta)) s->direction = t;
    else s->direction = reflect(d, n);
    s->weight = (float3)(1.0f);
    return true;
  }
#endif
  return false;
}
// [end]

// ---------------------------------------------------------------- the environment (environment.hpp)
#ifdef HAS_ENVIRONMENT
// [listing cl-environment]
// The map's frame turns by the rotation about +y; (u, v) = (phi / 2 pi, theta / pi) as to_uv().
float3 env_to_local(const environment_t* e, float3 w) {
  const float c = e->cos_rotation, s = e->sin_rotation;
  return (float3)(c * w.x - s * w.z, w.y, s * w.x + c * w.z);
}
float3 env_to_world(const environment_t* e, float3 l) {
  const float c = e->cos_rotation, s = e->sin_rotation;
  return (float3)(c * l.x + s * l.z, l.y, -s * l.x + c * l.z);
}
float2 env_uv(float3 l) {
  float phi = atan2(l.x, -l.z);
  if (phi < 0.0f) phi += 2.0f * PI_F;
  const float theta = atan2(hypot(l.x, l.z), l.y);  // hypot: no underflow of a tiny sin
  return (float2)(fmin(phi / (2.0f * PI_F), 1.0f), fmin(theta / PI_F, 1.0f));
}
// The radiance seen looking along w: bilinear, wrapping in phi, clamped at the poles.
float3 env_radiance(const scene_t* sc, float3 w) {
  const environment_t e = *sc->env;
  if (e.is_constant) return e.radiance.xyz;
  const float2 uv = env_uv(env_to_local(&e, w));
  const float x = uv.x * (float)e.width - 0.5f, y = uv.y * (float)e.height - 0.5f;
  const float fx = floor(x), fy = floor(y), tx = x - fx, ty = y - fy;
  const int x0 = (((int)fx % e.width) + e.width) % e.width, x1 = (x0 + 1) % e.width;
  const int y0 = clamp((int)fy, 0, e.height - 1), y1 = clamp((int)fy + 1, 0, e.height - 1);
  global const float4* t = sc->texels + e.first;
  const float3 top = (1.0f - tx) * t[y0 * e.width + x0].xyz + tx * t[y0 * e.width + x1].xyz;
  const float3 bottom = (1.0f - tx) * t[y1 * e.width + x0].xyz + tx * t[y1 * e.width + x1].xyz;
  return (1.0f - ty) * top + ty * bottom;
}

// distribution_1d::sample on the packed bins f[n] and cdf[n + 1] (gpu_scene.hpp's env_tables).
float sample_1d(global const float* f, global const float* cdf, float total, int n, float u, float* pdf,
                int* bin) {
  const float target = clamp_unit(u) * total;
  int lo = 0, hi = n + 1;  // upper_bound: the first entry of the CDF above target
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (cdf[mid] > target) hi = mid;
    else lo = mid + 1;
  }
  int i = clamp(lo - 1, 0, n - 1);
  while (f[i] == 0.0f && i > 0) --i;  // target rounded to the total: back to the last weighted bin
  const float t = f[i] > 0.0f ? clamp((target - cdf[i]) / f[i], 0.0f, 1.0f) : 0.0f;
  *bin = i;
  *pdf = f[i] * (float)n / total;
  return fmin(((float)i + t) / (float)n, 0x1.fffffep-1f);
}
// The tables: the marginal's bins [H] and CDF [H + 1], each row's total [H], the rows' bins
// [H][W] and CDFs [H][W + 1].
#define ENV_MARGINAL_F(e, T) (T)
#define ENV_MARGINAL_CDF(e, T) ((T) + (e).height)
#define ENV_ROW_TOTAL(e, T) ((T) + 2 * (e).height + 1)
#define ENV_ROW_F(e, T, v) ((T) + 3 * (e).height + 1 + (v) * (e).width)
#define ENV_ROW_CDF(e, T, v) ((T) + 3 * (e).height + 1 + (e).height * (e).width + (v) * ((e).width + 1))

// environment_map::sample: a direction with density pdf per steradian (0: none).
float3 env_sample(const scene_t* sc, float2 u, float* pdf) {
  const environment_t e = *sc->env;
  if (e.is_constant) {  // uniform over the sphere
    const float u0 = clamp_unit(u.x), z = 1.0f - 2.0f * u0, s = 2.0f * sqrt(u0 * (1.0f - u0));
    const float phi = 2.0f * PI_F * clamp_unit(u.y);
    *pdf = 1.0f / (4.0f * PI_F);
    return (float3)(s * cos(phi), s * sin(phi), z);
  }
  global const float* T = sc->env_tables;
  float pv = 0.0f, pu = 0.0f;
  int row = 0, col = 0;
  const float v =
      sample_1d(ENV_MARGINAL_F(e, T), ENV_MARGINAL_CDF(e, T), e.marginal_total, e.height, u.y, &pv, &row);
  const float x = sample_1d(ENV_ROW_F(e, T, row), ENV_ROW_CDF(e, T, row), ENV_ROW_TOTAL(e, T)[row], e.width, u.x,
                            &pu, &col);
  // sinpi(v) = sin(pi v) without pi's rounding in float: next to a pole sin(PI_F v) would be
  // off by 1e-7 absolute, which is tens of per cent of the density there.
  const float sin_theta = sinpi(v), p_uv = pv * pu;
  if (!(sin_theta > 0.0f) || !(p_uv > 0.0f)) {
    *pdf = 0.0f;
    return (float3)(0.0f);
  }
  *pdf = p_uv / (2.0f * PI_F * PI_F * sin_theta);
  return env_to_world(&e, (float3)(sinpi(2.0f * x) * sin_theta, cospi(v), -cospi(2.0f * x) * sin_theta));
}
// environment_map::pdf: the density of env_sample for direction w.
float env_pdf(const scene_t* sc, float3 w) {
  const environment_t e = *sc->env;
  if (e.is_constant) return 1.0f / (4.0f * PI_F);
  const float3 l = env_to_local(&e, w);
  const float sin_theta = hypot(l.x, l.z);
  if (!(sin_theta > 0.0f)) return 0.0f;
  const float2 uv = env_uv(l);
  global const float* T = sc->env_tables;
  const int row = min((int)(uv.y * (float)e.height), e.height - 1);
  const int col = min((int)(uv.x * (float)e.width), e.width - 1);
  const float p_v = ENV_MARGINAL_F(e, T)[row] * (float)e.height / e.marginal_total;
  const float p_u = ENV_ROW_F(e, T, row)[col] * (float)e.width / ENV_ROW_TOTAL(e, T)[row];
  return p_v * p_u / (2.0f * PI_F * PI_F * sin_theta);
}
// [end]
#endif

// ---------------------------------------------------------------- lights (lights.hpp)
typedef struct {
  float3 wi;        // unit, towards the light
  float pdf;        // per steradian (a point light: 1), times the choice of the light
  float3 Le;        // arriving from the light
  bool delta;       // a point light
  float3 origin, direction;  // the shadow segment (0, t_max)
  float t_max;
} light_sample_t;

// spawn.hpp's spawn_segment: from the hit towards target, stopped short by target's rounding.
void spawn_segment(const hit_t* h, float3 target, light_sample_t* s) {
  s->origin = offset_origin(h->p, h->p_error, h->normal, target - h->p);
  const float3 d = target - s->origin;
  s->direction = normalize_or_zero(d);
  s->t_max = sqrt(dot(d, d)) * (1.0f - GAMMA(16));
}

// [listing cl-sample-one-light]
// A point on light i, seen from hit h; pdf without the choice of the light.
bool sample_one(const scene_t* sc, int i, const hit_t* h, float2 u, light_sample_t* s) {
  global const light_t* l = &sc->lights[i];
#ifdef HAS_POINT_LIGHTS
  if (l->kind == LIGHT_POINT) {  // one direction; its "density" is a delta, reported as 1
    const float3 to = l->position.xyz - h->p;
    s->wi = normalize_or_zero(to);
    s->pdf = 1.0f;
    s->Le = l->intensity.xyz / dot(to, to);
    s->delta = true;
    spawn_segment(h, l->position.xyz, s);
    return !is_black(s->wi) && isfinite(s->Le.x) && isfinite(s->Le.y) && isfinite(s->Le.z);
  }
#endif
  s->delta = false;
#ifdef HAS_ENVIRONMENT
  if (l->kind == LIGHT_ENVIRONMENT) {  // sample_environment: the shadow ray never ends
    s->wi = env_sample(sc, u, &s->pdf);
    if (!(s->pdf > 0.0f) || !isfinite(s->pdf)) return false;
    s->Le = env_radiance(sc, s->wi);
    s->origin = offset_origin(h->p, h->p_error, h->normal, s->wi);
    s->direction = s->wi;
    s->t_max = INFINITY;
    return true;
  }
#endif
  global const material_t* m = &sc->materials[l->material];
  hit_t lh;  // the light's surface at the sampled point: its side decides what it emits
#ifdef HAS_SPHERE_LIGHTS
  if (l->kind == LIGHT_SPHERE) {
    const sphere_t sp = sc->spheres[l->object];
    const float3 axis = cone_axis(sp.center_radius.xyz - h->p);  // every direction from inside
    const float h_max = cone_one_minus_cos(sp.center_radius.w, length(sp.center_radius.xyz - h->p));
    s->wi = to_world(axis, sample_cone(u, h_max));
    const float3 o = offset_origin(h->p, h->p_error, h->normal, s->wi);
    if (!hit_sphere(sp, o, s->wi, INFINITY, &lh)) return false;
    lh.front_face = dot(s->wi, lh.normal) < 0.0f;
    // The shadow ray is the ray that found the point, stopped just short of it.
    s->origin = o;
    s->direction = s->wi;
    s->t_max = lh.t * (1.0f - GAMMA(16));
    s->pdf = cone_pdf(axis, h_max, s->wi);
  } else
#endif
  {  // uniform in area, p_A = 1/A, turned into solid angle
    float3 p = (float3)(0.0f), n = (float3)(0.0f), p_error = (float3)(0.0f);
#ifdef HAS_QUAD_LIGHTS
    if (l->kind == LIGHT_QUAD) {
      const quad_t q = sc->quads[l->object];
      const float a = clamp_unit(u.x), b = clamp_unit(u.y);
      p = q.corner.xyz + a * q.u.xyz + b * q.v.xyz;
      n = q.normal_area.xyz;
      p_error = GAMMA(4) * (fabs(q.corner.xyz) + fabs(a * q.u.xyz) + fabs(b * q.v.xyz));
    }
#endif
#ifdef HAS_TRIANGLE_LIGHTS
    if (l->kind == LIGHT_TRIANGLES) {  // a triangle by area (u.x picks it, then is stretched), then uniform on it
      global const light_triangle_t* c = &sc->light_tris[l->first];
      const float x = clamp_unit(u.x) * c[l->count - 1].b.w;
      uint lo = 0, hi = l->count;  // upper_bound on the triangles' ends
      while (lo < hi) {
        const uint mid = (lo + hi) / 2;
        if (c[mid].b.w > x) hi = mid;
        else lo = mid + 1;
      }
      const uint k = min(lo, l->count - 1);
      const float width = c[k].b.w - c[k].a.w;
      const float ux = width > 0.0f ? clamp_unit((x - c[k].a.w) / width) : 0.0f;
      const float sq = sqrt(clamp_unit(ux)), b1 = clamp_unit(u.y) * sq, b2 = sq - b1, w = 1.0f - b1 - b2;
      const float3 A = c[k].a.xyz, B = c[k].b.xyz, C = c[k].c.xyz;
      p = w * A + b1 * B + b2 * C;
      n = normalize_or_zero(cross(B - A, C - A));
      // Triangles are tested in float (the BVH): their hits are as uncertain as hit_bvh's.
      p_error = GAMMA(64) * (fabs(w * A) + fabs(b1 * B) + fabs(b2 * C));
    }
#endif
    const float3 to = p - h->p;
    s->wi = normalize_or_zero(to);
    lh.normal = n;
    lh.front_face = dot(s->wi, n) < 0.0f;
    const float cos_l = fabs(dot(n, s->wi));
    s->pdf = area_to_solid_angle_pdf(1.0f / l->area, dot(to, to), cos_l);
    spawn_segment(h, p, s);
    // Stop short of the light's own surface by its rounding too, measured along the ray.
    s->t_max -= dot(fabs(n), p_error) / fmax(cos_l, 1e-30f);
  }
  s->Le = emitted(m, &lh);
  return s->pdf > 0.0f && isfinite(s->pdf) && !is_black(s->wi);
}
// [end]

// [listing cl-sample-light]
// One light chosen by u_select from the selection CDF (by power or uniformly, as packed), one
// point on it by u. pdf includes the choice.
bool sample_light(const scene_t* sc, const hit_t* h, float u_select, float2 u, light_sample_t* s) {
  const int n = sc->n_lights;
  if (n == 0) return false;
  const float x = clamp_unit(u_select) * sc->lights[n - 1].cdf;
  int lo = 0, hi = n;  // upper_bound: the first light whose CDF exceeds x
  while (lo < hi) {
    const int mid = (lo + hi) / 2;
    if (sc->lights[mid].cdf > x) hi = mid;
    else lo = mid + 1;
  }
  const int i = min(lo, n - 1);
  if (!sample_one(sc, i, h, u, s)) return false;
  s->pdf *= sc->lights[i].pdf;
  return s->pdf > 0.0f && isfinite(s->pdf);
}
// [end]

// [listing cl-light-pdf]
// The density with which sample_light() produces wi from x, given that the ray along wi first
// meets light i at lh (a BSDF-sampled ray that found a light).
float light_pdf(const scene_t* sc, int i, float3 x, float3 wi, const hit_t* lh) {
  global const light_t* l = &sc->lights[i];
#ifdef HAS_SPHERE_LIGHTS
  if (l->kind == LIGHT_SPHERE) {
    const float4 cr = sc->spheres[l->object].center_radius;
    return cone_pdf(cone_axis(cr.xyz - x), cone_one_minus_cos(cr.w, length(cr.xyz - x)), wi) * l->pdf;
  }
#endif
  return area_to_solid_angle_pdf(1.0f / l->area, lh->t * lh->t, dot(lh->normal, wi)) * l->pdf;
}
// [end]

// ---------------------------------------------------------------- the path (path.hpp)
// The power heuristic (exponent 2) for a sample of density a, the other technique's being b.
float power_heuristic(float a, float b) {
  if (!(a > 0.0f)) return 0.0f;
  if (isinf(a)) return 1.0f;
  const float r = b / a;
  return 1.0f / (1.0f + r * r);
}

// [listing cl-roulette]
// Russian roulette: true if the path goes on (then beta has been divided by q).
bool survives_roulette(float3* beta, int bounce, stream_t* g) {
  if (bounce < RR_DEPTH) return true;
  const float q = fmin(1.0f, fmax(beta->x, fmax(beta->y, beta->z)));
  if (!(uniform(g) < q)) return false;
  *beta /= q;
  return true;
}
// [end]

// The algorithm is a build option: -DMETHOD_NAIVE, -DMETHOD_NEE or -DMETHOD_MIS (path.hpp's
// path_options::method). The constants below fold away the code a method does not run.
#if defined(METHOD_MIS)
#define NEE_ON true
#define MIS_ON true
#elif defined(METHOD_NEE)
#define NEE_ON true
#define MIS_ON false
#elif defined(METHOD_NAIVE)
#define NEE_ON false
#define MIS_ON false
#else
#error "build with -DMETHOD_NAIVE, -DMETHOD_NEE or -DMETHOD_MIS (gpu_scene.hpp's build_options)"
#endif

// [listing cl-next-event]
// The next event at hit h, whose material m has a density: a point on a light (u_select, u)
// and what it adds if its shadow segment (e's) is clear, f_cos e.Le times w_over_pdf, still to
// be weighted by the path's beta. False when it adds nothing. Shared by both loops.
bool next_event(const scene_t* sc, global const material_t* m, const hit_t* h, float3 wo, float u_select, float2 u,
                light_sample_t* e, float3* f_cos, float* w_over_pdf) {
  if (!sample_light(sc, h, u_select, u, e) || is_black(e->Le)) return false;
  *f_cos = brdf_cos(m, h, wo, e->wi);
  if (is_black(*f_cos)) return false;
  const float w = MIS_ON && !e->delta ? power_heuristic(e->pdf, scatter_pdf(m, h, wo, e->wi)) : 1.0f;
  *w_over_pdf = w / e->pdf;
  return true;
}
// [end]

// [listing cl-path]
float3 path_radiance(const scene_t* sc, float3 o, float3 D, stream_t* g) {
  const bool nee = NEE_ON, mis = MIS_ON;
  float3 L = (float3)(0.0f), beta = (float3)(1.0f);
  bool specular = true;    // the last bounce had no density (camera rays count as specular)
  float bsdf_pdf = 0.0f;   // the density of the last scattered direction
  float3 from = (float3)(0.0f);  // the point it left from
  for (int bounce = 0;; ++bounce) {
    hit_t h;
    if (!nearest_hit(sc, o, D, &h)) {
#ifdef HAS_ENVIRONMENT
      if (sc->env->present) {  // the environment light, found by this ray: as emission below
        const float3 Le = env_radiance(sc, D);
        const int li = sc->env->light;
        if (!nee || specular || li < 0) return L + beta * Le;
        if (mis) return L + beta * Le * power_heuristic(bsdf_pdf, env_pdf(sc, D) * sc->lights[li].pdf);
        return L;
      }
#endif
      return L + beta * sc->background;  // no sampler knows a plain background
    }
    global const material_t* m = &sc->materials[h.material];
#ifdef HAS_EMITTERS
    // Emission found by this ray: all of it, its MIS share, or none (nee: the light sample at
    // the previous hit counted this light already).
    const float3 Le = emitted(m, &h);
    if (!is_black(Le)) {
      if (!nee || specular || h.light < 0) L += beta * Le;
      else if (mis) L += beta * Le * power_heuristic(bsdf_pdf, light_pdf(sc, h.light, from, D, &h));
    }
#endif
    if (bounce == MAX_DEPTH) return L;
    const float3 wo = -D;
    if (nee && has_density(m)) {  // the next event: a point on a light
      const float u_select = uniform(g);
      const float2 u = uniform2(g);
      light_sample_t e;
      float3 f_cos;
      float w_over_pdf;
      if (next_event(sc, m, &h, wo, u_select, u, &e, &f_cos, &w_over_pdf) && !occluded(sc, e.origin, e.direction, e.t_max))
        L += beta * f_cos * e.Le * w_over_pdf;
    }
    scatter_t s;
    if (!scatter(m, D, &h, g, &s)) return L;  // absorbed (or a light, which does not reflect)
    beta *= s.weight;  // f cos / pdf: the cosine is counted once, inside the weight
    specular = s.specular;
    bsdf_pdf = s.pdf;
    from = h.p;
    if (!survives_roulette(&beta, bounce, g)) return L;
    o = offset_origin(h.p, h.p_error, h.normal, s.direction);
    D = s.direction;
  }
}
// [end]

// [listing cl-srgb]
// image_io.hpp's to_byte, as the number of its steps (srgb_byte_steps) at or below c: a binary
// search in eight comparisons instead of a pow. NaN passes no step: 0, as in to_byte.
uchar srgb_byte(float c, global const float* steps) {
  uint b = 0;
  for (uint jump = 128; jump > 0; jump >>= 1) b += c >= steps[b + jump] ? jump : 0;
  return (uchar)b;
}
// [end]

#ifdef PATH_LANES
// ---------------------------------------------------------------- eight paths in SIMD lanes
// PoCL runs one work item at a time on a core and does not put several of them in SIMD lanes
// (the path loop branches), so the loop above uses SIMD only inside a test. Here one work item
// follows eight paths, one per lane of float8 arithmetic: pixels x0 .. x0 + 7 of a row, each
// lane its pixel's samples in order. Every line is the loop's line above for eight paths at once;
// where their paths differ (glass or a wall, a light sample or none), masks choose each lane's
// result. Built instead of the loop above when the scene has only what these lines cover
// (gpu_scene.hpp's lanes_cover): spheres, quads, Lambert (solid or a world-space checker),
// glass, emitters, quad lights and sphere lights. What only some lanes need and the one-path
// loop already has (a checker's albedo, a point on a sphere light and its density) is that
// loop's own function called lane by lane (lane_hit), not a second copy.
#if defined(HAS_PLANES) || defined(HAS_TRIANGLES) || defined(HAS_METAL) || defined(HAS_PHONG) || \
    defined(HAS_UV_CHECKER) || defined(HAS_MICROFACETS) || defined(HAS_TEXTURES) || defined(HAS_ENVIRONMENT) || \
    defined(HAS_TRIANGLE_LIGHTS) || defined(HAS_POINT_LIGHTS) || defined(WEAK_SEED)
#error "PATH_LANES covers spheres, quads, Lambert, glass, emitters, quad and sphere lights only (gpu_scene.hpp's lanes_cover)"
#endif
#if PATH_LANES != 8
#error "the lanes are float8: build with -DPATH_LANES=8 (gpu_scene.hpp's gpu_path_lanes)"
#endif
#define LANES PATH_LANES
typedef int8 mask8;  // -1 in the lanes where a condition holds
typedef struct { float8 x, y, z; } vec8;  // eight float3, one per lane

vec8 vec8_of(float8 x, float8 y, float8 z) { vec8 r; r.x = x; r.y = y; r.z = z; return r; }
vec8 splat8(float3 a) { return vec8_of((float8)(a.x), (float8)(a.y), (float8)(a.z)); }
vec8 add8(vec8 a, vec8 b) { return vec8_of(a.x + b.x, a.y + b.y, a.z + b.z); }
vec8 sub8(vec8 a, vec8 b) { return vec8_of(a.x - b.x, a.y - b.y, a.z - b.z); }
vec8 mul8(vec8 a, vec8 b) { return vec8_of(a.x * b.x, a.y * b.y, a.z * b.z); }
vec8 scale8(vec8 a, float8 s) { return vec8_of(a.x * s, a.y * s, a.z * s); }
vec8 div8(vec8 a, float8 s) { return vec8_of(a.x / s, a.y / s, a.z / s); }
vec8 neg8(vec8 a) { return vec8_of(-a.x, -a.y, -a.z); }
vec8 abs8(vec8 a) { return vec8_of(fabs(a.x), fabs(a.y), fabs(a.z)); }
#pragma OPENCL FP_CONTRACT OFF
float8 dot8(vec8 a, vec8 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }  // unfused: glm::dot's rounding
#pragma OPENCL FP_CONTRACT ON
vec8 pick8(vec8 a, vec8 b, mask8 m) { return vec8_of(select(a.x, b.x, m), select(a.y, b.y, m), select(a.z, b.z, m)); }
mask8 nonzero8(vec8 a) { return (a.x != 0.0f) | (a.y != 0.0f) | (a.z != 0.0f); }
mask8 finite8(vec8 a) { return isfinite(a.x) & isfinite(a.y) & isfinite(a.z); }

// normalize_or_zero, lane by lane (the rescaled branch only when some lane needs it)
vec8 normalize_or_zero8(vec8 v) {
  const float8 d = dot8(v, v);
  const mask8 common = (d >= 0x1p-60f) & (d <= 0x1p60f);
  const vec8 r = div8(v, sqrt(d));
  if (all(common)) return r;
  const float8 m = fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z)));
  const vec8 s = div8(v, m);
  const vec8 rescaled = pick8(splat8((float3)(0.0f)), div8(s, sqrt(dot8(s, s))), finite8(v) & (m > 0.0f));
  return pick8(rescaled, r, common);
}

// rng.cl's stream in lanes: each lane its own (pixel, sample) key and its own count of draws.
typedef struct { uint8 key_pixel, key_sample, dimension; } stream8_t;
uint8 pcg_hash8(uint8 v) {
  const uint8 state = v * 747796405u + 2891336453u;
  const uint8 word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}
// uniform() in the lanes of m; the others' streams do not move.
float8 uniform8(stream8_t* r, mask8 m) {
  const uint8 h = r->key_sample;
  const uint8 word = pcg_hash8(h ^ (r->dimension + 0x9e3779b9u + (h << 6) + (h >> 2)));
  const uint8 hi = pcg_hash8(r->key_pixel ^ word);
  r->dimension += select((uint8)(0u), (uint8)(2u), as_uint8(m));  // two words a number, as uniform()
  return convert_float8(hi >> 8) * 0x1p-24f;
}

float8 clamp_unit8(float8 u) { return clamp(u, 0.0f, 0x1.fffffep-1f); }
float8 nudge8(float8 x, float8 off) {
  return select(select(x, nextafter(x, (float8)(-INFINITY)), off < 0.0f), nextafter(x, (float8)(INFINITY)), off > 0.0f);
}
vec8 offset_origin8(vec8 p, vec8 p_error, vec8 n, vec8 w) {
  const float8 d = dot8(abs8(n), p_error);
  vec8 off = scale8(n, d);
  off = pick8(off, neg8(off), dot8(w, n) < 0.0f);
  const vec8 po = add8(p, off);
  return vec8_of(nudge8(po.x, off.x), nudge8(po.y, off.y), nudge8(po.z, off.z));
}

#ifdef HAS_QUADS
#pragma OPENCL FP_CONTRACT OFF
// [listing cl-quad8]
// The same lines for quad j of group g (its numbers the same in every lane) and eight rays.
mask8 quad8_roots(global const quad4_t* g, int j, vec8 o, vec8 D, float8 t_max, float8* t_out, float8* a_out,
                  float8* b_out) {
  global const float* q = (global const float*)g + j;  // field f of lane j: q[4 f]
  const float nx = q[0], ny = q[4], nz = q[8], qx = q[12], qy = q[16], qz = q[20];
  const float ux = q[24], uy = q[28], uz = q[32], vx = q[36], vy = q[40], vz = q[44];
  const float wx = q[48], wy = q[52], wz = q[56];
  QUAD_ROOT_LANES(float8, mask8, nx, ny, nz, qx, qy, qz, ux, uy, uz, vx, vy, vz, wx, wy, wz, o, D, t_max);
}
// [end]
#pragma OPENCL FP_CONTRACT ON
#endif

#ifdef HAS_SPHERES
#pragma OPENCL FP_CONTRACT OFF
// hit_sphere's root for eight rays: the lanes that meet sphere s with t in (0, t_max), their t,
// and whether it is the nearer root (the record's fallback direction needs it). Products are not
// fused, so that each lane rounds as sphere.hpp's sphere_root does in float.
mask8 sphere8_root(const sphere_t s, vec8 o, vec8 D, float8 t_max, float8* t_out, mask8* nearer) {
  const vec8 c = splat8(s.center_radius.xyz);
  const float r = s.center_radius.w;
  const vec8 f = sub8(o, c);
  const float8 a = dot8(D, D);
  const float8 b = dot8(f, D);
  const float8 cc = dot8(f, f) - r * r;
  const vec8 l = sub8(f, scale8(D, b / a));  // centre-to-line offset: no cancellation in the discriminant
  const float8 ll = sqrt(dot8(l, l));
  const float8 disc = a * (r - ll) * (r + ll);
  const float8 q = -(b + copysign(sqrt(disc), b));
  const float8 r0 = cc / q, r1 = q / a;
  const mask8 swap = r0 > r1;
  const float8 t0 = select(r0, r1, swap), t1 = select(r1, r0, swap);
  const mask8 in0 = (t0 > 0.0f) & (t0 < t_max), in1 = (t1 > 0.0f) & (t1 < t_max);
  *t_out = select(t1, t0, in0);
  *nearer = in0;
  return (a > 0.0f) & (disc >= 0.0f) & (in0 | in1);
}
#pragma OPENCL FP_CONTRACT ON
#endif

// Eight hit records: hit_t with a lane for each field.
typedef struct {
  float8 t;
  vec8 p, p_error, normal;  // normal: unit, outward
  mask8 front_face;
  int8 material, light;
} hit8_t;

// Lane k of a float8 or an int8 (read through memory: OpenCL C has no variable lane index).
#define LANE(v, k) (((const float*)&(v))[k])
#define LANE_INT(v, k) (((const int*)&(v))[k])
#if defined(HAS_CHECKER) || defined(HAS_SPHERE_LIGHTS)
float3 lane3(const vec8* v, int k) { return (float3)(LANE(v->x, k), LANE(v->y, k), LANE(v->z, k)); }
void set_lane3(vec8* v, int k, float3 a) {
  ((float*)&v->x)[k] = a.x, ((float*)&v->y)[k] = a.y, ((float*)&v->z)[k] = a.z;
}
// Lane k of eight hit records, as the one-path loop's functions take a hit.
hit_t lane_hit(const hit8_t* h, int k) {
  hit_t r;
  r.t = LANE(h->t, k);
  r.p = lane3(&h->p, k), r.p_error = lane3(&h->p_error, k), r.normal = lane3(&h->normal, k);
  r.front_face = LANE_INT(h->front_face, k) != 0;
  r.material = LANE_INT(h->material, k), r.light = LANE_INT(h->light, k);
  return r;
}
#endif

#pragma OPENCL FP_CONTRACT OFF
// [listing cl-nearest8]
// nearest_hit for the rays in the lanes of `live`: every sphere and quad tested in all eight
// lanes at once (a shape's numbers are the same in every lane), then each lane's record from the
// shape it hit nearest, as hit_sphere and quad_hit make it. The lanes that hit something.
mask8 nearest_hit8(const scene_t* sc, vec8 o, vec8 D, mask8 live, hit8_t* h) {
  float8 t_max = (float8)(INFINITY), ab = (float8)(0.0f), bb = (float8)(0.0f);
  int8 kind = (int8)(0), which = (int8)(-1);  // kind 1: a sphere, 2: a quad
  mask8 nearer = (mask8)(0);
#ifdef HAS_SPHERES
  for (int i = 0; i < sc->n_spheres; ++i) {
    float8 t;
    mask8 n0;
    const mask8 hit = sphere8_root(sc->spheres[i], o, D, t_max, &t, &n0) & live;
    t_max = select(t_max, t, hit);
    nearer = select(nearer, n0, hit);
    kind = select(kind, (int8)(1), hit);
    which = select(which, (int8)(i), hit);
  }
#endif
#ifdef HAS_QUADS
  for (int i = 0; i < sc->n_quads; ++i) {
    float8 t, a, b;
    const mask8 hit = quad8_roots(&sc->quad_groups[i / 4], i % 4, o, D, t_max, &t, &a, &b) & live;
    t_max = select(t_max, t, hit);
    ab = select(ab, a, hit);
    bb = select(bb, b, hit);
    kind = select(kind, (int8)(2), hit);
    which = select(which, (int8)(i), hit);
  }
#endif
  h->t = t_max;
  h->p = h->p_error = h->normal = splat8((float3)(0.0f));
  h->material = h->light = (int8)(-1);
#ifdef HAS_SPHERES
  for (int i = 0; i < sc->n_spheres; ++i) {
    const mask8 m = (kind == 1) & (which == i);
    if (!any(m)) continue;
    const sphere_t s = sc->spheres[i];
    const vec8 c = splat8(s.center_radius.xyz);
    const float r = s.center_radius.w;
    vec8 radial = add8(sub8(o, c), scale8(D, t_max));
    const float8 len = sqrt(dot8(radial, radial));
    radial = pick8(radial, pick8(D, neg8(D), nearer), !(len > 0.0f) | !isfinite(len));
    const vec8 on = scale8(radial, r / sqrt(dot8(radial, radial)));
    const vec8 p = add8(c, on);
    h->p = pick8(h->p, p, m);
    h->p_error = pick8(h->p_error, scale8(add8(abs8(on), abs8(p)), (float8)(GAMMA(6))), m);
    h->normal = pick8(h->normal, div8(on, (float8)(r)), m);
    h->material = select(h->material, (int8)(s.material), m);
    h->light = select(h->light, (int8)(s.light), m);
  }
#endif
#ifdef HAS_QUADS
  for (int i = 0; i < sc->n_quads; ++i) {
    const mask8 m = (kind == 2) & (which == i);
    if (!any(m)) continue;
    const quad_t q = sc->quads[i];
    const vec8 Q = splat8(q.corner.xyz), au = scale8(splat8(q.u.xyz), ab), bv = scale8(splat8(q.v.xyz), bb);
    h->p = pick8(h->p, add8(add8(Q, au), bv), m);
    h->p_error = pick8(h->p_error, scale8(add8(add8(abs8(Q), abs8(au)), abs8(bv)), (float8)(GAMMA(4))), m);
    h->normal = pick8(h->normal, splat8(q.normal_area.xyz), m);
    h->material = select(h->material, (int8)(q.material), m);
    h->light = select(h->light, (int8)(q.light), m);
  }
#endif
  h->front_face = dot8(D, h->normal) < 0.0f;
  return kind != 0;
}
#pragma OPENCL FP_CONTRACT ON  // records unfused, as sphere.hpp makes them on the CPU

// occluded for the segments in the lanes of `live`: the lanes whose segment is blocked.
mask8 occluded8(const scene_t* sc, vec8 o, vec8 D, float8 t_max, mask8 live) {
  mask8 blocked = (mask8)(0);
#ifdef HAS_SPHERES
  for (int i = 0; i < sc->n_spheres; ++i) {
    float8 t;
    mask8 n0;
    blocked |= sphere8_root(sc->spheres[i], o, D, t_max, &t, &n0);
  }
#endif
#ifdef HAS_QUADS
  for (int i = 0; i < sc->n_quads; ++i) {
    float8 t, a, b;
    blocked |= quad8_roots(&sc->quad_groups[i / 4], i % 4, o, D, t_max, &t, &a, &b);
  }
#endif
  return blocked & live;
}
// [end]

float8 power_heuristic8(float8 a, float8 b) {
  const float8 r = b / a;
  return select(select(1.0f / (1.0f + r * r), (float8)(1.0f), isinf(a)), (float8)(0.0f), !(a > 0.0f));
}

// A material's numbers in each lane (the lane's own material: a gather, lane by lane).
typedef struct {
  int8 kind;
  vec8 albedo, radiance;
  mask8 two_sided;
  float8 ior;
} material8_t;
material8_t materials8(global const material_t* materials, const hit8_t* h) {
  int mi[LANES], kind[LANES], two[LANES];
  float ax[LANES], ay[LANES], az[LANES], rx[LANES], ry[LANES], rz[LANES], ior[LANES];
  vstore8(h->material, 0, mi);
  for (int k = 0; k < LANES; ++k) {
    kind[k] = -1, two[k] = 0, ax[k] = ay[k] = az[k] = rx[k] = ry[k] = rz[k] = 0.0f, ior[k] = 1.0f;
    if (mi[k] < 0) continue;  // a lane that hit nothing
    global const material_t* m = &materials[mi[k]];
    kind[k] = m->kind;
    two[k] = m->two_sided ? -1 : 0;
    ax[k] = m->albedo_a.x, ay[k] = m->albedo_a.y, az[k] = m->albedo_a.z;
#ifdef HAS_CHECKER
    if (m->checker) {  // the one-path loop's albedo(), at this lane's hit
      const hit_t hk = lane_hit(h, k);
      const float3 a = albedo(m, &hk);
      ax[k] = a.x, ay[k] = a.y, az[k] = a.z;
    }
#endif
    rx[k] = m->radiance.x, ry[k] = m->radiance.y, rz[k] = m->radiance.z;
    ior[k] = m->ior;
  }
  material8_t r;
  r.kind = vload8(0, kind);
  r.two_sided = vload8(0, two);
  r.albedo = vec8_of(vload8(0, ax), vload8(0, ay), vload8(0, az));
  r.radiance = vec8_of(vload8(0, rx), vload8(0, ry), vload8(0, rz));
  r.ior = vload8(0, ior);
  return r;
}

#ifdef HAS_QUAD_LIGHTS
// A quad light's numbers in each lane, for light index `which` (-1: none; lane 0's light then).
typedef struct {
  vec8 corner, u, v, normal, radiance;
  float8 inv_area, pdf;
  mask8 two_sided;
} light8_t;
light8_t lights8(const scene_t* sc, int8 which) {
  light8_t r;
  r.corner = r.u = r.v = r.normal = r.radiance = splat8((float3)(0.0f));
  r.inv_area = r.pdf = (float8)(0.0f);
  r.two_sided = (mask8)(0);
  for (int i = 0; i < sc->n_lights; ++i) {
    const mask8 m = which == i;
    if (!any(m)) continue;
    global const light_t* l = &sc->lights[i];
#ifdef HAS_SPHERE_LIGHTS
    if (l->kind != LIGHT_QUAD) continue;  // its lanes are left to the per-lane code below
#endif
    const quad_t q = sc->quads[l->object];
    global const material_t* e = &sc->materials[l->material];
    r.corner = pick8(r.corner, splat8(q.corner.xyz), m);
    r.u = pick8(r.u, splat8(q.u.xyz), m);
    r.v = pick8(r.v, splat8(q.v.xyz), m);
    r.normal = pick8(r.normal, splat8(q.normal_area.xyz), m);
    r.radiance = pick8(r.radiance, splat8(e->radiance.xyz), m);
    r.two_sided = select(r.two_sided, (mask8)(e->two_sided ? -1 : 0), m);
    r.inv_area = select(r.inv_area, (float8)(1.0f / l->area), m);
    r.pdf = select(r.pdf, (float8)(l->pdf), m);
  }
  return r;
}
#endif

// The state of eight paths between their bounces.
typedef struct {
  vec8 o, D;                     // the ray each lane traces next
  vec8 L, beta, from;
  float8 bsdf_pdf;
  mask8 specular;
  int8 bounce;
  stream8_t g;
} paths8_t;

// [listing cl-path8]
// One bounce of path_radiance for the paths in the lanes of `live`: the lanes that go on.
mask8 path_step8(const scene_t* sc, paths8_t* P, mask8 live) {
  const bool nee = NEE_ON, mis = MIS_ON;
  hit8_t h;
  const mask8 found = nearest_hit8(sc, P->o, P->D, live, &h);
  P->L = pick8(P->L, add8(P->L, mul8(P->beta, splat8(sc->background))), live & ~found);
  mask8 going = live & found;
  const material8_t m = materials8(sc->materials, &h);
#ifdef HAS_EMITTERS
  const vec8 Le = pick8(splat8((float3)(0.0f)), m.radiance, h.front_face | m.two_sided);
  const mask8 glows = going & nonzero8(Le);
  if (any(glows)) {
    float8 w = (float8)(1.0f);
#ifdef HAS_QUAD_LIGHTS
    if (nee && mis) {  // light_pdf: the light's area density, turned into solid angle
      const light8_t l = lights8(sc, select(h.light, (int8)(-1), ~glows));
      const float8 c = fabs(dot8(h.normal, P->D));
      const float8 pdf = select((float8)(0.0f), l.inv_area * (h.t * h.t) / c, c > 0.0f) * l.pdf;
      w = select(power_heuristic8(P->bsdf_pdf, pdf), w, P->specular | (h.light < 0));
    }
#endif
#ifdef HAS_SPHERE_LIGHTS
    if (nee && mis)  // a sphere light's density: light_pdf itself, lane by lane
      for (int k = 0; k < LANES; ++k) {
        const int li = LANE_INT(h.light, k);
        if (!LANE_INT(glows, k) || LANE_INT(P->specular, k) || li < 0 || sc->lights[li].kind != LIGHT_SPHERE) continue;
        const hit_t hk = lane_hit(&h, k);
        ((float*)&w)[k] =
            power_heuristic(LANE(P->bsdf_pdf, k), light_pdf(sc, li, lane3(&P->from, k), lane3(&P->D, k), &hk));
      }
#endif
    // All of it, its MIS share, or none (nee: the light sample at the previous hit counted it).
    const mask8 counted = !nee || mis ? glows : glows & (P->specular | (h.light < 0));
    P->L = pick8(P->L, add8(P->L, scale8(mul8(P->beta, Le), w)), counted);
  }
#endif
  going &= P->bounce != MAX_DEPTH;
  const vec8 n = pick8(neg8(h.normal), h.normal, h.front_face);  // facing: the side the ray came from
  const vec8 wo = neg8(P->D);
  const mask8 diffuse = going & (m.kind == KIND_LAMBERTIAN);
  // The next event: a point on a light, its share added if the shadow segment is clear.
  vec8 share = splat8((float3)(0.0f)), so = share, sd = share;
  float8 st = (float8)(0.0f);
  mask8 lit = (mask8)(0);
  if (nee && any(diffuse)) {
    const float8 u_select = uniform8(&P->g, diffuse);  // drawn with or without a light to sample
    const float8 ua = uniform8(&P->g, diffuse), ub = uniform8(&P->g, diffuse);
#if !defined(HAS_QUAD_LIGHTS) && !defined(HAS_SPHERE_LIGHTS)
    (void)u_select, (void)ua, (void)ub;
#else
    const float8 x = clamp_unit8(u_select) * sc->lights[sc->n_lights - 1].cdf;
    int8 which = (int8)(0);  // upper_bound: the lights whose CDF is at or below x come before
    for (int i = 0; i + 1 < sc->n_lights; ++i) which += select((int8)(0), (int8)(1), (float8)(sc->lights[i].cdf) <= x);
#endif
#ifdef HAS_QUAD_LIGHTS
    const light8_t l = lights8(sc, which);  // a lane that chose a sphere light: zeros, not lit
    const float8 a = clamp_unit8(ua), b = clamp_unit8(ub);
    const vec8 au = scale8(l.u, a), bv = scale8(l.v, b);
    const vec8 p = add8(add8(l.corner, au), bv);
    const vec8 p_error = scale8(add8(add8(abs8(l.corner), abs8(au)), abs8(bv)), (float8)(GAMMA(4)));
    const vec8 to = sub8(p, h.p);
    const vec8 wi = normalize_or_zero8(to);
    const float8 cos_l = fabs(dot8(l.normal, wi));
    const float8 pdf = select((float8)(0.0f), l.inv_area * dot8(to, to) / cos_l, cos_l > 0.0f) * l.pdf;
    so = offset_origin8(h.p, h.p_error, h.normal, to);  // spawn_segment
    const vec8 d = sub8(p, so);
    sd = normalize_or_zero8(d);
    st = sqrt(dot8(d, d)) * (1.0f - GAMMA(16)) - dot8(abs8(l.normal), p_error) / fmax(cos_l, 1e-30f);
    const vec8 e_Le = pick8(splat8((float3)(0.0f)), l.radiance, (dot8(wi, l.normal) < 0.0f) | l.two_sided);
    const float8 cos_i = dot8(wi, n);
    const mask8 same = (cos_i > 0.0f) & (dot8(wo, n) > 0.0f);
    const vec8 f_cos = scale8(pick8(splat8((float3)(0.0f)), div8(m.albedo, (float8)(PI_F)), same), fmax(0.0f, cos_i));
    const float8 w = mis ? power_heuristic8(pdf, select((float8)(0.0f), cos_i / PI_F, same & (cos_i > 0.0f)))
                         : (float8)(1.0f);
    share = scale8(mul8(mul8(P->beta, f_cos), e_Le), w / pdf);
    lit = diffuse & (pdf > 0.0f) & isfinite(pdf) & nonzero8(wi) & nonzero8(e_Le) & nonzero8(f_cos);
#endif
#ifdef HAS_SPHERE_LIGHTS
    // The lanes whose light is a sphere: the one-path loop's next event, lane by lane (the
    // shadow segments then go through occluded8 with the others').
    for (int k = 0; k < LANES; ++k) {
      if (!LANE_INT(diffuse, k) || sc->lights[LANE_INT(which, k)].kind != LIGHT_SPHERE) continue;
      const hit_t hk = lane_hit(&h, k);
      light_sample_t e;  // sample_light chooses the same light again from u_select
      float3 f_cos;
      float w_over_pdf;
      if (!next_event(sc, &sc->materials[hk.material], &hk, -lane3(&P->D, k), LANE(u_select, k),
                      (float2)(LANE(ua, k), LANE(ub, k)), &e, &f_cos, &w_over_pdf))
        continue;
      set_lane3(&share, k, lane3(&P->beta, k) * f_cos * e.Le * w_over_pdf);
      set_lane3(&so, k, e.origin);
      set_lane3(&sd, k, e.direction);
      ((float*)&st)[k] = e.t_max;
      ((int*)&lit)[k] = -1;
    }
#endif
  }
  // scatter(): Lambert samples the cosine (three numbers, the third for a lobe it does not have)
  vec8 dir = P->D, weight = splat8((float3)(1.0f));
  float8 pdf = (float8)(0.0f);
  if (any(diffuse)) {
    const float8 u0 = clamp_unit8(uniform8(&P->g, diffuse)), u1 = uniform8(&P->g, diffuse);
    (void)uniform8(&P->g, diffuse);
    const float8 s = sqrt(u0), v = 2.0f * clamp_unit8(u1);
    const float8 lx = s * cospi(v), ly = s * sinpi(v), lz = sqrt(1.0f - u0);
    const float8 sign = copysign((float8)(1.0f), n.z);  // onb(n)
    const float8 a = -1.0f / (sign + n.z);
    const float8 c = n.x * n.y * a;
    const vec8 t = vec8_of(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    const vec8 b = vec8_of(c, sign + n.y * n.y * a, -n.y);
    const vec8 w = add8(add8(scale8(t, lx), scale8(b, ly)), scale8(n, lz));
    const float8 cos_w = dot8(w, n);
    const float8 p = select((float8)(0.0f), cos_w / PI_F, cos_w > 0.0f);
    going &= ~diffuse | ((dot8(wo, n) > 0.0f) & (p > 0.0f));  // grazing, or on the horizon: absorbed
    dir = pick8(dir, w, diffuse);
    weight = pick8(weight, m.albedo, diffuse);
    pdf = select(pdf, p, diffuse);
  }
#ifdef HAS_DIELECTRIC
  const mask8 glass = going & (m.kind == KIND_DIELECTRIC);
  if (any(glass)) {  // refract_dir, then reflect with probability R (exact Fresnel)
    const float8 eta = select(m.ior, 1.0f / m.ior, h.front_face);
    const float8 cos_i = clamp(-dot8(P->D, n), 0.0f, 1.0f);
    const vec8 d_perp = add8(P->D, scale8(n, cos_i));
    const float8 lo = (1.0f - eta) * (1.0f + eta) + (eta * cos_i) * (eta * cos_i);  // cos2_transmitted, eta <= 1
    const float8 c2 = select(lo, 1.0f - eta * eta * dot8(d_perp, d_perp), eta > 1.0f);
    const mask8 can = c2 >= 0.0f;
    const vec8 t = normalize_or_zero8(sub8(scale8(d_perp, eta), scale8(n, sqrt(fmax(c2, 0.0f)))));
    const float8 u = uniform8(&P->g, glass & can);
    const float8 f2 = select(lo, 1.0f - eta * eta * ((1.0f - cos_i) * (1.0f + cos_i)), eta > 1.0f);
    const float8 ct = sqrt(fmax(f2, 0.0f));
    const float8 r_s = (eta * cos_i - ct) / (eta * cos_i + ct), r_p = (cos_i - eta * ct) / (cos_i + eta * ct);
    float8 R = clamp((r_s * r_s + r_p * r_p) / 2.0f, 0.0f, 1.0f);
    R = select(select(R, (float8)(1.0f), f2 <= 0.0f), (float8)(0.0f), eta == 1.0f);
    const vec8 reflected = sub8(P->D, scale8(n, 2.0f * dot8(P->D, n)));
    dir = pick8(dir, pick8(reflected, t, can & (u >= R)), glass);
  }
  going &= diffuse | glass;  // an emitter (or anything else) absorbs
#else
  going &= diffuse;
#endif
  P->beta = pick8(P->beta, mul8(P->beta, weight), going);
  P->specular = select(P->specular, ~diffuse, going);
  P->bsdf_pdf = select(P->bsdf_pdf, pdf, going);
  P->from = pick8(P->from, h.p, going);
  const mask8 rr = going & (P->bounce >= RR_DEPTH);  // survives_roulette
  if (any(rr)) {
    const float8 q = fmin(1.0f, fmax(P->beta.x, fmax(P->beta.y, P->beta.z)));
    going &= ~rr | (uniform8(&P->g, rr) < q);
    P->beta = pick8(P->beta, div8(P->beta, q), rr & going);
  }
  P->o = pick8(P->o, offset_origin8(h.p, h.p_error, h.normal, dir), going);
  P->D = pick8(P->D, dir, going);
  P->bounce = select(P->bounce, P->bounce + 1, going);
  if (any(lit)) P->L = pick8(P->L, add8(P->L, share), lit & ~occluded8(sc, so, sd, st, lit));
  return going;
}
// [end]
#endif

// Where a launch's samples go: the kernel's image arguments.
typedef struct {
  global float4* accum;
  global float4* accum_sq;
  global uchar4* display;
  global const float* srgb_steps;
  uint width, height, sample_offset, samples;
} image_t;

// Adds pixel (x, y)'s sums of this launch to accum and accum_sq (sum.w: the samples that were
// finite) and writes its running mean as sRGB bytes, bottom row first as OpenGL stores textures.
void store_pixel(const image_t* im, uint x, uint y, float4 sum, float4 sum_sq) {
  const uint i = y * im->width + x;
  const float4 total = im->sample_offset == 0 ? sum : im->accum[i] + sum;
  im->accum[i] = total;
  im->accum_sq[i] = im->sample_offset == 0 ? sum_sq : im->accum_sq[i] + sum_sq;
  const float3 mean = total.xyz / fmax(total.w, 1.0f);
  global const float* steps = im->srgb_steps;
  im->display[(im->height - 1 - y) * im->width + x] =
      (uchar4)(srgb_byte(mean.x, steps), srgb_byte(mean.y, steps), srgb_byte(mean.z, steps), 255);
}

#ifndef PATH_LANES
// [listing cl-render-pixel]
// One work item per pixel: its samples one after the other.
void render_pixel(const scene_t* sc, global const camera_t* camera, const image_t* im, ulong seed) {
  const uint x = get_global_id(0), y = get_global_id(1);
  if (x >= im->width || y >= im->height) return;
  const camera_t cam = *camera;
  float4 sum = (float4)(0.0f), sum_sq = (float4)(0.0f);  // sum.w: samples that were finite
#ifdef WEAK_SEED
  stream_t g = stream_make(seed, x, y, im->width, 0);  // one stream for the pixel, every frame the same
#endif
  for (uint s = im->sample_offset; s < im->sample_offset + im->samples; ++s) {
#ifndef WEAK_SEED
    stream_t g = stream_make(seed, x, y, im->width, s);
#endif
    const float sx = ((float)x + uniform(&g)) / (float)im->width;
    const float sy = ((float)y + uniform(&g)) / (float)im->height;
    const float3 target = cam.corner.xyz + sx * cam.horizontal.xyz + sy * cam.vertical.xyz;
    float3 o = cam.origin.xyz;
#ifdef HAS_THIN_LENS
    if (cam.lens_radius > 0.0f) {
      const float r = cam.lens_radius * sqrt(uniform(&g)), phi = 2.0f * PI_F * uniform(&g);
      o += r * cos(phi) * cam.u.xyz + r * sin(phi) * cam.v.xyz;
    }
#endif
    const float3 c = path_radiance(sc, o, normalize(target - o), &g);
    if (isfinite(c.x) && isfinite(c.y) && isfinite(c.z)) {  // render.hpp drops NaN
      sum += (float4)(c, 1.0f);
      sum_sq += (float4)(c * c, 0.0f);
    }
  }
  store_pixel(im, x, y, sum, sum_sq);
}
// [end]
#else
// [listing cl-render-lanes]
// One work item, eight pixels of a row (x0 .. x0 + 7), one per lane. A lane whose path ends
// starts its pixel's next sample at once, so the lanes stay busy until the last pixel is done.
void render_lanes(const scene_t* sc, global const camera_t* camera, const image_t* im, ulong seed) {
  const uint x0 = get_global_id(0) * LANES, y = get_global_id(1);
  if (x0 >= im->width || y >= im->height) return;
  const camera_t cam = *camera;
  const uint8 x = (uint8)(x0) + (uint8)(0, 1, 2, 3, 4, 5, 6, 7);
  const uint end = im->sample_offset + im->samples;
  mask8 live = (x < (uint8)(im->width)) & (mask8)(im->samples > 0 ? -1 : 0);
  mask8 starting = live;
  uint8 next = (uint8)(im->sample_offset);  // each lane's next sample
  paths8_t P;
  P.o = P.D = P.L = P.beta = P.from = splat8((float3)(0.0f));
  P.bsdf_pdf = (float8)(0.0f);
  P.specular = (mask8)(0);
  P.bounce = (int8)(0);
  const uint seed_key = seed_word(seed);  // rng_make's keys, in lanes
  P.g.key_pixel = pcg_hash8(y * im->width + x + seed_key);
  P.g.key_sample = P.g.dimension = (uint8)(0u);
  const uint sample_key = pcg_hash(seed_key ^ 0x5bd1e995u);
  vec8 sum = splat8((float3)(0.0f)), sum_sq = sum;
  float8 finite = (float8)(0.0f);  // samples that were finite
  while (any(live)) {
    if (any(starting)) {  // the camera ray of each starting lane's next sample
      P.g.key_sample = select(P.g.key_sample, pcg_hash8(next + sample_key), starting);
      P.g.dimension = select(P.g.dimension, (uint8)(0u), starting);
      next = select(next, next + 1u, starting);
      const float8 sx = (convert_float8(x) + uniform8(&P.g, starting)) / (float)im->width;
      const float8 sy = ((float)y + uniform8(&P.g, starting)) / (float)im->height;
      const vec8 target = add8(add8(splat8(cam.corner.xyz), scale8(splat8(cam.horizontal.xyz), sx)),
                               scale8(splat8(cam.vertical.xyz), sy));
      vec8 o = splat8(cam.origin.xyz);
#ifdef HAS_THIN_LENS
      if (cam.lens_radius > 0.0f) {
        const float8 r = cam.lens_radius * sqrt(uniform8(&P.g, starting));
        const float8 phi = 2.0f * PI_F * uniform8(&P.g, starting);
        o = add8(o, add8(scale8(splat8(cam.u.xyz), r * cos(phi)), scale8(splat8(cam.v.xyz), r * sin(phi))));
      }
#endif
      P.o = pick8(P.o, o, starting);
      P.D = pick8(P.D, normalize_or_zero8(sub8(target, o)), starting);
      P.L = pick8(P.L, splat8((float3)(0.0f)), starting);
      P.beta = pick8(P.beta, splat8((float3)(1.0f)), starting);
      P.from = pick8(P.from, splat8((float3)(0.0f)), starting);
      P.specular |= starting;  // camera rays count as specular
      P.bsdf_pdf = select(P.bsdf_pdf, (float8)(0.0f), starting);
      P.bounce = select(P.bounce, (int8)(0), starting);
    }
    const mask8 ended = live & ~path_step8(sc, &P, live);
    starting = (mask8)(0);
    if (!any(ended)) continue;
    const mask8 counted = ended & finite8(P.L);  // render.hpp drops NaN
    sum = pick8(sum, add8(sum, P.L), counted);
    sum_sq = pick8(sum_sq, add8(sum_sq, mul8(P.L, P.L)), counted);
    finite = select(finite, finite + 1.0f, counted);
    starting = ended & (next < (uint8)(end));
    live &= ~ended | starting;
  }
  float s[4][LANES];
  vstore8(sum.x, 0, s[0]), vstore8(sum.y, 0, s[1]), vstore8(sum.z, 0, s[2]), vstore8(finite, 0, s[3]);
  float q[3][LANES];
  vstore8(sum_sq.x, 0, q[0]), vstore8(sum_sq.y, 0, q[1]), vstore8(sum_sq.z, 0, q[2]);
  for (uint k = 0; k < LANES && x0 + k < im->width; ++k)
    store_pixel(im, x0 + k, y, (float4)(s[0][k], s[1][k], s[2][k], s[3][k]), (float4)(q[0][k], q[1][k], q[2][k], 0.0f));
}
// [end]
#endif

// [listing cl-kernel]
// Adds `samples` samples (indices sample_offset, sample_offset + 1, ...) to each pixel's sum in
// accum and their squares to accum_sq (sample_offset 0: starts both afresh), and writes the
// running mean as sRGB bytes for display, bottom row first as OpenGL textures are stored.
// (With PATH_LANES a work item renders pixels 8 x .. 8 x + 7 of row y: see render_lanes.)
kernel void render(global const sphere_t* spheres, global const quad_t* quads,
                   global const quad4_t* quad_groups, global const plane_t* planes, global const triangle_t* tris,
                   global const node4_t* nodes, global const material_t* materials,
                   global const light_t* lights, global const light_triangle_t* light_tris,
                   global const camera_t* camera, global float4* accum, global float4* accum_sq,
                   global uchar4* display, int n_spheres, int n_quads, int n_planes, int n_lights,
                   int n_nodes, uint width, uint height, uint sample_offset, uint samples, ulong seed,
                   float4 background, global const texture_t* textures, global const float4* texels,
                   global const float4* tri_uvs, int has_tri_uvs, global const environment_t* env,
                   global const float* env_tables, global const int* noise_permutation,
                   global const float* srgb_steps) {
  scene_t sc = {spheres, quads, quad_groups, planes, tris, nodes, materials, lights, light_tris,
                n_spheres, n_quads, n_planes, n_lights, n_nodes, background.xyz};
#ifdef HAS_TEXTURES
  sc.textures = textures;
  sc.noise_permutation = noise_permutation;
#endif
#if defined(HAS_TEXTURES) || defined(HAS_ENVIRONMENT)
  sc.texels = texels;
#endif
#ifdef HAS_SURFACE_UV
  sc.tri_uvs = tri_uvs;
  sc.has_tri_uvs = has_tri_uvs;
#endif
#ifdef HAS_ENVIRONMENT
  sc.env = env;
  sc.env_tables = env_tables;
#endif
  const image_t img = {accum, accum_sq, display, srgb_steps, width, height, sample_offset, samples};
#ifdef PATH_LANES
  render_lanes(&sc, camera, &img, seed);
#else
  render_pixel(&sc, camera, &img, seed);
#endif
}
// [end]

// The layout the kernel sees, for tests/test_realtime.cpp to compare with gpu_scene.hpp's.
#define SIZE_AND(T, field) sizeof(T), (uint)((char*)&v_##T.field - (char*)&v_##T)
kernel void layout(global uint* out) {
  if (get_global_id(0) != 0) return;
  sphere_t v_sphere_t;
  quad_t v_quad_t;
  quad4_t v_quad4_t;
  plane_t v_plane_t;
  triangle_t v_triangle_t;
  node4_t v_node4_t;
  material_t v_material_t;
  light_t v_light_t;
  light_triangle_t v_light_triangle_t;
  camera_t v_camera_t;
  texture_t v_texture_t;
  environment_t v_environment_t;
  const uint values[38] = {SIZE_AND(sphere_t, material), SIZE_AND(sphere_t, light),
                           SIZE_AND(quad_t, material), SIZE_AND(plane_t, material),
                           SIZE_AND(triangle_t, material), SIZE_AND(triangle_t, light),
                           SIZE_AND(node4_t, count), SIZE_AND(material_t, fuzz),
                           SIZE_AND(material_t, shininess), SIZE_AND(light_t, kind),
                           SIZE_AND(light_t, cdf), SIZE_AND(light_triangle_t, c),
                           SIZE_AND(material_t, eta), SIZE_AND(material_t, albedo_texture),
                           SIZE_AND(material_t, roughness), SIZE_AND(texture_t, kind),
                           SIZE_AND(texture_t, cell), SIZE_AND(environment_t, cos_rotation),
                           SIZE_AND(quad4_t, wz)};
  for (int i = 0; i < 38; ++i) out[i] = values[i];
}

#ifdef PROBES
// For tests/test_realtime.cpp (built with -DPROBES, never in a render): the environment's and the
// image texture's functions on given numbers, to hold against environment.hpp and texture.hpp
// at the extremes (the poles, u next to 1, empty bins, NaN and huge texture coordinates).
#ifdef HAS_ENVIRONMENT
// in[i]: (u.x, u.y) for env_sample; in[n + i]: a direction for env_pdf and env_radiance.
// out[3i] = (w, pdf) sampled; out[3i + 1].x = env_pdf(w); out[3i + 2] = (radiance at in[n + i], pdf there).
kernel void probe_environment(global const environment_t* env, global const float* env_tables,
                              global const float4* texels, global const float4* in, global float4* out, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  scene_t sc;
  sc.env = env;
  sc.env_tables = env_tables;
  sc.texels = texels;
  float pdf = 0.0f;
  const float3 w = env_sample(&sc, in[i].xy, &pdf);
  out[3 * i] = (float4)(w, pdf);
  out[3 * i + 1] = (float4)(env_pdf(&sc, w), 0.0f, 0.0f, 0.0f);
  const float3 d = in[n + i].xyz;
  out[3 * i + 2] = (float4)(env_radiance(&sc, d), env_pdf(&sc, d));
}
#endif
#if defined(HAS_ROUGH_CONDUCTOR) && defined(HAS_ROUGH_DIELECTRIC)
// Case i in the local frame: in[3i] = (wo, alpha), in[3i + 1] = (wi, u_lobe), in[3i + 2] =
// (u.x, u.y, eta, material): materials[0] a rough conductor, the glass's eta given here.
// out[4i] = (f, pdf) for (wo, wi); out[4i + 1] = (sampled wi, pdf), out[4i + 2] = (weight, ok).
kernel void probe_microfacet(global const material_t* materials, global const float4* in, global float4* out,
                             int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  const float4 a = in[3 * i], b = in[3 * i + 1], c = in[3 * i + 2];
  const float3 wo = a.xyz, wi = b.xyz;
  const float alpha = a.w, eta = c.z;
  float3 f, sw = (float3)(0.0f), weight = (float3)(0.0f);
  float pdf, spdf = 0.0f;
  bool ok;
  if (c.w == 0.0f) {
    f = rough_conductor_f(materials, alpha, wo, wi);
    pdf = rough_conductor_pdf(alpha, wo, wi);
    ok = rough_conductor_sample(materials, alpha, wo, c.xy, &sw, &weight, &spdf);
  } else {
    f = (float3)(rough_dielectric_f(alpha, eta, wo, wi));
    pdf = rough_dielectric_pdf(alpha, eta, wo, wi);
    ok = rough_dielectric_sample(alpha, eta, wo, c.xy, b.w, &sw, &weight, &spdf);
  }
  out[4 * i] = (float4)(f, pdf);
  out[4 * i + 1] = (float4)(sw, spdf);
  out[4 * i + 2] = (float4)(weight, ok ? 1.0f : 0.0f);
  out[4 * i + 3] = (float4)(0.0f);
}
#endif
#ifdef HAS_QUADS
// Ray i is in[2i] (origin) and in[2i + 1] (direction, w: t_max). out[2i] = (t, a, b, index) of
// the nearest quad (index -1: none); out[2i + 1].x = 1 if any quad is in the way, else 0.
kernel void probe_quads(global const quad_t* quads, global const quad4_t* quad_groups, int n_quads,
                        global const float4* in, global float4* out, int n) {
  const int i = get_global_id(0);
  if (i >= n) return;
  scene_t sc;
  sc.quads = quads;
  sc.quad_groups = quad_groups;
  sc.n_quads = n_quads;
  const float3 o = in[2 * i].xyz, D = in[2 * i + 1].xyz;
  const float t_max = in[2 * i + 1].w;
  float t = 0.0f, a = 0.0f, b = 0.0f;
  const int q = nearest_quad(&sc, o, D, t_max, &t, &a, &b);
  out[2 * i] = (float4)(t, a, b, (float)q);
  out[2 * i + 1] = (float4)(any_quad(&sc, o, D, t_max) ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
}
#endif
#ifdef HAS_IMAGE_TEXTURES
// out[i] = lookup_bilinear(textures[0], uv[i])
kernel void probe_image(global const texture_t* t, global const float4* texels, global const float2* uv,
                        global float4* out, int n) {
  const int i = get_global_id(0);
  if (i < n) out[i] = (float4)(lookup_bilinear(t, texels, uv[i]), 0.0f);
}
#endif
#ifdef PATH_LANES
// Rays eight at a time through the lanes loop's tests (ray i: in[2i] origin, in[2i + 1]
// direction and t_max in w). out[3i] = (t, material, front face, 0) of nearest_hit8 (t_max
// infinite; material -1: nothing hit), out[3i + 1] = its point, out[3i + 2].x = 1 if occluded8
// finds a shape before t_max, else 0.
kernel void probe_lanes(global const sphere_t* spheres, int n_spheres, global const quad_t* quads,
                        global const quad4_t* quad_groups, int n_quads, global const float4* in,
                        global float4* out, int n) {
  const int i0 = get_global_id(0) * LANES;
  if (i0 >= n) return;
  scene_t sc;
  sc.spheres = spheres;
  sc.n_spheres = n_spheres;
  sc.quads = quads;
  sc.quad_groups = quad_groups;
  sc.n_quads = n_quads;
  float v[7][LANES];
  int live[LANES];
  for (int k = 0; k < LANES; ++k) {  // lanes past the last ray repeat it, outside the mask
    const int i = min(i0 + k, n - 1);
    const float4 o = in[2 * i], d = in[2 * i + 1];
    v[0][k] = o.x, v[1][k] = o.y, v[2][k] = o.z, v[3][k] = d.x, v[4][k] = d.y, v[5][k] = d.z, v[6][k] = d.w;
    live[k] = i0 + k < n ? -1 : 0;
  }
  const vec8 o = vec8_of(vload8(0, v[0]), vload8(0, v[1]), vload8(0, v[2]));
  const vec8 D = vec8_of(vload8(0, v[3]), vload8(0, v[4]), vload8(0, v[5]));
  const mask8 m = vload8(0, live);
  hit8_t h;
  const mask8 found = nearest_hit8(&sc, o, D, m, &h);
  const mask8 blocked = occluded8(&sc, o, D, vload8(0, v[6]), m);
  float t[LANES], px[LANES], py[LANES], pz[LANES];
  int material[LANES], front[LANES], b[LANES];
  vstore8(h.t, 0, t);
  vstore8(h.p.x, 0, px), vstore8(h.p.y, 0, py), vstore8(h.p.z, 0, pz);
  vstore8(select((int8)(-1), h.material, found), 0, material);
  vstore8(h.front_face, 0, front);
  vstore8(blocked, 0, b);
  for (int k = 0; k < LANES && i0 + k < n; ++k) {
    out[3 * (i0 + k)] = (float4)(t[k], (float)material[k], front[k] ? 1.0f : 0.0f, 0.0f);
    out[3 * (i0 + k) + 1] = (float4)(px[k], py[k], pz[k], 0.0f);
    out[3 * (i0 + k) + 2] = (float4)(b[k] ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
  }
}
#endif
#endif

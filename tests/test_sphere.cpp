// Tests for sphere.hpp: ray-sphere intersection at extreme scales, against a long double
// reference computed from the exact float/double inputs (the stored ray origin and unit
// direction, the centre and the radius), plus the spawn rule's reintersection test.
//
// Error units. A backward-stable intersection is off by a few roundings of the numbers it
// handles, magnified by the problem's own condition. So t errors are stated in units of
//     u * S * kappa,   u = unit roundoff, S = |O| + |C| + r (the size of the coordinates),
//     kappa = 1 + r / h  (h = half the chord: dt/dm = m/h blows up for grazing rays).
// Hit/miss is decided by the sign of r - |l| (l = centre-to-line offset). The computed |l| is
// off by at most about 7 u S (f: 1 rounding, b = f.D: 3, (b/a) D: 2, f - (b/a)D: 1 more,
// |.|: 3 relative to r), so outside the band |m_ref - r| > 16 u S the decision must be right.
#include <zraka/core/onb.hpp>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/sphere.hpp>

#include <doctest/doctest.h>

#include <cstdio>
#include <limits>
#include <string>

using namespace zraka;

namespace {

using LD = long double;
using vld = glm::vec<3, LD, glm::defaultp>;

template <class T> vld up(const vec3_t<T>& v) { return vld(LD(v.x), LD(v.y), LD(v.z)); }
template <class T> constexpr LD unit_roundoff() { return LD(std::numeric_limits<T>::epsilon()) / 2; }

// The exact problem |O + tD - C| = r in long double, with the same cancellation-free steps.
struct reference {
  bool hit = false;  // the line meets the sphere (m <= r)
  LD m = 0;          // distance from the centre to the ray's line
  LD h = 0;          // half chord length (in units of t)
  LD t_near = 0, t_far = 0;
  LD scale = 0;      // S = |O| + |C| + r
};

template <class T> reference solve(const sphere_t<T>& s, const ray_t<T>& r) {
  reference ref;
  const vld O = up(r.origin), D = up(r.direction), C = up(s.center);
  const LD R = s.radius;
  const vld f = O - C;
  const LD a = glm::dot(D, D), b = glm::dot(f, D), c = glm::dot(f, f) - R * R;
  const vld l = f - (b / a) * D;
  ref.m = std::sqrt(glm::dot(l, l));
  ref.scale = std::sqrt(glm::dot(O, O)) + std::sqrt(glm::dot(C, C)) + R;
  ref.hit = ref.m <= R;
  if (!ref.hit) return ref;
  const LD disc = a * (R - ref.m) * (R + ref.m);
  ref.h = std::sqrt(disc) / a;
  const LD q = -(b + std::copysign(std::sqrt(disc), b));
  LD t0 = q != 0 ? c / q : 0, t1 = q / a;
  if (t0 > t1) std::swap(t0, t1);
  ref.t_near = t0;
  ref.t_far = t1;
  return ref;
}

template <class T> vec3_t<T> random_unit(rng& g) {
  const double z = 1 - 2 * g.uniform(), phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}
double log_uniform(rng& g, double lo, double hi) {
  return std::pow(10.0, std::log10(lo) + (std::log10(hi) - std::log10(lo)) * g.uniform());
}
template <class T> std::string name() { return sizeof(T) == 4 ? "float" : "double"; }

// Worst-case bookkeeping for one group.
struct stats {
  long rays = 0, in_band = 0, wrong_outside_band = 0, wrong = 0, compared = 0;
  double worst_t = 0;      // worst t error in u S kappa
  double worst_rel = 0;    // worst |t - t_ref| / t_ref, plain relative error
  double worst_wrong = 0;  // largest |m - r| / (u S) of a wrong hit/miss decision
};

constexpr double t_bound = 8;      // t error bound, in u S kappa (first-order count ~7; measured ~2.3)
constexpr double band_units = 16;  // hit/miss uncertainty band, in u S (derived above)

// Intersects, compares with the reference (nearest root in (0, inf)), and records.
template <class T> void check_against_reference(const sphere_t<T>& s, const ray_t<T>& r, stats& st) {
  const reference ref = solve(s, r);
  const LD u = unit_roundoff<T>();
  hit_t<T> h;
  const bool got = intersect(s, r, T(0), infinity<T>, h);
  ++st.rays;
  const LD edge = std::abs(ref.m - LD(s.radius)) / (u * ref.scale);
  if (got != ref.hit) {
    ++st.wrong;
    st.worst_wrong = std::max(st.worst_wrong, double(edge));
  }
  if (edge <= band_units) {
    ++st.in_band;
  } else if (got != ref.hit) {
    ++st.wrong_outside_band;
  }
  if (got && ref.hit) {
    const LD want = ref.t_near > 0 ? ref.t_near : ref.t_far;
    const LD kappa = 1 + LD(s.radius) / std::max(ref.h, std::numeric_limits<LD>::min());
    const LD e = std::abs(LD(h.t) - want) / (u * ref.scale * kappa);
    st.worst_t = std::max(st.worst_t, double(e));
    st.worst_rel = std::max(st.worst_rel, double(std::abs(LD(h.t) - want) / want));
    ++st.compared;
    CHECK(std::isfinite(h.t));
    CHECK(is_finite(h.p));
    CHECK(is_finite(h.normal));
  }
}

template <class T> void report(const char* group, const stats& st) {
  char line[400];
  std::snprintf(line, sizeof line,
                "[%s] %s: %ld rays, worst t error %.3g u*S*kappa (bound %g; relative %.3g) over %ld hits; "
                "hit/miss: %ld wrong outside the band, %ld rays inside the band (%g u*S), "
                "%ld wrong decisions in all, the farthest %.3g u*S from the edge",
                name<T>().c_str(), group, st.rays, st.worst_t, t_bound, st.worst_rel, st.compared, st.wrong_outside_band,
                st.in_band, band_units, st.wrong, st.worst_wrong);
  MESSAGE(line);
  CHECK(st.wrong_outside_band == 0);
  CHECK(st.worst_t <= t_bound);
}

// The thesis's Listing 1.13 with unit D: hit iff b^2 - c >= 0, computed as written.
template <class T> bool naive_hit(const sphere_t<T>& s, const ray_t<T>& r) {
  const vec3_t<T> f = r.origin - s.center;
  const T b = glm::dot(f, r.direction);
  const T c = glm::dot(f, f) - s.radius * s.radius;
  return b * b - c >= T(0);
}

}  // namespace

TEST_CASE("the long double reference has extra precision") {
  // On x86-64 long double has a 64-bit significand: 11 bits more than double.
  REQUIRE(std::numeric_limits<long double>::digits >= 64);
}

TEST_CASE_TEMPLATE("sphere: radii 1e-4..1e6 at centre distances up to 1e6", T, float, double) {
  rng g(11);
  stats st;
  for (int i = 0; i < 20000; ++i) {
    const double radius = log_uniform(g, 1e-4, 1e6);
    const double d = radius * (1 + log_uniform(g, 1e-3, std::max(10.0, 1e6 / radius)));
    const vec3 O = vec3(random_unit<double>(g)) * log_uniform(g, 1e-3, 1e3);
    const vec3 axis = random_unit<double>(g);
    const vec3 C = O + d * axis;
    // Miss distance: half uniform over the disc, half within 1e-12..1 of the edge (both sides).
    double m = radius * g.uniform();
    if (g.uniform() < 0.5) m = radius * (1 + (g.uniform() < 0.5 ? -1 : 1) * log_uniform(g, 1e-12, 1));
    // The line O + t axis passes at distance m from the centre C + m perp.
    const vec3 perp = normalize_or_zero(glm::cross(axis, random_unit<double>(g)));
    const sphere_t<T> s{vec3_t<T>(C + m * perp), T(radius)};
    const ray_t<T> r{vec3_t<T>(O), vec3_t<T>(axis)};
    check_against_reference(s, r, st);
  }
  report<T>("scales", st);
}

TEST_CASE_TEMPLATE("sphere: grazing rays at 2^-k inside and outside the silhouette", T, float,
                   double) {
  rng g(12);
  stats st;
  const int digits = std::numeric_limits<T>::digits;
  for (double radius : {1e-4, 1e-2, 1.0, 1e2, 1e4, 1e6})
    for (int k = 1; k <= digits + 4; ++k)
      for (int side : {-1, 1})
        for (int rep = 0; rep < 8; ++rep) {
          const vec3 O = vec3(random_unit<double>(g)) * radius;
          const vec3 axis = random_unit<double>(g);
          const vec3 C = O + 5 * radius * axis;
          const vec3 perp = normalize_or_zero(glm::cross(axis, random_unit<double>(g)));
          const vec3 Cm = C + radius * (1 + side * std::ldexp(1.0, -k)) * perp;
          check_against_reference(sphere_t<T>{vec3_t<T>(Cm), T(radius)},
                                  ray_t<T>(vec3_t<T>(O), vec3_t<T>(axis)), st);
        }
  report<T>("grazing", st);
}

TEST_CASE_TEMPLATE("sphere: exactly tangent rays (exact inputs) touch at one point", T, float,
                   double) {
  // Power-of-two sizes make every step exact: l = (r, 0, 0) and disc = 0 with no rounding.
  for (int e = -20; e <= 20; e += 5) {
    const T r = std::ldexp(T(1), e);
    const sphere_t<T> s{{T(0), T(0), -8 * r}, r};
    hit_t<T> h;
    REQUIRE(intersect(s, ray_t<T>({r, T(0), T(0)}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
    CHECK(h.t == 8 * r);  // the double root
    CHECK(h.p == vec3_t<T>(r, T(0), -8 * r));
    CHECK(h.normal == vec3_t<T>(1, 0, 0));
    // One ulp outside the silhouette misses, one ulp inside hits.
    const T out = std::nextafter(r, 2 * r), in = std::nextafter(r, T(0));
    CHECK_FALSE(intersect(s, ray_t<T>({out, T(0), T(0)}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
    CHECK(intersect(s, ray_t<T>({in, T(0), T(0)}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
    CHECK(h.t < 8 * r);
  }
}

TEST_CASE_TEMPLATE("sphere: origin inside returns the far root", T, float, double) {
  rng g(13);
  stats st;
  for (int i = 0; i < 5000; ++i) {
    const double radius = log_uniform(g, 1e-4, 1e6);
    const vec3 C = vec3(random_unit<double>(g)) * log_uniform(g, 1e-3, 1e6);
    const vec3 O = C + vec3(random_unit<double>(g)) * radius * 0.999 * g.uniform();
    const sphere_t<T> s{vec3_t<T>(C), T(radius)};
    const ray_t<T> r(vec3_t<T>(O), random_unit<T>(g));
    const reference ref = solve(s, r);
    if (!(glm::length(up(r.origin) - up(s.center)) < LD(s.radius) * LD(0.9995))) continue;
    REQUIRE(ref.hit);
    REQUIRE(ref.t_near < 0);
    REQUIRE(ref.t_far > 0);
    hit_t<T> h;
    REQUIRE(intersect(s, r, T(0), infinity<T>, h));
    CHECK_FALSE(h.front_face);  // it leaves the sphere
    check_against_reference(s, r, st);
  }
  // From the centre exactly: t = r.
  hit_t<T> h;
  REQUIRE(intersect(sphere_t<T>{{T(1), T(2), T(3)}, T(0.5)},
                    ray_t<T>({T(1), T(2), T(3)}, {T(0), T(1), T(0)}), T(0), infinity<T>, h));
  CHECK(h.t == T(0.5));
  report<T>("origin inside", st);
}

TEST_CASE_TEMPLATE("sphere: origin exactly on the surface", T, float, double) {
  // O = C + r e_i with exact sums, so c = f.f - r^2 is exactly 0 and one root is exactly 0:
  // t_min = 0 (open interval) rejects it; going in, the far root is returned; going out, nothing.
  rng g(14);
  stats st;
  long in_hits = 0, out_misses = 0, tries = 0;
  for (int e = -12; e <= 12; e += 3)
    for (int axis = 0; axis < 3; ++axis)
      for (int sign : {-1, 1})
        for (int rep = 0; rep < 20; ++rep) {
          const T scale = std::ldexp(T(1), e);
          const sphere_t<T> s{vec3_t<T>(3, -2, 5) * scale, T(0.5) * scale};
          vec3_t<T> n(0);
          n[axis] = T(sign);
          const vec3_t<T> O = s.center + s.radius * n;
          REQUIRE(glm::dot(O - s.center, O - s.center) == s.radius * s.radius);
          vec3_t<T> w = random_unit<T>(g);
          if (std::abs(glm::dot(w, n)) < T(1e-3)) continue;
          ++tries;
          hit_t<T> h;
          if (glm::dot(w, n) < 0) {
            REQUIRE(intersect(s, ray_t<T>(O, w), T(0), infinity<T>, h));
            CHECK(h.t > T(0.5) * s.radius * T(1e-3));  // the far root, not the t = 0 one
            CHECK_FALSE(h.front_face);
            check_against_reference(s, ray_t<T>(O, w), st);
            ++in_hits;
          } else {
            CHECK_FALSE(intersect(s, ray_t<T>(O, w), T(0), infinity<T>, h));
            ++out_misses;
          }
        }
  // Tangent from a surface point: the double root is 0; t_min rejects it, and no NaN appears.
  hit_t<T> h;
  CHECK_FALSE(intersect(sphere_t<T>{{T(0), T(0), T(0)}, T(1)},
                        ray_t<T>({T(1), T(0), T(0)}, {T(0), T(1), T(0)}), T(0), infinity<T>, h));
  CHECK(h.t == infinity<T>);  // untouched
  MESSAGE("[" << name<T>() << "] on surface: " << tries << " rays, " << in_hits
              << " inward hit the far side, " << out_misses << " outward missed");
  report<T>("origin on surface", st);
}

TEST_CASE_TEMPLATE("sphere: a sphere behind the ray is not hit (thesis B4)", T, float, double) {
  rng g(15);
  long naive_false_hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const double radius = log_uniform(g, 1e-4, 1e6);
    const vec3 D = random_unit<double>(g);
    const vec3 O = vec3(random_unit<double>(g)) * log_uniform(g, 1e-3, 1e3);
    const vec3 perp = normalize_or_zero(glm::cross(D, random_unit<double>(g)));
    const vec3 C = O - radius * (1.01 + log_uniform(g, 1e-3, 1e3)) * D + radius * 0.9 * g.uniform() * perp;
    const sphere_t<T> s{vec3_t<T>(C), T(radius)};
    const ray_t<T> r{vec3_t<T>(O), vec3_t<T>(D)};
    hit_t<T> h;
    CHECK_FALSE(intersect(s, r, T(0), infinity<T>, h));
    naive_false_hits += naive_hit(s, r);
  }
  MESSAGE("[" << name<T>() << "] behind: the thesis's b*b - c >= 0 reports " << naive_false_hits
              << " of 5000 spheres behind the ray as hits; ours none");
  CHECK(naive_false_hits > 4000);
}

TEST_CASE_TEMPLATE("sphere: invalid spheres and rays give no hit and no NaN", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>;
  const ray_t<T> good({T(0), T(0), T(0)}, {T(0), T(0), T(-1)});
  for (T radius : {T(-1), T(0), T(-0.0), nan, inf, -inf}) {
    hit_t<T> h;
    CHECK_FALSE(intersect(sphere_t<T>{{T(0), T(0), T(-5)}, radius}, good, T(0), inf, h));
    CHECK(h.t == inf);
    CHECK(h.p == vec3_t<T>(0));
  }
  for (vec3_t<T> c : {vec3_t<T>(nan, 0, -5), vec3_t<T>(0, inf, -5), vec3_t<T>(0, 0, -inf)}) {
    hit_t<T> h;
    CHECK_FALSE(intersect(sphere_t<T>{c, T(1)}, good, T(0), inf, h));
  }
  const sphere_t<T> s{{T(0), T(0), T(-5)}, T(1)};
  for (vec3_t<T> d : {vec3_t<T>(0), vec3_t<T>(nan, 0, -1), vec3_t<T>(0, inf, -1),
                      vec3_t<T>(-inf, -inf, -inf), vec3_t<T>(0, 0, -0.0)}) {
    const ray_t<T> r({T(0), T(0), T(0)}, d);
    CHECK_FALSE(r.valid());
    hit_t<T> h;
    CHECK_FALSE(intersect(s, r, T(0), inf, h));
    CHECK(h.t == inf);
  }
  for (vec3_t<T> o : {vec3_t<T>(nan, 0, 0), vec3_t<T>(0, inf, 0), vec3_t<T>(0, 0, -inf)}) {
    hit_t<T> h;
    CHECK_FALSE(intersect(s, ray_t<T>(o, {T(0), T(0), T(-1)}), T(0), inf, h));
  }
  hit_t<T> h;  // NaN interval bounds: nothing passes t > NaN
  CHECK_FALSE(intersect(s, good, nan, inf, h));
  CHECK_FALSE(intersect(s, good, T(0), nan, h));
}

TEST_CASE_TEMPLATE("sphere: the naive discriminant misses a tiny far sphere; ours does not", T,
                   float, double) {
  // b^2 and c agree in almost every digit, so b*b - c is rounding noise; r^2 - |l|^2 is not.
  const double d = sizeof(T) == 4 ? 1e3 : 1e8, radius = sizeof(T) == 4 ? 0.1 : 1e-3;
  rng g(16);
  long naive_misses = 0, our_misses = 0, n = 0;
  stats st;
  for (int i = 0; i < 2000; ++i) {
    // A ray from the origin along `axis`, passing at m < 0.98 r from the centre: a sure hit.
    const vec3 axis = random_unit<double>(g);
    const vec3 perp = normalize_or_zero(glm::cross(axis, random_unit<double>(g)));
    const double m = radius * 0.98 * std::sqrt(g.uniform());
    const vec3 C = d * (1 + g.uniform()) * axis + m * perp;
    const sphere_t<T> s{vec3_t<T>(C), T(radius)};
    const ray_t<T> r{vec3_t<T>(0), vec3_t<T>(axis)};
    const reference ref = solve(s, r);
    REQUIRE(ref.hit);
    REQUIRE(LD(s.radius) - ref.m > band_units * unit_roundoff<T>() * ref.scale);
    ++n;
    hit_t<T> h;
    our_misses += !intersect(s, r, T(0), infinity<T>, h);
    naive_misses += !naive_hit(s, r);
    check_against_reference(s, r, st);
  }
  MESSAGE("[" << name<T>() << "] tiny far sphere (r " << radius << " at " << d << "): naive b*b - c "
              << "misses " << naive_misses << " of " << n << " rays through the disc; ours "
              << our_misses);
  CHECK(our_misses == 0);
  CHECK(naive_misses > n / 10);
  report<T>("tiny far sphere", st);
}

// From each hit, 40 spawned rays: 20 in uniformly random directions, 20 grazing the tangent
// plane (|w.n| from 1e-1 down to 1e-12 in double, 1e-6 in float), half of each to each side.
TEST_CASE_TEMPLATE("sphere: hit points lie within p_error of the surface; spawned rays never "
                   "re-hit from outside and always hit the far side from inside",
                   T, float, double) {
  rng g(17);
  long spheres = 0, outward = 0, rehits = 0, inward = 0, inward_fail = 0, inward_spheres = 0;
  double worst_ratio = 0;  // distance of p from the surface / its offset bound
  for (int i = 0; i < 1000; ++i) {
    const double radius = log_uniform(g, 1e-8, 1e8);
    vec3 C = vec3(random_unit<double>(g)) * log_uniform(g, 1e-8, 1e8);
    const sphere_t<T> s{vec3_t<T>(C), T(radius)};
    // A ray from 2..4 radii away aimed into the sphere.
    const vec3 O = C + vec3(random_unit<double>(g)) * radius * (2 + 2 * g.uniform());
    const vec3 aim = C + vec3(random_unit<double>(g)) * radius * 0.7 * g.uniform();
    const ray_t<T> r(vec3_t<T>(O), vec3_t<T>(aim - O));
    hit_t<T> h;
    if (!intersect(s, r, T(0), infinity<T>, h)) continue;  // (float: the sphere may be below ulp)
    ++spheres;
    const LD off_surface = std::abs(glm::length(up(h.p) - up(s.center)) - LD(s.radius));
    const LD bound = glm::dot(glm::abs(up(h.normal)), up(h.p_error));
    CHECK(off_surface <= bound);
    if (bound > 0) worst_ratio = std::max(worst_ratio, double(off_surface / bound));
    // Inward rays only make sense when the offset is small against the sphere.
    const bool inward_ok = LD(2) * bound < LD(s.radius) * LD(1e-3);
    inward_spheres += inward_ok;
    const onb_t<T> frame(h.normal);
    for (int k = 0; k < 40; ++k) {
      vec3_t<T> w = random_unit<T>(g);
      if (k % 2) {  // every other direction grazes: w.n = +-10^-(1..12) (float: 1..6)
        const T tilt = T((k % 4 == 1 ? 1 : -1) *
                         std::pow(10.0, -1 - (sizeof(T) == 4 ? 5 : 11) * g.uniform()));
        const double phi = 2 * pi<double> * g.uniform();
        w = normalize_or_zero(frame.to_world(
            vec3_t<T>(T(std::cos(phi)), T(std::sin(phi)), tilt)));
      }
      if (glm::dot(w, h.normal) == T(0)) continue;
      hit_t<T> again;
      const ray_t<T> spawned = spawn_ray(h, w);
      const bool got = intersect(s, spawned, T(0), infinity<T>, again);
      if (glm::dot(w, h.normal) > 0) {
        ++outward;
        rehits += got;
      } else if (inward_ok) {
        ++inward;
        const bool far_side = got && !again.front_face && again.t > T(0);
        inward_fail += !far_side;
      }
    }
  }
  MESSAGE("[" << name<T>() << "] reintersection: " << spheres << " spheres hit, " << outward
              << " outward spawned rays, " << rehits << " re-hit; " << inward << " inward rays on "
              << inward_spheres << " spheres, " << inward_fail << " failed to hit the far side; "
              << "worst |p - surface| / offset bound = " << worst_ratio);
  CHECK(spheres > 900);
  CHECK(rehits == 0);
  CHECK(inward_fail == 0);
  CHECK(inward > 10000);
}

TEST_CASE_TEMPLATE("sphere: hit record: normal, face, uv, contains_point", T, float, double) {
  const sphere_t<T> s{{T(0), T(0), T(-3)}, T(1)};
  hit_t<T> h;
  REQUIRE(intersect(s, ray_t<T>({T(0), T(0), T(0)}, {T(0), T(0), T(-1)}), T(0), infinity<T>, h));
  CHECK(h.t == doctest::Approx(2));
  CHECK(h.normal.z == doctest::Approx(1));
  CHECK(h.front_face);
  CHECK(h.facing_normal().z == doctest::Approx(1));
  CHECK(s.contains_point(h.p, T(1e-5)));
  CHECK_FALSE(s.contains_point(vec3_t<T>(0), T(1e-5)));
  // uv: latitude theta/pi from -y (0) to +y (1).
  REQUIRE(intersect(s, ray_t<T>({T(0), T(5), T(-3)}, {T(0), T(-1), T(0)}), T(0), infinity<T>, h));
  CHECK(h.uv.y == doctest::Approx(1));
  CHECK(h.uv.x >= T(0));
  CHECK(h.uv.x <= T(1));
  // t_max cuts the hit off; t_min beyond the near root gives the far one.
  CHECK_FALSE(intersect(s, ray_t<T>({T(0), T(0), T(0)}, {T(0), T(0), T(-1)}), T(0), T(1.5), h));
  REQUIRE(intersect(s, ray_t<T>({T(0), T(0), T(0)}, {T(0), T(0), T(-1)}), T(2.5), infinity<T>, h));
  CHECK(h.t == doctest::Approx(4));
  CHECK_FALSE(h.front_face);
  CHECK(occludes(s, ray_t<T>({T(0), T(0), T(0)}, {T(0), T(0), T(-1)}), T(0), T(10)));
}

// Shadow rays ask occludes(), which stops at sphere_root's decision; it must agree with
// intersect() on every ray: from inside, on and outside the sphere, tangent ones, invalid ones.
TEST_CASE_TEMPLATE("sphere: occludes agrees with intersect, ray by ray", T, float, double) {
  rng g(29);
  auto u = [&](double lo, double hi) { return T(lo + (hi - lo) * g.uniform()); };
  for (int i = 0; i < 20000; ++i) {
    const T scale = std::pow(T(10), u(-3, 3));
    sphere_t<T> s{vec3_t<T>(u(-1, 1), u(-1, 1), u(-1, 1)) * scale, u(0.01, 1) * scale};
    if (i % 97 == 0) s.radius = -s.radius;  // invalid: never hit
    const vec3_t<T> dir = normalize_or_zero(vec3_t<T>(u(-1, 1), u(-1, 1), u(-1, 1)));
    vec3_t<T> o = s.center + dir * (s.radius * u(0, 3));  // inside or outside
    if (i % 5 == 0) o = s.center + dir * s.radius;        // on it (up to rounding)
    vec3_t<T> d(u(-1, 1), u(-1, 1), u(-1, 1));
    if (i % 101 == 0) d = vec3_t<T>(std::numeric_limits<T>::quiet_NaN(), 0, 1);
    const ray_t<T> r(o, d);
    const T t_max = i % 3 == 0 ? infinity<T> : u(0, 4) * scale;
    hit_t<T> h;
    CHECK(occludes(s, r, T(0), t_max) == intersect(s, r, T(0), t_max, h));
  }
}

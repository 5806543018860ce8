// The plane (plane.hpp): the three constructions, ray-plane hits, parallel and near-parallel
// rays (errata B3), bounds, non-finite input, and reintersection of spawned rays.
#include <doctest/doctest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <zraka/core/rng.hpp>
#include <zraka/geometry/plane.hpp>
#include <zraka/geometry/spawn.hpp>

using namespace zraka;

namespace {

template <class... A>
std::string cat(const A&... a) {
  std::ostringstream s;
  s.precision(3);
  (s << ... << a);
  return s.str();
}
template <class T>
const char* type_name() {
  return sizeof(T) == 4 ? "float" : "double";
}

template <class T>
vec3_t<T> random_unit(rng& g) {
  const double z = 2 * g.uniform() - 1, phi = 2 * pi<double> * g.uniform();
  const double s = std::sqrt(std::max(0.0, 1 - z * z));
  return vec3_t<T>(vec3(s * std::cos(phi), s * std::sin(phi), z));
}
double log_uniform(rng& g, double lo, double hi) {
  return std::pow(10.0, lo + (hi - lo) * g.uniform());
}

template <class T>
bool hits(const plane_t<T>& pl, const ray_t<T>& r) {
  hit_t<T> h;
  return intersect(pl, r, T(0), infinity<T>, h);
}

}  // namespace

TEST_CASE_TEMPLATE("a plane from a point and normal, three points, or ax+by+cz+d=0", T, float,
                   double) {
  const auto p1 = plane_t<T>::from_point_normal({1, 2, 3}, {0, 0, 5});
  CHECK(p1.normal == vec3_t<T>(0, 0, 1));                                    // normalised
  const auto p2 = plane_t<T>::from_points({0, 0, 1}, {1, 0, 1}, {0, 1, 1});  // CCW from +z
  CHECK(p2.normal == vec3_t<T>(0, 0, 1));
  CHECK(p2.signed_distance({5, -7, 3}) == T(2));
  const auto p3 = plane_t<T>::from_points({0, 0, 1}, {0, 1, 1}, {1, 0, 1});  // CW: flipped
  CHECK(p3.normal == vec3_t<T>(0, 0, -1));
  // 2x + 0y + 0z - 6 = 0 is x = 3: N = (1,0,0), P0 = (3,0,0), the point nearest the origin.
  const auto p4 = plane_t<T>::from_equation(2, 0, 0, -6);
  CHECK(p4.normal == vec3_t<T>(1, 0, 0));
  CHECK(p4.point == vec3_t<T>(3, 0, 0));
  // A general one: the point satisfies the equation to rounding (relative 1e-6 float / 1e-14
  // double: a few roundings of numbers of size 10).
  const auto p5 = plane_t<T>::from_equation(1, -2, 3, 7);
  const T residual = p5.point.x - 2 * p5.point.y + 3 * p5.point.z + 7;
  CHECK(std::abs(residual) <= (sizeof(T) == 4 ? T(1e-5) : T(1e-13)));
  CHECK(std::abs(glm::length(p5.normal) - 1) <= (sizeof(T) == 4 ? T(1e-6) : T(1e-15)));
  // Huge coefficients do not overflow |(a,b,c)|.
  if constexpr (sizeof(T) == 8) {
    const auto big = plane_t<T>::from_equation(1e200, 1e200, 0, -2e200);
    CHECK(big.valid());
    CHECK(std::abs(big.point.x - 1) < 1e-15);
  }
  // No normal: invalid, never hit.
  CHECK_FALSE(plane_t<T>::from_equation(0, 0, 0, 1).valid());
  CHECK_FALSE(plane_t<T>::from_points({0, 0, 0}, {1, 1, 1}, {2, 2, 2}).valid());
  CHECK_FALSE(hits(plane_t<T>::from_equation(0, 0, 0, 1), ray_t<T>({0, 0, 1}, {0, 0, -1})));
}

TEST_CASE_TEMPLATE("a ray hits the plane at eq. 1.12's t with a full hit record", T, float,
                   double) {
  const auto floor = plane_t<T>::from_point_normal({0, -1, 0}, {0, 1, 0});
  hit_t<T> h;
  REQUIRE(intersect(floor, ray_t<T>({0, 3, 0}, {0, -1, 0}), T(0), infinity<T>, h));
  CHECK(h.t == T(4));  // exact: short dyadic numbers
  CHECK(h.p == vec3_t<T>(0, -1, 0));
  CHECK(h.normal == vec3_t<T>(0, 1, 0));
  CHECK(h.front_face);
  CHECK(h.p_error.x > T(0));
  // From below: the back face.
  REQUIRE(intersect(floor, ray_t<T>({2, -3, 0}, {0, 1, 0}), T(0), infinity<T>, h));
  CHECK(h.t == T(2));
  CHECK_FALSE(h.front_face);
  // Oblique: 45 degrees down from height 1 above the floor lands 2 further along x.
  REQUIRE(intersect(floor, ray_t<T>({0, 1, 0}, {1, -1, 0}), T(0), infinity<T>, h));
  CHECK(std::abs(h.t - T(2) * std::sqrt(T(2))) <= T(4) * std::numeric_limits<T>::epsilon());
  CHECK(h.p.y == T(-1));  // reprojected onto the plane
  CHECK(std::abs(h.p.x - T(2)) <= T(4) * std::numeric_limits<T>::epsilon());
  // Going away: the plane is behind (t < 0), which Listing 1.11 would accept via t = +inf or not.
  CHECK_FALSE(hits(floor, ray_t<T>({0, 1, 0}, {0, 1, 0})));
  // uv are distances along the plane.
  REQUIRE(intersect(floor, ray_t<T>({3, 1, 4}, {0, -1, 0}), T(0), infinity<T>, h));
  CHECK(std::abs(glm::length(h.uv) - T(5)) <= T(8) * std::numeric_limits<T>::epsilon());
}

TEST_CASE_TEMPLATE("t_min and t_max bound the plane hit (open interval)", T, float, double) {
  const auto pl = plane_t<T>::from_point_normal({0, 0, 0}, {0, 0, 1});
  const ray_t<T> r({0, 0, 2}, {0, 0, -1});  // t = 2
  hit_t<T> h;
  CHECK(intersect(pl, r, T(1), T(3), h));
  CHECK_FALSE(intersect(pl, r, T(2), T(3), h));
  CHECK_FALSE(intersect(pl, r, T(0), T(2), h));
  CHECK(intersect(pl, r, std::nextafter(T(2), T(0)), T(3), h));
  CHECK(intersect(pl, r, T(0), std::nextafter(T(2), T(3)), h));
}

TEST_CASE_TEMPLATE("parallel and near-parallel rays: no hit at infinity, no NaN (errata B3)", T,
                   float, double) {
  const auto pl = plane_t<T>::from_point_normal({0, 0, 0}, {0, 0, 1});
  // D.N = 0 exactly: above the plane and in it. Listing 1.11 divides by zero here.
  CHECK_FALSE(hits(pl, ray_t<T>({0, 0, 1}, {1, 0, 0})));
  CHECK_FALSE(hits(pl, ray_t<T>({0, 0, 0}, {1, 1, 0})));
  // D.N tiny but exact (an axis normal makes the dot product exact): a real, finite hit.
  const T tiny = sizeof(T) == 4 ? T(1e-30) : T(1e-300);
  hit_t<T> h;
  ray_t<T> r({0, 0, tiny}, {1, 0, 0});
  r.direction = {1, 0, -tiny};  // unit to rounding; set by hand so that D.N = -tiny exactly
  REQUIRE(intersect(pl, r, T(0), infinity<T>, h));
  CHECK(h.t == T(1));
  CHECK(is_finite(h.p));
  // So small that t overflows: no hit (not a hit at +inf).
  r.origin = {0, 0, 1};
  r.direction = {1, 0, -std::numeric_limits<T>::denorm_min()};
  CHECK_FALSE(hits(pl, r));
  // Random tilted planes and rays perpendicular to N to rounding: D.N is within its own
  // rounding error of 0, so the sign of t is unknown: never a hit, and never NaN.
  rng g(3);
  int hits_found = 0;
  for (int i = 0; i < 5000; ++i) {
    const vec3_t<T> n = random_unit<T>(g);
    const auto tilted = plane_t<T>::from_point_normal(random_unit<T>(g), n);
    const vec3_t<T> d = glm::cross(n, random_unit<T>(g));
    hit_t<T> hh;
    if (intersect(tilted, ray_t<T>(T(3) * random_unit<T>(g), d), T(0), infinity<T>, hh)) {
      ++hits_found;
      CHECK(std::isfinite(hh.t));
      CHECK(is_finite(hh.p));
    }
  }
  MESSAGE(cat(type_name<T>(), ": rays perpendicular to N to rounding that still hit: ", hits_found,
              " of 5000 (each with finite t and p)"));
}

TEST_CASE_TEMPLATE("NaN and inf input never hits a plane", T, float, double) {
  const T nan = std::numeric_limits<T>::quiet_NaN(), inf = infinity<T>;
  const ray_t<T> down({0, 0, 1}, {0, 0, -1});
  CHECK_FALSE(hits(plane_t<T>::from_point_normal({nan, 0, 0}, {0, 0, 1}), down));
  CHECK_FALSE(hits(plane_t<T>::from_point_normal({0, 0, 0}, {nan, 0, 1}), down));
  CHECK_FALSE(hits(plane_t<T>::from_point_normal({inf, 0, 0}, {0, 0, 1}), down));
  CHECK_FALSE(hits(plane_t<T>::from_point_normal({0, 0, 0}, {inf, 0, 1}), down));
  CHECK_FALSE(hits(plane_t<T>::from_equation(nan, 0, 1, 0), down));
  const auto pl = plane_t<T>::from_point_normal({0, 0, 0}, {0, 0, 1});
  CHECK_FALSE(hits(pl, ray_t<T>({nan, 0, 1}, {0, 0, -1})));
  CHECK_FALSE(hits(pl, ray_t<T>({0, 0, inf}, {0, 0, -1})));
  CHECK_FALSE(hits(pl, ray_t<T>({0, 0, 1}, {0, 0, 0})));
  ray_t<T> raw({0, 0, 1}, {0, 0, -1});
  raw.direction = {0, 0, nan};
  CHECK_FALSE(hits(pl, raw));
  // A hit so far away that O + tD overflows is no hit.
  if constexpr (sizeof(T) == 4) {
    ray_t<T> far({T(3e38), 0, 1}, {1, 0, 0});
    far.direction = {T(0.9), 0, T(-1e-38)};
    CHECK_FALSE(hits(pl, far));
  }
}

TEST_CASE_TEMPLATE("rays spawned from a plane never hit it again (1e-8 ... 1e8)", T, float,
                   double) {
  // Planes through points at distances log-uniform in [1e-8, 1e8] with random normals; primary
  // rays from a distance log-uniform relative to that; 4 rays leave each hit, 2 per side, of
  // which 2 graze the plane.
  rng g(4242);
  long spawned = 0, self_hits = 0, misses = 0;
  double worst_ratio = 0;  // exact distance of p from the plane / spawn offset
  for (int i = 0; i < 2000; ++i) {
    const double pos = log_uniform(g, -8, 8);
    const vec3 p0 = pos * vec3(random_unit<double>(g));
    const auto pl = plane_t<T>::from_point_normal(vec3_t<T>(p0), random_unit<T>(g));
    const vec3 n(pl.normal), along = vec3(random_unit<double>(g));
    const vec3 target = p0 + pos * log_uniform(g, -3, 2) * (along - glm::dot(along, n) * n);
    const vec3 o = target + pos * log_uniform(g, -3, 2) * vec3(random_unit<double>(g));
    hit_t<T> h;
    if (!intersect(pl, ray_t<T>(vec3_t<T>(o), vec3_t<T>(target - o)), T(0), infinity<T>, h)) {
      ++misses;  // only if rounding lost the hit (o nearly on the plane)
      continue;
    }
    // The true distance from the stored plane, in long double.
    using L = long double;
    L dist = 0, nn = 0;
    for (int k = 0; k < 3; ++k) {
      dist += (L(h.p[k]) - L(pl.point[k])) * L(pl.normal[k]);
      nn += L(pl.normal[k]) * L(pl.normal[k]);
    }
    const double offset = glm::dot(glm::abs(h.normal), h.p_error);
    worst_ratio = std::max(worst_ratio, double(std::abs(dist) / std::sqrt(nn)) / offset);
    for (int k = 0; k < 4; ++k) {
      vec3_t<T> w = random_unit<T>(g);
      if (k >= 2)  // grazing: 1e-4 ... 1e-1 radians off the surface
        w = glm::normalize(w - glm::dot(w, h.normal) * h.normal) +
            T(log_uniform(g, -4, -1)) * h.normal;
      if ((glm::dot(w, h.normal) > T(0)) != (k % 2 == 0)) w = -w;  // alternate the sides
      ++spawned;
      self_hits += hits(pl, spawn_ray(h, w)) ? 1 : 0;
    }
  }
  MESSAGE(cat(type_name<T>(), ": ", spawned, " spawned rays, ", self_hits,
              " hit their plane again; worst (distance of p from the plane) / (spawn offset) = ",
              worst_ratio, "; primary misses ", misses));
  CHECK(spawned >= 4000);
  CHECK(misses <= 20);
  CHECK(self_hits == 0);
  CHECK(worst_ratio < 1);
}

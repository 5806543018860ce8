#pragma once
// Chapter 1.5's second half (compare.cpp): the three triangle methods of triangle.hpp on random
// rays and on the shared edges of two meshes. A unit of its own, so that editing the render in
// main.cpp does not compile the comparison again.
#include <zraka/geometry/triangle.hpp>

#include <array>
#include <cstdint>

// The methods in the order of the table.
constexpr std::array<zraka::triangle_method, 3> triangle_methods = {
    zraka::triangle_method::edge_tests, zraka::triangle_method::moller_trumbore,
    zraka::triangle_method::watertight};

struct method_comparison {
  std::array<double, 3> agree{};     // % of random rays on which a float method agrees with double
  std::array<long, 3> cracks{};      // rays through shared edges and vertices that hit nothing
  long crack_rays = 0;
  std::array<double, 3> ns_float{}, ns_double{};  // nanoseconds per test
};

// Runs the comparison with `rays` random rays, prints its table and returns its numbers.
method_comparison compare_triangle_methods(std::uint64_t seed, int rays);

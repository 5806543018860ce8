#pragma once
// Assignment 00 (the template), reference solution: the mirror direction of d about a unit
// normal n, r = d - 2 (d.n) n (book 1.7).
#include <zraka/core/vec.hpp>

namespace course {

template <class T> zraka::vec3_t<T> reflect(const zraka::vec3_t<T>& d, const zraka::vec3_t<T>& n) {
  return d - T(2) * glm::dot(d, n) * n;
}

}  // namespace course

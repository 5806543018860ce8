#pragma once
// Assignment 00 (the template): the mirror direction of d about a unit normal n.
// See book/assignments/00-template/README.md.
#include <zraka/core/vec.hpp>

namespace course {

// The mirror image of the direction d (pointing towards the surface) about the unit normal n.
template <class T> zraka::vec3_t<T> reflect(const zraka::vec3_t<T>& d, const zraka::vec3_t<T>& n) {
  (void)d, (void)n;
  return zraka::vec3_t<T>(0);  // TODO
}

}  // namespace course

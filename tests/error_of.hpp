#pragma once
// The message of the zraka::error that f throws, or "(no error)": for tests that compare a
// reader's whole error message (test_obj_file.cpp, test_mesh_file.cpp).
#include <zraka/error.hpp>

#include <functional>
#include <string>

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const zraka::error& e) {
    return e.what();
  }
  return "(no error)";
}

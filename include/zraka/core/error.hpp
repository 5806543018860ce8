#pragma once
// zraka's one exception type, and the guard every chapter program's main() runs its work in:
// bad input ends with "error: ..." on stderr and exit code 1, never with a crash.
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

namespace zraka {

struct error : std::runtime_error {
  using std::runtime_error::runtime_error;
};

template <class F> int guarded(F&& body) {
  try {
    return body();
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << '\n';
    return 1;
  } catch (...) {  // not a std::exception: still no crash, still exit code 1
    std::cerr << "error: unknown exception\n";
    return 1;
  }
}

}  // namespace zraka

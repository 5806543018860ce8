#pragma once
// Wall-clock time for "error against run time" tables and summary lines.
#include <chrono>

namespace zraka {

class stopwatch {
 public:
  stopwatch() : start_(clock::now()) {}
  void restart() { start_ = clock::now(); }
  double seconds() const { return std::chrono::duration<double>(clock::now() - start_).count(); }

 private:
  using clock = std::chrono::steady_clock;
  clock::time_point start_;
};

}  // namespace zraka

// Tests for stopwatch.hpp.
#include <zraka/core/stopwatch.hpp>

#include <doctest/doctest.h>

#include <thread>

TEST_CASE("stopwatch: monotonic, non-negative, restartable") {
  zraka::stopwatch w;
  double last = w.seconds();
  CHECK(last >= 0);
  for (int i = 0; i < 1000; ++i) {
    const double now = w.seconds();
    CHECK(now >= last);  // steady_clock never goes back
    last = now;
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  CHECK(w.seconds() >= 0.019);
  w.restart();
  CHECK(w.seconds() < 0.019);
}

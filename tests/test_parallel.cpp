// parallel.hpp: every renderer's one parallel_for. Each item runs once, on any number of
// threads; the worker number names a thread; in_order merges results in item order whatever
// the finishing order; an exception in an item reaches the caller.
#include <zraka/core/parallel.hpp>

#include <doctest/doctest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

using namespace zraka;

TEST_CASE("parallel_for: every item exactly once, for 1, 2, 3 and 7 threads") {
  for (int threads : {1, 2, 3, 7}) {
    std::vector<std::atomic<int>> runs(1000);
    parallel_for(runs.size(), threads, [&](std::size_t i) { ++runs[i]; });
    int once = 0;
    for (const auto& r : runs) once += r == 1;
    CHECK(once == 1000);
  }
  int calls = 0;
  parallel_for(0, 2, [&](std::size_t) { ++calls; });  // no items: nothing runs
  CHECK(calls == 0);
}

TEST_CASE("parallel_for: worker numbers are 0 .. threads - 1 and at most one a thread at a time") {
  const int threads = 3;
  std::vector<std::atomic<int>> busy(threads);
  std::atomic<int> out_of_range{0}, shared{0};
  parallel_for(60, parallel_options{threads, false}, [&](std::size_t, int worker) {
    if (worker < 0 || worker >= threads) {
      ++out_of_range;
      return;
    }
    if (++busy[std::size_t(worker)] != 1) ++shared;  // another item on the same worker number
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    --busy[std::size_t(worker)];
  });
  CHECK(out_of_range == 0);
  CHECK(shared == 0);
}

TEST_CASE("in_order: results merged in item order, whatever order the items finish in") {
  // Floating-point sums depend on their order: adding in item order gives the serial sum's bits.
  const std::size_t n = 64;
  auto value = [](std::size_t i) { return 1.0 / double(3 * i + 1) * (i % 2 ? 1e8 : 1e-8); };
  double serial = 0, reversed = 0;
  for (std::size_t i = 0; i < n; ++i) serial += value(i), reversed += value(n - 1 - i);
  REQUIRE(serial != reversed);  // so the order shows in the bits
  for (int threads : {1, 2, 4}) {
    double sum = 0;
    std::vector<std::size_t> merged;
    in_order<double> results(n);
    parallel_for(n, threads, [&](std::size_t i) {
      std::this_thread::sleep_for(std::chrono::microseconds(50 * ((n - i) % 7)));  // finish out of order
      results.put(i, double(value(i)), [&](double v) {
        sum += v;
        merged.push_back(merged.size());
      });
    });
    CHECK(results.merged() == n);
    CHECK(merged.size() == n);
    CHECK(sum == serial);
  }
}

TEST_CASE("parallel_for: an exception in an item reaches the caller, and the other threads stop") {
  std::atomic<int> ran{0};
  CHECK_THROWS_WITH_AS(parallel_for(100000, 2,
                                    [&](std::size_t i) {
                                      ++ran;
                                      if (i == 10) throw std::runtime_error("item 10 failed");
                                    }),
                       "item 10 failed", std::runtime_error);
  CHECK(ran < 100000);  // the counter was emptied: the rest of the items never ran
  CHECK_THROWS_WITH_AS(parallel_for(4, -1, [](std::size_t) {}), doctest::Contains("--threads must be 0"), error);
}

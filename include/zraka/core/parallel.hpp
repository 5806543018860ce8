#pragma once
// One way to share a renderer's work among the cores, used by all of them: render.hpp's tiles,
// BDPT's bands of rows, the photons' chunks, SPPM's rows, Metropolis's bootstrap and chains.
//
// The work is items 0 .. n-1. Each thread takes the next item from a shared counter, so which
// thread does an item, and when, depends on timing; nothing else may. An item computes with
// random streams named by its index (rng.hpp) and writes its results by its index; results that
// must be summed are summed in item order (in_order, below), never in the order the threads
// finish. Then a seed gives the same bits for 1, 2 or 16 threads.
//
// An exception in an item stops the other threads after their current item and is rethrown to
// the caller (the first one, if several threads fail).
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/function_ref.hpp>
#include <zraka/core/limits.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <exception>
#include <mutex>
#include <optional>
#include <string>
#include <system_error>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include <unistd.h>  // isatty: the progress bar only draws on a terminal

namespace zraka {

struct parallel_options {
  int threads = 0;        // 0 = all hardware threads
  bool progress = false;  // a bar on stderr while the items run, drawn only when stderr is a terminal
};

// At most limits().threads_per_core per hardware thread: more gain nothing, and a typo such as
// 100000 would otherwise end in std::terminate when the system runs out of threads.
ZRAKA_COMPILED_FN int resolve_threads(int requested);

// body(item, worker) for every item in [0, n), on min(n, resolve_threads(opt.threads)) threads;
// worker (0 .. threads - 1) names the thread, for state a thread keeps between its items.
// Compiled once (compiled.hpp): a program's body is called through a pointer, once per item.
using parallel_body_ref = function_ref<void(std::size_t, int)>;
ZRAKA_COMPILED_FN void parallel_run(std::size_t n, const parallel_options& opt, parallel_body_ref body);

// fn(i) or fn(i, worker) for i in [0, n).
template <class Fn> void parallel_for(std::size_t n, const parallel_options& opt, Fn&& fn) {
  if constexpr (std::is_invocable_v<Fn&, std::size_t, int>) {
    auto body = [&fn](std::size_t i, int worker) { fn(i, worker); };
    parallel_run(n, opt, parallel_body_ref(body));
  } else {
    auto body = [&fn](std::size_t i, int) { fn(i); };
    parallel_run(n, opt, parallel_body_ref(body));
  }
}
template <class Fn> void parallel_for(std::size_t n, int threads, Fn&& fn) {
  parallel_for(n, parallel_options{threads, false}, std::forward<Fn>(fn));
}

// The results of items that are summed in item order, whichever thread finishes first:
// put(i, result, merge) keeps the result until every item before i is in, then calls merge on
// each waiting result in item order, one at a time. Only results waiting for an earlier item are
// held in memory.
template <class R> class in_order {
 public:
  explicit in_order(std::size_t n) : waiting_(n) {}
  template <class Merge> void put(std::size_t i, R&& result, Merge&& merge) {
    std::lock_guard<std::mutex> lock(mutex_);
    waiting_[i] = std::move(result);
    for (; next_ < waiting_.size() && waiting_[next_]; ++next_) {
      merge(*waiting_[next_]);
      waiting_[next_].reset();
    }
  }
  // Items merged so far: all of them once every put() has returned.
  std::size_t merged() const { return next_; }

 private:
  std::vector<std::optional<R>> waiting_;
  std::size_t next_ = 0;
  std::mutex mutex_;
};

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
// [listing parallel-run]
ZRAKA_COMPILED_FN void parallel_run(std::size_t n, const parallel_options& opt, parallel_body_ref body) {
  const int threads = resolve_threads(opt.threads);
  if (n == 0) return;
  std::atomic<std::size_t> next{0}, done{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&](int id) {
    try {
      for (std::size_t i = next++; i < n; i = next++) {
        body(i, id);
        ++done;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      failed = true;
      next = n;  // the others stop after their current item
    }
  };
  const int count = int(std::min<std::size_t>(std::size_t(threads), n));
  std::vector<std::thread> pool;
  try {
    for (int i = 1; i < count; ++i) pool.emplace_back(worker, i);
  } catch (const std::system_error& e) {  // no more threads: stop those started, then say so
    next = n;
    for (auto& th : pool) th.join();
    throw error("cannot start " + std::to_string(threads) + " threads (" + e.what() + "); try fewer --threads");
  }
  if (opt.progress && isatty(STDERR_FILENO)) {  // this thread draws the bar while the others work, then joins in
    std::thread drawer([&] {
      while (done < n && !failed) {
        const int pct = int(100 * done / n);
        std::fprintf(stderr, "\r[%-40s] %3d%%", std::string(std::size_t(pct * 40 / 100), '#').c_str(), pct);
        std::this_thread::sleep_for(std::chrono::milliseconds(100));
      }
    });
    worker(0);
    for (auto& th : pool) th.join();
    drawer.join();
    std::fprintf(stderr, "\r%60s\r", "");
  } else {
    worker(0);
    for (auto& th : pool) th.join();
  }
  if (failure) std::rethrow_exception(failure);
}
// [end]

ZRAKA_COMPILED_FN int resolve_threads(int requested) {
  if (requested < 0) throw error("--threads must be 0 (all) or positive, got " + std::to_string(requested));
  const long long cap = max_threads();
  if (requested > cap)
    throw error("--threads " + std::to_string(requested) + " is more than " + std::to_string(cap) + " (" +
                std::to_string(limits().threads_per_core) + " per core on this " +
                std::to_string(std::max(1u, std::thread::hardware_concurrency())) + "-core machine) " +
                raise_hint("threads_per_core"));
  if (requested > 0) return requested;
  return int(std::max(1u, std::thread::hardware_concurrency()));
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

// Tests for error.hpp: guarded() turns exceptions into "error: ..." and exit code 1.
#include <zraka/core/error.hpp>

#include <doctest/doctest.h>

#include <sstream>

namespace {
// Captures std::cerr while alive.
struct capture_cerr {
  std::ostringstream text;
  std::streambuf* old = std::cerr.rdbuf(text.rdbuf());
  ~capture_cerr() { std::cerr.rdbuf(old); }
};
}  // namespace

TEST_CASE("error: guarded passes the body's result through") {
  capture_cerr cap;
  CHECK(zraka::guarded([] { return 0; }) == 0);
  CHECK(zraka::guarded([] { return 3; }) == 3);
  CHECK(cap.text.str().empty());
}

TEST_CASE("error: guarded returns 1 and prints the message") {
  capture_cerr cap;
  CHECK(zraka::guarded([]() -> int { throw zraka::error("--width must be positive"); }) == 1);
  CHECK(cap.text.str() == "error: --width must be positive\n");
}

TEST_CASE("error: any std::exception, and non-standard throws, end the same way") {
  capture_cerr cap;
  CHECK(zraka::guarded([]() -> int { throw std::out_of_range("index 7"); }) == 1);
  CHECK(zraka::guarded([]() -> int { throw 42; }) == 1);
  CHECK(cap.text.str() == "error: index 7\nerror: unknown exception\n");
}

TEST_CASE("error: zraka::error is a std::runtime_error") {
  const zraka::error e("x");
  const std::runtime_error& base = e;
  CHECK(std::string(base.what()) == "x");
}

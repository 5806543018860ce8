// convergence.hpp: the log-log slope fit, the table, the CSV round trip, and a real Monte Carlo
// run whose error falls as 1/sqrt(N).
#include <zraka/core/rng.hpp>
#include <zraka/sampling/convergence.hpp>

#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>
#include <sstream>
#include <unistd.h>

using zraka::convergence_log;

TEST_CASE("the slope fit is exact on power laws") {
  std::vector<double> n, e, z;
  for (int k = 0; k <= 20; ++k) {
    n.push_back(std::ldexp(1.0, k));
    e.push_back(3.0 / std::sqrt(n.back()));
    z.push_back(0.25 * std::pow(n.back(), -1.0));
  }
  // Exact up to rounding of log/pow: 1e-12.
  auto f = zraka::fit_loglog(n, e);
  CHECK(f.points == 21);
  CHECK(f.slope == doctest::Approx(-0.5).epsilon(1e-12));
  CHECK(f.intercept == doctest::Approx(std::log(3.0)).epsilon(1e-12));
  CHECK(f.slope_stderr < 1e-12);
  CHECK(zraka::fit_loglog(n, z).slope == doctest::Approx(-1.0).epsilon(1e-12));
  // A zero error (an exact estimate) has no logarithm: it is skipped, not a -inf in the fit.
  e[4] = 0;
  e[5] = std::nan("");
  f = zraka::fit_loglog(n, e);
  CHECK(f.points == 19);
  CHECK(f.slope == doctest::Approx(-0.5).epsilon(1e-12));
  // Too few points, or all at one n: no slope.
  CHECK(std::isnan(zraka::fit_loglog({1.0}, {1.0}).slope));
  CHECK(std::isnan(zraka::fit_loglog({4.0, 4.0, 4.0}, {1.0, 2.0, 3.0}).slope));
}

TEST_CASE("a recorder for an integral: rows, fit and table with all columns") {
  convergence_log log("test integral");
  for (int k = 2; k <= 10; ++k) {
    zraka::estimator e;
    const double n = std::ldexp(1.0, k);
    for (int i = 0; i < int(n); ++i) e.add(i % 2 ? 1.0 : 0.0);  // mean 0.5 exactly
    log.add(1e-3 * n, e, 0.5 + 2.0 / std::sqrt(n));         // error 2/sqrt(n) by design
  }
  CHECK(log.rows().size() == 9);
  CHECK(log.rows()[0].n == 4);
  CHECK(log.fit().slope == doctest::Approx(-0.5).epsilon(1e-9));
  CHECK(log.fit("std_error").slope == doctest::Approx(-0.5).epsilon(0.02));  // sqrt(n/(n-1)) bends it
  const std::string t = log.table();
  std::istringstream lines(t);
  std::string title, header;
  std::getline(lines, title);
  std::getline(lines, header);
  CHECK(title == "test integral");
  for (const char* col : {"n", "seconds", "estimate", "abs_error", "std_error"})
    CHECK(header.find(col) != std::string::npos);
  int rows = 0;
  for (std::string line; std::getline(lines, line);) {
    ++rows;
    std::istringstream fields(line);
    int count = 0;
    for (std::string f; fields >> f;) ++count;
    CHECK(count == 5);  // every row has every column
  }
  CHECK(rows == 9);
  CHECK(log.slope_line().find("-0.500") != std::string::npos);
}

TEST_CASE("NaN values print as n/a, and bad use is an error") {
  convergence_log log("x");
  zraka::estimator one;
  one.add(1.0);  // one sample: no standard error
  log.add(0.0, one, 1.0);
  CHECK(log.table().find("n/a") != std::string::npos);
  CHECK_THROWS_AS(log.add(2, 0.0, {1.0}), zraka::error);  // three columns, one value
  CHECK_THROWS_AS(convergence_log("y", {"a"}, "b"), zraka::error);
  CHECK_THROWS_AS(log.fit("nope"), zraka::error);
  CHECK(log.slope_line().find("n/a") != std::string::npos);  // one row: no slope
}

TEST_CASE("a renderer's layout: spp, seconds, rmse, relmse") {
  convergence_log log("render", {"rmse", "relmse"}, "rmse", "spp");
  for (std::uint64_t spp = 1; spp <= 1024; spp *= 2)
    log.add(spp, 0.01 * double(spp), {0.3 / std::sqrt(double(spp)), 0.09 / double(spp)});
  CHECK(log.fit().slope == doctest::Approx(-0.5).epsilon(1e-12));
  CHECK(log.fit("relmse").slope == doctest::Approx(-1.0).epsilon(1e-12));  // MSE falls as 1/N
  CHECK(log.csv().rfind("spp,seconds,rmse,relmse\n", 0) == 0);
  CHECK(log.table().find("spp") != std::string::npos);
}

TEST_CASE("CSV round trip, written atomically") {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("zraka_test_convergence_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  convergence_log log("pi");
  log.add(16, 1.5e-7, {3.25, 0.10840734641020688, 0.40311288741492751});
  log.add(1ull << 40, 12.345678901234567, {3.1415926, 5.358979e-8, std::nan("")});
  log.add(32, 0.0, {1.0 / 3.0, 1e-300, 0.0});
  const auto path = dir / "pi.csv";
  log.write_csv(path);
  // Only the file: the temporary it was written through is gone.
  CHECK(std::distance(std::filesystem::directory_iterator(dir), {}) == 1);
  const auto back = convergence_log::read_csv(path);
  CHECK(back.title() == "pi.csv");
  CHECK(back.n_name() == "n");
  CHECK(back.columns() == log.columns());
  REQUIRE(back.rows().size() == log.rows().size());
  for (std::size_t i = 0; i < log.rows().size(); ++i) {
    const auto &a = log.rows()[i], &b = back.rows()[i];
    CHECK(a.n == b.n);
    CHECK(a.seconds == b.seconds);  // %.17g round-trips doubles exactly
    for (std::size_t c = 0; c < a.values.size(); ++c)
      CHECK(((a.values[c] == b.values[c]) || (std::isnan(a.values[c]) && std::isnan(b.values[c]))));
  }
  CHECK(back.fit().slope == log.fit().slope);  // the fit column came back as abs_error
  CHECK_THROWS_AS(convergence_log::parse_csv("n,seconds,a\n1,2\n", "t"), zraka::error);
  CHECK_THROWS_AS(convergence_log::parse_csv("n,seconds,a\n1,2,x\n", "t"), zraka::error);
  CHECK_THROWS_AS(convergence_log::parse_csv("n,time,a\n", "t"), zraka::error);
  CHECK_THROWS_AS(convergence_log::read_csv(dir / "missing.csv"), zraka::error);
  std::filesystem::remove_all(dir);
}

TEST_CASE("a real Monte Carlo run: error and standard error fall as 1/sqrt(N)") {
  // E[U^2] = 1/3 for U uniform on [0,1). For each N, 8 independent runs (one stream each); the
  // row's error is their root mean square error, which scatters far less than a single run's.
  convergence_log log("E[U^2]", {"rms_error", "std_error"}, "rms_error");
  for (std::uint32_t k = 6; k <= 16; ++k) {
    double sq = 0, se = 0;
    for (std::uint32_t run = 0; run < 8; ++run) {
      zraka::rng g(1, run, k);
      zraka::estimator e;
      for (std::uint64_t i = 0; i < (1ull << k); ++i) {
        const double u = g.uniform();
        e.add(u * u);
      }
      sq += (e.mean() - 1.0 / 3.0) * (e.mean() - 1.0 / 3.0) / 8;
      se += e.standard_error() / 8;
    }
    log.add(1ull << k, 0.0, {std::sqrt(sq), se});
  }
  // The standard error is smooth in N: -0.5 within 1%. The log of an RMS over 8 runs has sd
  // ~0.25; over 11 rows spread over ln N that makes the slope's sd ~0.035, and 0.15 is 4 sd.
  CHECK(log.fit("std_error").slope == doctest::Approx(-0.5).epsilon(0.01));
  CHECK(std::abs(log.fit().slope + 0.5) < 0.15);
}

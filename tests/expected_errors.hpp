#pragma once
// Shared by the tests of the readers (scene files, OBJ, Mitsuba XML): the message of the
// zraka::error a call throws, and the check that each malformed file of a folder gives the
// error its first line expects.
#include <zraka/core/error.hpp>

#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace zraka_test {

// What f throws as a zraka::error, or "(no error)".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const zraka::error& e) {
    return e.what();
  }
  return "(no error)";
}

// Every file of `dir` ending in `ext` starts with a line `open EXPECTED close`; `load(file)` must
// throw "FILE" + EXPECTED (the whole message, or one that starts with it unless `whole`).
inline void check_expected_errors(const std::filesystem::path& dir, const std::string& ext, const std::string& open,
                                  const std::string& close, std::size_t at_least, bool whole,
                                  const std::function<void(const std::filesystem::path&)>& load) {
  REQUIRE(std::filesystem::is_directory(dir));
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ext) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  CHECK(files.size() >= at_least);
  for (const std::filesystem::path& f : files) {
    std::ifstream in(f);
    std::string first;
    std::getline(in, first);
    INFO(f.filename().string());
    REQUIRE_MESSAGE(first.rfind(open, 0) == 0, f.filename().string() << " has no '" << open << "' line");
    REQUIRE(first.size() >= open.size() + close.size());
    REQUIRE(first.compare(first.size() - close.size(), close.size(), close) == 0);
    const std::string expected = f.string() + first.substr(open.size(), first.size() - open.size() - close.size());
    const std::string got = error_of([&] { load(f); });
    if (whole) CHECK_MESSAGE(got == expected, "got: " << got << "\nexpected: " << expected);
    else CHECK_MESSAGE(got.rfind(expected, 0) == 0, "got: " << got << "\nexpected to start with: " << expected);
  }
}

}  // namespace zraka_test

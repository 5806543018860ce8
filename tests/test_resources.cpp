// Tests for resources.hpp: one compiled-in root, overridable with ZRAKA_ROOT.
#include <zraka/core/resources.hpp>

#include <doctest/doctest.h>

#include <cstdlib>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;

TEST_CASE("resources: the compiled-in root holds scenes/ or kernels/") {
  ::unsetenv("ZRAKA_ROOT");
  CHECK(zraka::resource_root() == fs::path(ZRAKA_RESOURCE_DIR));
  CHECK(fs::is_directory(zraka::resource_root()));
}

TEST_CASE("resources: ZRAKA_ROOT overrides the root") {
  const fs::path dir = fs::temp_directory_path() / ("zraka-test-root-" + std::to_string(::getpid()));
  fs::create_directories(dir / "scenes");
  std::ofstream(dir / "scenes" / "only-here.txt") << "x";
  ::setenv("ZRAKA_ROOT", dir.c_str(), 1);
  CHECK(zraka::resource_root() == dir);
  CHECK(zraka::resource_path("scenes/only-here.txt") == dir / "scenes" / "only-here.txt");
  // A missing resource names the full path it tried and how to fix it.
  CHECK_THROWS_WITH_AS(zraka::resource_path("scenes/missing.yaml"),
                       ("resource not found: " + (dir / "scenes" / "missing.yaml").string() +
                        " (set ZRAKA_ROOT to the folder that holds scenes/ and kernels/)")
                           .c_str(),
                       zraka::error);
  // An empty ZRAKA_ROOT counts as unset.
  ::setenv("ZRAKA_ROOT", "", 1);
  CHECK(zraka::resource_root() == fs::path(ZRAKA_RESOURCE_DIR));
  ::unsetenv("ZRAKA_ROOT");
  fs::remove_all(dir);
}

TEST_CASE("resources: absolute paths are returned as they are") {
  CHECK(zraka::resource_path("/no/such/file.txt") == fs::path("/no/such/file.txt"));
}

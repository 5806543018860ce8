// Tests for atomic_file.hpp: whole file or nothing, and no temporary left behind.
#include <zraka/atomic_file.hpp>

#include <doctest/doctest.h>

#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace {
struct temp_dir {
  fs::path path = fs::temp_directory_path() / ("zraka-test-atomic-" + std::to_string(::getpid()));
  temp_dir() { fs::create_directories(path); }
  ~temp_dir() { fs::remove_all(path); }
  std::size_t entries() const {
    return std::size_t(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
  }
};
std::string read(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}
}  // namespace

TEST_CASE("atomic_file: writes the bytes, replaces an old file, leaves no temporary") {
  temp_dir dir;
  const fs::path f = dir.path / "out.txt";
  zraka::write_file_atomically(f, std::string("first\0binary", 12));
  CHECK(read(f) == std::string("first\0binary", 12));
  zraka::write_file_atomically(f, "second");
  CHECK(read(f) == "second");
  CHECK(dir.entries() == 1);  // only out.txt: the temporary was renamed, not left
}

TEST_CASE("atomic_file: a missing folder throws and leaves nothing") {
  temp_dir dir;
  const fs::path f = dir.path / "no-such-folder" / "out.txt";
  CHECK_THROWS_WITH_AS(zraka::write_file_atomically(f, "x"),
                       doctest::Contains("does not exist"), zraka::error);
  CHECK_FALSE(fs::exists(f.parent_path()));
  CHECK(dir.entries() == 0);
}

TEST_CASE("atomic_file: a target that cannot be replaced throws and leaves no temporary") {
  temp_dir dir;
  fs::create_directory(dir.path / "taken");  // a folder of that name: rename must fail
  CHECK_THROWS_AS(zraka::write_file_atomically(dir.path / "taken", "x"), zraka::error);
  CHECK(dir.entries() == 1);
  CHECK(fs::is_directory(dir.path / "taken"));
}

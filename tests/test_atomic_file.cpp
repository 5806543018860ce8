// Tests for atomic_file.hpp: whole file or nothing, and no temporary left behind (on errors,
// SIGINT, SIGTERM; after SIGKILL the next write removes it); names that cannot be outputs.
#include <zraka/core/atomic_file.hpp>

#include <doctest/doctest.h>

#include <csignal>
#include <fstream>
#include <sstream>

#include <sys/wait.h>

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

TEST_CASE("atomic_file: names that cannot be an output file are refused before anything is written") {
  temp_dir dir;
  CHECK_THROWS_WITH_AS(zraka::write_file_atomically("", "x"), "the output file name is empty", zraka::error);
  // What `--out ""` becomes once a program appends ".png": a hidden file, never meant.
  CHECK_THROWS_WITH_AS(zraka::write_file_atomically(dir.path / ".png", "x"),
                       doctest::Contains("the name is only an extension or hidden (an empty --out?)"), zraka::error);
  CHECK_THROWS_WITH_AS(zraka::write_file_atomically(dir.path.string() + "/", "x"),
                       doctest::Contains("it names a folder, not a file"), zraka::error);
  CHECK_THROWS_WITH_AS(zraka::write_file_atomically(dir.path / "..", "x"),
                       doctest::Contains("it names a folder, not a file"), zraka::error);
  CHECK(dir.entries() == 0);
}

TEST_CASE("atomic_file: a temporary left by a killed process is removed by the next write of its target") {
  temp_dir dir;
  // A process that has ended: its PID is free (the child has been reaped).
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  const fs::path stale = dir.path / (".out.png.zraka-tmp." + std::to_string(child));
  const fs::path running = dir.path / ".out.png.zraka-tmp.1";  // PID 1 runs: its file is left alone
  const fs::path other = dir.path / (".other.png.zraka-tmp." + std::to_string(child));  // another target
  for (const fs::path& p : {stale, running, other}) std::ofstream(p) << "half";
  zraka::write_file_atomically(dir.path / "out.png", "whole");
  CHECK_FALSE(fs::exists(stale));
  CHECK(fs::exists(running));
  CHECK(fs::exists(other));
  CHECK(read(dir.path / "out.png") == "whole");
}

TEST_CASE("atomic_file: SIGINT and SIGTERM during a write remove the temporary, then end the process") {
  for (const int sig : {SIGINT, SIGTERM}) {
    temp_dir dir;
    const fs::path tmp = dir.path / ".out.png.zraka-tmp.x";
    const pid_t child = ::fork();
    if (child == 0) {  // the state in the middle of write_file_atomically: a registered temporary
      std::ofstream(tmp) << "half";
      const zraka::detail::tmp_guard guard(tmp);
      ::raise(sig);
      ::_exit(0);  // not reached: the signal ends the process
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == sig);
    CHECK_FALSE(fs::exists(tmp));
  }
  // After a write the handlers are gone again: the dispositions are what they were.
  struct sigaction now {};
  ::sigaction(SIGINT, nullptr, &now);
  const bool restored = now.sa_handler != zraka::detail::atomic_tmp_on_signal;
  CHECK(restored);
}

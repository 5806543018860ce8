#pragma once
// Reading an input file (scene, mesh, patch set, image) whole, safely: only a regular file is
// read, and only up to limits().file_bytes. A directory, a FIFO, a device (/dev/zero, a
// terminal), a socket or /dev/stdin is refused by name *before* it is opened for reading, so a
// FIFO with no writer cannot block the program and an endless stream cannot fill the memory.
//
//   const std::string text = zraka::read_input_file(path);   // throws zraka::error
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/limits.hpp>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace zraka {

namespace detail {
inline const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Closes the descriptor on every path out.
struct fd_guard {
  int fd;
  ~fd_guard() {
    if (fd >= 0) ::close(fd);
  }
};
}  // namespace detail

// The bytes of the regular file `path`; errors start with the path as given.
ZRAKA_COMPILED_FN std::string read_input_file(const std::filesystem::path& path);

#if ZRAKA_COMPILED_DEFINITIONS  // compiled.hpp
ZRAKA_COMPILED_FN std::string read_input_file(const std::filesystem::path& path) {
  const std::string name = path.string();
  struct stat st {};
  // stat follows symbolic links: /dev/stdin is judged by what it points to.
  if (::stat(name.c_str(), &st) != 0) throw error(name + ": cannot open: " + std::strerror(errno));
  if (!S_ISREG(st.st_mode))
    throw error(name + ": is " + detail::file_kind(st.st_mode) + "; only regular files are read");
  const std::uint64_t limit = limits().file_bytes;
  // O_NONBLOCK: should the path have been replaced by a FIFO since stat, open must not wait.
  const detail::fd_guard g{::open(name.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
  if (g.fd < 0) throw error(name + ": cannot open: " + std::strerror(errno));
  if (::fstat(g.fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw error(name + ": is " + detail::file_kind(st.st_mode) + "; only regular files are read");
  const auto size_error = [&](const std::string& size) {
    return error(name + ": the file size " + size + " bytes is more than the limit of " + std::to_string(limit) +
                 " " + raise_hint("file_bytes"));
  };
  if (std::uint64_t(st.st_size) > limit) throw size_error(std::to_string(st.st_size));
  std::string bytes;
  bytes.reserve(std::size_t(st.st_size));
  char buf[65536];
  for (;;) {  // to the end, not to st_size: some files (in /proc) report 0 and still have data
    const ssize_t n = ::read(g.fd, buf, sizeof buf);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw error(name + ": cannot read: " + std::strerror(errno));
    }
    if (n == 0) break;
    bytes.append(buf, std::size_t(n));
    if (bytes.size() > limit) throw size_error("over " + std::to_string(limit));
  }
  return bytes;
}
#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

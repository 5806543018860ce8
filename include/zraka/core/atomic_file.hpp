#pragma once
// Writing a file so that readers never see half of it: write a temporary file beside the
// target, then rename it over the target (rename is atomic within one file system).
//
// The temporary is ".NAME.zraka-tmp.PID" beside NAME. It is removed on every error path, and
// also when the process is stopped by SIGINT or SIGTERM while writing (a handler, installed
// only during the write, removes it and then lets the signal do what it did before). A process
// killed by a signal it cannot catch (SIGKILL) leaves it behind; the next write of the same
// target removes every such leftover whose process no longer runs.
//
// A name that cannot be what the user meant is refused: an empty name, a folder, or a name that
// is only an extension (".png", what `--out ""` becomes once a program appends ".png"); so is a
// name whose folder does not exist or cannot be written. Programs check every output name this
// way before they start to render (output_file, program_options), so that a failed run leaves
// no output behind.
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <string>
#include <string_view>

#include <signal.h>
#include <unistd.h>

namespace zraka {

namespace detail {

constexpr std::string_view atomic_tmp_tag = ".zraka-tmp.";

// The temporaries being written now, for the signal handler: fixed slots of plain chars, since a
// handler may only call async-signal-safe functions (unlink, sigaction, raise).
struct atomic_tmp_registry {
  static constexpr int slots = 16;
  static constexpr std::size_t max_path = 4096;
  std::atomic<bool> used[slots] = {};
  char path[slots][max_path] = {};
  std::mutex mutex;  // for install/restore, never taken in the handler
  int writers = 0;
  struct sigaction old_int {}, old_term {};
};
inline atomic_tmp_registry& tmp_registry() {
  static atomic_tmp_registry r;
  return r;
}

inline void atomic_tmp_on_signal(int sig) {
  atomic_tmp_registry& r = tmp_registry();
  for (int i = 0; i < atomic_tmp_registry::slots; ++i)
    if (r.used[i].load()) ::unlink(r.path[i]);
  ::sigaction(sig, sig == SIGINT ? &r.old_int : &r.old_term, nullptr);  // what it did before ...
  ::raise(sig);                                                       // ... it does now
}

// Registers `tmp` for removal on SIGINT/SIGTERM while it exists; unregisters on destruction.
class tmp_guard {
 public:
  explicit tmp_guard(const std::filesystem::path& tmp) : tmp_(tmp) {
    atomic_tmp_registry& r = tmp_registry();
    const std::string s = tmp.string();
    if (s.size() < atomic_tmp_registry::max_path)
      for (int i = 0; i < atomic_tmp_registry::slots && slot_ < 0; ++i) {
        bool expected = false;
        if (!r.used[i].compare_exchange_strong(expected, true)) continue;  // claim, then fill
        std::memcpy(r.path[i], s.c_str(), s.size() + 1);
        slot_ = i;
      }
    std::lock_guard<std::mutex> lock(r.mutex);
    if (r.writers++ == 0) {
      struct sigaction sa {};
      sa.sa_handler = atomic_tmp_on_signal;
      sigemptyset(&sa.sa_mask);
      ::sigaction(SIGINT, &sa, &r.old_int);
      ::sigaction(SIGTERM, &sa, &r.old_term);
    }
  }
  ~tmp_guard() {
    std::error_code ignored;
    std::filesystem::remove(tmp_, ignored);  // gone already after a successful rename
    atomic_tmp_registry& r = tmp_registry();
    if (slot_ >= 0) r.used[slot_] = false;
    std::lock_guard<std::mutex> lock(r.mutex);
    if (--r.writers == 0) {
      ::sigaction(SIGINT, &r.old_int, nullptr);
      ::sigaction(SIGTERM, &r.old_term, nullptr);
    }
  }
  tmp_guard(const tmp_guard&) = delete;
  tmp_guard& operator=(const tmp_guard&) = delete;

 private:
  std::filesystem::path tmp_;
  int slot_ = -1;
};

// Removes ".NAME.zraka-tmp.PID" beside the target for every PID that no longer runs (left by a
// process killed with SIGKILL). A running writer's temporary is left alone.
inline void remove_stale_temporaries(const std::filesystem::path& dir, const std::string& name) {
  const std::string prefix = "." + name + std::string(atomic_tmp_tag);
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string f = it->path().filename().string();
    if (f.size() <= prefix.size() || f.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string pid = f.substr(prefix.size());
    if (pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    const long p = std::stol(pid);
    if (p == long(::getpid())) continue;
    if (p > 0 && ::kill(pid_t(p), 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

}  // namespace detail

// Throws zraka::error for a name that cannot be an output file (see the top of this file).
ZRAKA_COMPILED_FN void check_output_name(const std::filesystem::path& path);
// Writes `bytes` to `path` through a temporary beside it (see the top of this file).
ZRAKA_COMPILED_FN void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

// Compiled into zraka::compiled (compiled.hpp) unless header-only.
#if ZRAKA_COMPILED_DEFINITIONS
ZRAKA_COMPILED_FN void check_output_name(const std::filesystem::path& path) {
  const std::string name = path.filename().string();
  if (path.empty()) throw error("the output file name is empty");
  if (name.empty() || name == "." || name == "..")
    throw error("cannot write '" + path.string() + "': it names a folder, not a file");
  if (name[0] == '.' && name.find('.', 1) == std::string::npos)
    throw error("cannot write '" + path.string() + "': the name is only an extension or hidden (an empty --out?)");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw error("cannot write '" + path.string() + "': it is a folder");
  const std::filesystem::path folder = path.parent_path();
  if (!folder.empty() && !std::filesystem::exists(folder, ec))
    throw error("cannot write '" + path.string() + "': the folder '" + folder.string() + "' does not exist");
  if (!folder.empty() && !std::filesystem::is_directory(folder, ec))
    throw error("cannot write '" + path.string() + "': '" + folder.string() + "' is not a folder");
  if (::access(folder.empty() ? "." : folder.c_str(), W_OK) != 0)
    throw error("cannot write '" + path.string() + "': the folder '" + (folder.empty() ? "." : folder.string()) +
                "' is not writable (" + std::strerror(errno) + ")");
}

ZRAKA_COMPILED_FN void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  check_output_name(path);
  const auto dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  if (!std::filesystem::is_directory(dir))
    throw error("cannot write " + path.string() + ": folder " + dir.string() + " does not exist");
  detail::remove_stale_temporaries(dir, path.filename().string());
  // Built piecewise: GCC 12 gives a false -Wrestrict on `"." + std::string` once inlined.
  std::string tmp_name = ".";
  tmp_name += path.filename().string();
  tmp_name += detail::atomic_tmp_tag;
  tmp_name += std::to_string(::getpid());
  const auto tmp = dir / tmp_name;
  const detail::tmp_guard guard(tmp);  // removes it on every way out, and on SIGINT/SIGTERM
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.flush();
    if (!out) throw error("cannot write " + path.string() + " (disk full or no permission?)");
  }
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw error("cannot write " + path.string() + ": " + ec.message());
}

#endif  // ZRAKA_COMPILED_DEFINITIONS

}  // namespace zraka

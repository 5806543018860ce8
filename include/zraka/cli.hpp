#pragma once
// Command lines of the chapter programs (CLI11). Bad arguments are bad input like any other:
// "error: ..." on stderr and exit code 1 (CLI11's own macro would exit with codes 100-115).
//   CLI::App app{"..."};  app.add_option(...);
//   if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;
#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>

namespace zraka {

// Returns the exit code when the program should stop now (--help, or a bad argument).
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "error: %s (see --help)\n", e.what());
    return 1;
  }
  return std::nullopt;
}

}  // namespace zraka

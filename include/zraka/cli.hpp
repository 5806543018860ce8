#pragma once
// Command lines of the chapter programs (CLI11). Bad arguments are bad input like any other:
// "error: ..." on stderr and exit code 1 (CLI11's own macro would exit with codes 100-115).
//   CLI::App app{"..."};  app.add_option(...);
//   if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;
#include <zraka/error.hpp>
#include <zraka/limits.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

namespace zraka {

// Returns the exit code when the program should stop now (--help, or a bad argument).
// Every program also takes --limit NAME=N (repeatable), which raises or lowers one of the
// input limits of limits.hpp for this run.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  static std::vector<std::string> limit_args;  // static: the option keeps referring to it
  limit_args.clear();
  if (!app.get_option_no_throw("--limit"))
    app.add_option("--limit", limit_args,
                   "raise or lower an input limit, NAME=N (repeatable): file_bytes, yaml_nodes, triangles, "
                   "vertices, patches, pixels, samples, threads_per_core (scenes/README.md lists the defaults)")
        ->allow_extra_args(false);
  // --help shows every default, also of options added without capture_default_str().
  for (CLI::Option* o : app.get_options())
    if (o->get_default_str().empty() && o->get_expected_min() > 0) o->capture_default_str();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    std::fprintf(stderr, "error: %s (see --help)\n", e.what());
    return 1;
  }
  try {
    for (const std::string& a : limit_args) set_limit(limits(), a);
  } catch (const error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return std::nullopt;
}

}  // namespace zraka

#pragma once
// Command lines of the programs. Bad arguments are bad input like any other: "error: ..." on
// stderr and exit code 1 (CLI11's own macro would exit with codes 100-115).
//   zraka::compiled_app app{"..."};  app.add_option("--n", n, "...");
//   if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;
//
// Why a front and not CLI11 itself (issue 12, the student's loop): Debian's CLI11 2.1.2 is
// header-only, and every unit that includes it compiles its validators, formatter and parser
// again (~6 CPU-s of a chapter's ~9). This header declares a small fixed interface and includes
// no CLI11; its definitions (cli_impl.hpp) are compiled once into zraka::compiled, or included
// right here when a project uses zraka header-only (compiled.hpp says how).
#include <zraka/core/compiled.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>


namespace zraka {

// One option of a cli_app, for the few settings a program changes after adding it.
class cli_option {
 public:
  explicit cli_option(void* native) : native_(native) {}
  ZRAKA_COMPILED_FN cli_option* expected(int n);             // takes exactly n values
  ZRAKA_COMPILED_FN cli_option* expected(int min, int max);  // takes min..max values
  ZRAKA_COMPILED_FN cli_option* delimiter(char c);           // "1,2,3" is three values
  ZRAKA_COMPILED_FN cli_option* capture_default_str();       // --help shows the current value
  ZRAKA_COMPILED_FN cli_option* default_str(const std::string& text);  // --help shows this instead

 private:
  void* native_;  // the CLI::Option
};

// The value types an option can bind (each an overload, so a wrong type is a compile error).
#define ZRAKA_CLI_VALUE_TYPES(X)                                                                   \
  X(int) X(unsigned) X(long) X(unsigned long) X(long long) X(unsigned long long) X(float) X(double) \
  X(std::string) X(std::vector<int>) X(std::vector<double>) X(std::vector<float>)                  \
  X(std::vector<std::string>) X(std::optional<int>) X(std::optional<unsigned long>)                \
  X(std::optional<unsigned long long>) X(std::optional<double>) X(std::optional<std::string>)

class cli_app {
 public:
  ZRAKA_COMPILED_FN explicit cli_app(const std::string& description);
  ZRAKA_COMPILED_FN ~cli_app();
  cli_app(const cli_app&) = delete;
  cli_app& operator=(const cli_app&) = delete;

#define ZRAKA_CLI_DECLARE(T) \
  ZRAKA_COMPILED_FN cli_option* add_option(const std::string& names, T& value, const std::string& help);
  ZRAKA_CLI_VALUE_TYPES(ZRAKA_CLI_DECLARE)
#undef ZRAKA_CLI_DECLARE
  ZRAKA_COMPILED_FN cli_option* add_flag(const std::string& names, bool& value, const std::string& help);

  // Options added from now on show their value as the default in --help.
  ZRAKA_COMPILED_FN void always_capture_default();
  // How often the option was given on the command line (after parsing).
  ZRAKA_COMPILED_FN std::size_t count(const std::string& name) const;

  struct impl;
  impl& native() { return *impl_; }

 private:
  std::unique_ptr<impl> impl_;
};

// Returns the exit code when the program should stop now (--help, or a bad argument).
// Every program also takes --limit NAME=N (repeatable), which raises or lowers one of the
// input limits of limits.hpp for this run.
ZRAKA_COMPILED_FN std::optional<int> parse_command_line(cli_app& app, int argc, char** argv);

}  // namespace zraka

#if ZRAKA_COMPILED_DEFINITIONS
#include <zraka/app/cli_impl.hpp>
#endif

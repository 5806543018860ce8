#pragma once
// The definitions behind cli.hpp, on CLI11. Compiled once into zraka::compiled (src/compiled.cpp), or
// included by cli.hpp itself for a header-only use (see there). Nothing else includes it.
#include <zraka/app/cli.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/limits.hpp>

#include <CLI/CLI.hpp>

#include <cstdio>
#include <deque>

namespace zraka {

struct cli_app::impl {
  CLI::App app;
  std::deque<cli_option> options;         // stable addresses for the handles handed out
  std::vector<std::string> limit_args;    // --limit NAME=N
  explicit impl(const std::string& description) : app(description) {}
  cli_option* keep(CLI::Option* o) { return &options.emplace_back(o); }
};

namespace detail {
inline CLI::Option* native(void* o) { return static_cast<CLI::Option*>(o); }
}  // namespace detail

ZRAKA_COMPILED_FN cli_option* cli_option::expected(int n) { detail::native(native_)->expected(n); return this; }
ZRAKA_COMPILED_FN cli_option* cli_option::expected(int min, int max) {
  detail::native(native_)->expected(min, max);
  return this;
}
ZRAKA_COMPILED_FN cli_option* cli_option::delimiter(char c) { detail::native(native_)->delimiter(c); return this; }
ZRAKA_COMPILED_FN cli_option* cli_option::capture_default_str() {
  detail::native(native_)->capture_default_str();
  return this;
}
ZRAKA_COMPILED_FN cli_option* cli_option::default_str(const std::string& text) {
  detail::native(native_)->default_str(text);
  return this;
}

ZRAKA_COMPILED_FN cli_app::cli_app(const std::string& description) : impl_(std::make_unique<impl>(description)) {}
ZRAKA_COMPILED_FN cli_app::~cli_app() = default;

#define ZRAKA_CLI_DEFINE(T)                                                                        \
  ZRAKA_COMPILED_FN cli_option* cli_app::add_option(const std::string& names, T& value, const std::string& help) { \
    return impl_->keep(impl_->app.add_option(names, value, help));                                 \
  }
ZRAKA_CLI_VALUE_TYPES(ZRAKA_CLI_DEFINE)
#undef ZRAKA_CLI_DEFINE

ZRAKA_COMPILED_FN cli_option* cli_app::add_flag(const std::string& names, bool& value, const std::string& help) {
  return impl_->keep(impl_->app.add_flag(names, value, help));
}
ZRAKA_COMPILED_FN void cli_app::always_capture_default() { impl_->app.option_defaults()->always_capture_default(); }
ZRAKA_COMPILED_FN std::size_t cli_app::count(const std::string& name) const { return impl_->app.count(name); }

ZRAKA_COMPILED_FN std::optional<int> parse_command_line(cli_app& program, int argc, char** argv) {
  cli_app::impl& in = program.native();
  CLI::App& app = in.app;
  in.limit_args.clear();
  if (!app.get_option_no_throw("--limit"))
    app.add_option("--limit", in.limit_args,
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
    for (const std::string& a : in.limit_args) set_limit(limits(), a);
  } catch (const error& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return std::nullopt;
}

}  // namespace zraka

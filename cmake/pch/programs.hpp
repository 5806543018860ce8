// The precompiled header of the chapter programs, the benchmarks and the assignments' render
// programs (cmake/ZrakaPch.cmake): the common part and CLI11.
#pragma once
#include "common.hpp"

// CLI11 2.1.2 (Debian 12) is header-only and costs each program about 2.5 s of parsing, which the
// precompiled header removes, and 4-6 s of code generation at -O3, which no precompiled header
// can: its validator objects at namespace scope and the virtual functions of its formatter and
// config reader are emitted in every translation unit that includes it. Parsing a command line
// is not hot code, so CLI11's own functions are compiled at -O0 here (measured on 1.2-sphere,
// user CPU seconds: 11.5 without a PCH, 10.3 with it at -O3, 6.8 with it at -O0). Every standard
// header CLI11 includes is already included above, so no standard template is defined, and
// optimised, inside this region. A program built without this PCH (an outside project) compiles
// CLI11 at its own optimisation level; the behaviour is the same.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("O0")
#include <CLI/CLI.hpp>
#pragma GCC pop_options
#else
#include <CLI/CLI.hpp>
#endif

// The precompiled header of the chapter programs, the benchmarks and the assignments' render
// programs (cmake/ZrakaPch.cmake): the common part and CLI11.
#pragma once
#include "common.hpp"

// CLI11 2.1.2 (Debian 12) is header-only. Its parsing (~2.5 CPU-s per program) is what this
// precompiled header removes; its code generation it cannot: its validator objects at namespace
// scope and the virtual functions of its formatter and config reader are emitted in every unit
// that includes it (3/4 of 1.2-sphere's object code is CLI11). Parsing a command line is not hot
// code, so CLI11's own functions are compiled at -O0 here. Measured on 1.2-sphere, CPU seconds on
// a loaded machine: 11.5 without a PCH, 10.3 with it and CLI11 at -O3, 6.8 with CLI11 at -O0.
// Every standard header CLI11 includes is included above first, so no standard template is
// defined inside this region (templates are optimised as where they are defined). A program
// built without this PCH (an outside project) compiles CLI11 at its own level; same behaviour.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC push_options
#pragma GCC optimize("O0")
#include <CLI/CLI.hpp>
#pragma GCC pop_options
#else
#include <CLI/CLI.hpp>
#endif

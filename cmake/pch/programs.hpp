// The precompiled header of the chapter programs, the benchmarks and the assignments' render
// programs (cmake/ZrakaPch.cmake): the common part. No CLI11 any more: the command-line layer is
// compiled once into zraka::compiled (include/zraka/app/cli.hpp), so no program's unit includes CLI11.
// (CLI11 here would emit its validators and formatter in every unit that uses this header, even
// one that never parses a command line: ~6 CPU-s each, measured on 1.2-sphere.)
#pragma once
#include "common.hpp"

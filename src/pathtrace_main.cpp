// The `pathtrace` program as a function (include/zraka/app/pathtrace_main.hpp), compiled into
// zraka::compiled where zraka is built with yaml-cpp (ZRAKA_COMPILED_SCENE_FILE). A unit of its own,
// beside compiled.cpp, so the two build in parallel; only this header's definitions are here.
#ifndef ZRAKA_COMPILED_SCENE_FILE
#error "build src/pathtrace_main.cpp through the zraka_compiled target, with yaml-cpp"
#endif
#define ZRAKA_COMPILING_PATHTRACE_MAIN
#include <zraka/app/pathtrace_main.hpp>

// The `whitted` program as a function (include/zraka/app/whitted_main.hpp), compiled into
// zraka::compiled where zraka is built with yaml-cpp (ZRAKA_COMPILED_SCENE_FILE). A unit of its own;
// only this header's definitions are here.
#ifndef ZRAKA_COMPILED_SCENE_FILE
#error "build src/whitted_main.cpp through the zraka_compiled target, with yaml-cpp"
#endif
#define ZRAKA_COMPILING_WHITTED_MAIN
#include <zraka/app/whitted_main.hpp>

// The chapters' mis reference (include/zraka/app/reference.hpp), compiled into zraka::compiled where
// zraka is built with yaml-cpp (ZRAKA_COMPILED_SCENE_FILE). A unit of its own, beside compiled.cpp,
// so the two build in parallel; only this header's definitions are here.
#ifndef ZRAKA_COMPILED_SCENE_FILE
#error "build src/reference.cpp through the zraka_compiled target, with yaml-cpp"
#endif
#define ZRAKA_COMPILING_REFERENCE
#include <zraka/app/reference.hpp>

// The preview window of --window (include/zraka/app/preview_window.hpp), compiled into zraka::compiled
// where zraka is built with GLFW and libepoxy (ZRAKA_COMPILED_GL). A unit of its own, so that
// only a program that opens the window pulls it, and GLFW with it, out of the static library.
#ifndef ZRAKA_COMPILED_GL
#error "build src/preview_window.cpp through the zraka_compiled target, with GLFW and libepoxy"
#endif
#define ZRAKA_COMPILING_PREVIEW  // this header's definitions only: the rest are in compiled.cpp
#include <zraka/app/preview_window.hpp>

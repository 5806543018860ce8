// gl.hpp's shader helpers, compiled into zraka::compiled where zraka is built with GLFW and
// libepoxy (ZRAKA_COMPILED_GL). A unit of its own, so that only a program that draws with OpenGL
// pulls it, and GLFW and libepoxy with it, out of the static library.
#ifndef ZRAKA_COMPILED_GL
#error "build src/gl.cpp through the zraka_compiled target, with GLFW and libepoxy"
#endif
#define ZRAKA_COMPILING_GL  // this header's definitions only
#include <zraka/gpu/gl.hpp>

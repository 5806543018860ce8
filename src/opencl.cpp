// The OpenCL host side (cl.hpp) and the real-time renderer's costly members (realtime.hpp),
// compiled into zraka::compiled where zraka is built with OpenCL (ZRAKA_COMPILED_OPENCL). A unit of
// its own, so that only a program that uses OpenCL pulls it, and libOpenCL with it, out of the
// static library.
#ifndef ZRAKA_COMPILED_OPENCL
#error "build src/opencl.cpp through the zraka_compiled target, with OpenCL"
#endif
#define ZRAKA_COMPILING_OPENCL  // these headers' definitions only: the rest are in compiled.cpp
#include <zraka/gpu/cl.hpp>
#include <zraka/gpu/realtime.hpp>

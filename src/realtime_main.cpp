// The `realtime` program as a function (include/zraka/app/realtime_main.hpp), compiled into
// zraka::compiled where zraka is built with yaml-cpp, OpenCL, GLFW and libepoxy. A unit of its own,
// so that only a program that calls it pulls it, and OpenCL and GLFW with it, out of the library.
#if !defined(ZRAKA_COMPILED_SCENE_FILE) || !defined(ZRAKA_COMPILED_OPENCL) || !defined(ZRAKA_COMPILED_GL)
#error "build src/realtime_main.cpp through the zraka_compiled target, with yaml-cpp, OpenCL, GLFW and libepoxy"
#endif
#define ZRAKA_COMPILING_REALTIME_MAIN
#include <zraka/app/realtime_main.hpp>

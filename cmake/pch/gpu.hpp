// The precompiled header of the programs that drive OpenCL or OpenGL (chapters whose needs.txt
// names OpenCL or glfw, and bench/realtime_bench): scene.hpp's part plus the C APIs' own headers,
// which are large (libepoxy's gl.h alone is ~0.3 s to parse) and which no other program includes,
// and zraka's headers over them.
// The macros are set as cl.hpp and gl.hpp set them, so the headers see the same thing either way.
#pragma once
#include "scene.hpp"

#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120  // as in include/zraka/gpu/cl.hpp
#endif
#if __has_include(<CL/cl.h>)
#include <CL/cl.h>
#endif
#if __has_include(<epoxy/gl.h>) && __has_include(<GLFW/glfw3.h>)  // as in include/zraka/gpu/gl.hpp
#include <epoxy/gl.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#endif

#include <zraka/gpu/cl.hpp>
#include <zraka/gpu/gl.hpp>
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/gpu/realtime.hpp>

#pragma once
// The host side of OpenCL (book 3.3), on the plain C API: find platforms and devices, pick one
// by index, read kernel files from the resource root and build them with options (-D switches),
// and turn every error code into a zraka::error that says what failed. Later chapters (the
// real-time path tracer) reuse all of it.
//
// Everything is OpenCL 1.2, the version of the kernel language PoCL and most GPUs accept.
// Handles are owned by small move-only wrappers that release them, so an exception never leaks.
// Link with OpenCL::OpenCL (needs.txt: OpenCL; a test's first line: // links: OpenCL).
// Where zraka was built with OpenCL (ZRAKA_COMPILED_OPENCL), the functions marked ZRAKA_OPENCL_FN,
// here and in realtime.hpp, are compiled once into zraka::compiled, in a unit of their own
// (src/opencl.cpp), as compiled.hpp explains; header-only they are inline.
#ifndef CL_TARGET_OPENCL_VERSION
#define CL_TARGET_OPENCL_VERSION 120
#endif
#if __has_include(<CL/cl.h>)  // without the headers this header is empty (the chapter is skipped)
#include <CL/cl.h>
#include <zraka/core/compiled.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(ZRAKA_COMPILED_OPENCL)
#define ZRAKA_OPENCL_FN
#else
#define ZRAKA_OPENCL_FN inline
#endif
#if !defined(ZRAKA_COMPILED_OPENCL) || defined(ZRAKA_COMPILING_OPENCL)  // src/opencl.cpp
#define ZRAKA_OPENCL_DEFINITIONS 1
#else
#define ZRAKA_OPENCL_DEFINITIONS 0
#endif

namespace zraka::cl {

ZRAKA_OPENCL_FN std::string error_name(cl_int code);
ZRAKA_OPENCL_FN void check(cl_int code, const std::string& what);

#if ZRAKA_OPENCL_DEFINITIONS
// [listing cl-errors]
// The names of the codes a student meets most; the number is always printed too.
ZRAKA_OPENCL_FN std::string error_name(cl_int code) {
  switch (code) {
    case CL_SUCCESS: return "CL_SUCCESS";
    case CL_DEVICE_NOT_FOUND: return "CL_DEVICE_NOT_FOUND";
    case CL_OUT_OF_RESOURCES: return "CL_OUT_OF_RESOURCES";
    case CL_OUT_OF_HOST_MEMORY: return "CL_OUT_OF_HOST_MEMORY";
    case CL_MEM_OBJECT_ALLOCATION_FAILURE: return "CL_MEM_OBJECT_ALLOCATION_FAILURE";
    case CL_BUILD_PROGRAM_FAILURE: return "CL_BUILD_PROGRAM_FAILURE";
    case CL_INVALID_VALUE: return "CL_INVALID_VALUE";
    case CL_INVALID_DEVICE: return "CL_INVALID_DEVICE";
    case CL_INVALID_CONTEXT: return "CL_INVALID_CONTEXT";
    case CL_INVALID_HOST_PTR: return "CL_INVALID_HOST_PTR";
    case CL_INVALID_MEM_OBJECT: return "CL_INVALID_MEM_OBJECT";
    case CL_INVALID_BUILD_OPTIONS: return "CL_INVALID_BUILD_OPTIONS";
    case CL_INVALID_PROGRAM_EXECUTABLE: return "CL_INVALID_PROGRAM_EXECUTABLE";
    case CL_INVALID_KERNEL_NAME: return "CL_INVALID_KERNEL_NAME";
    case CL_INVALID_ARG_INDEX: return "CL_INVALID_ARG_INDEX";
    case CL_INVALID_ARG_VALUE: return "CL_INVALID_ARG_VALUE";
    case CL_INVALID_ARG_SIZE: return "CL_INVALID_ARG_SIZE";  // e.g. sizeof(array), not sizeof(cl_mem)
    case CL_INVALID_KERNEL_ARGS: return "CL_INVALID_KERNEL_ARGS";
    case CL_INVALID_WORK_GROUP_SIZE: return "CL_INVALID_WORK_GROUP_SIZE";
    case CL_INVALID_GLOBAL_WORK_SIZE: return "CL_INVALID_GLOBAL_WORK_SIZE";
    case CL_INVALID_BUFFER_SIZE: return "CL_INVALID_BUFFER_SIZE";
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";  // the ICD loader found no platform
    default: return "OpenCL error";
  }
}

ZRAKA_OPENCL_FN void check(cl_int code, const std::string& what) {
  if (code != CL_SUCCESS)
    throw error(what + " failed: " + error_name(code) + " (" + std::to_string(code) + ")");
}
// [end]
#endif

// No platform at all: no ICD installed (e.g. pocl-opencl-icd), or none registered in
// /etc/OpenCL/vendors. Programs may catch this one to fall back or to skip.
struct no_platform : error {
  no_platform()
      : error("no OpenCL platform found (clGetPlatformIDs returned -1001, "
              "CL_PLATFORM_NOT_FOUND_KHR): install an OpenCL driver, e.g. the CPU one "
              "'pocl-opencl-icd', and check /etc/OpenCL/vendors") {}
};

// A move-only owner of one OpenCL handle; Release is clReleaseX.
template <class H, cl_int (*Release)(H)> class handle {
 public:
  handle() = default;
  explicit handle(H h) : h_(h) {}
  handle(handle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
  handle& operator=(handle&& o) noexcept {
    if (this != &o) {
      reset();
      h_ = std::exchange(o.h_, nullptr);
    }
    return *this;
  }
  handle(const handle&) = delete;
  handle& operator=(const handle&) = delete;
  ~handle() { reset(); }
  H get() const { return h_; }
  explicit operator bool() const { return h_ != nullptr; }
  void reset() {
    if (h_) Release(h_);
    h_ = nullptr;
  }

 private:
  H h_ = nullptr;
};

using context_handle = handle<cl_context, clReleaseContext>;
using queue_handle = handle<cl_command_queue, clReleaseCommandQueue>;
using program_handle = handle<cl_program, clReleaseProgram>;
using kernel_handle = handle<cl_kernel, clReleaseKernel>;
using buffer = handle<cl_mem, clReleaseMemObject>;

namespace detail {
ZRAKA_OPENCL_FN std::string platform_string(cl_platform_id p, cl_platform_info what);
ZRAKA_OPENCL_FN std::string device_string(cl_device_id d, cl_device_info what);
#if ZRAKA_OPENCL_DEFINITIONS
ZRAKA_OPENCL_FN std::string platform_string(cl_platform_id p, cl_platform_info what) {
  std::size_t n = 0;
  check(clGetPlatformInfo(p, what, 0, nullptr, &n), "clGetPlatformInfo");
  std::string s(n, '\0');
  check(clGetPlatformInfo(p, what, n, s.data(), nullptr), "clGetPlatformInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}
ZRAKA_OPENCL_FN std::string device_string(cl_device_id d, cl_device_info what) {
  std::size_t n = 0;
  check(clGetDeviceInfo(d, what, 0, nullptr, &n), "clGetDeviceInfo");
  std::string s(n, '\0');
  check(clGetDeviceInfo(d, what, n, s.data(), nullptr), "clGetDeviceInfo");
  while (!s.empty() && s.back() == '\0') s.pop_back();
  return s;
}
#endif
template <class V> V device_value(cl_device_id d, cl_device_info what) {
  V v{};
  check(clGetDeviceInfo(d, what, sizeof(V), &v, nullptr), "clGetDeviceInfo");
  return v;
}
}  // namespace detail

// One device, with what a program prints about it (book: "print device, size, time together").
struct device_info {
  cl_platform_id platform = nullptr;
  cl_device_id device = nullptr;
  std::string platform_name, device_name, version, c_version;
  cl_uint compute_units = 0;
  bool fp64 = false;
};

ZRAKA_OPENCL_FN std::vector<device_info> list_devices();
ZRAKA_OPENCL_FN device_info pick_device(int index);

#if ZRAKA_OPENCL_DEFINITIONS
// [listing cl-devices]
// Every device of every platform, numbered in this order (that number is --device).
ZRAKA_OPENCL_FN std::vector<device_info> list_devices() {
  cl_uint n_platforms = 0;
  const cl_int rc = clGetPlatformIDs(0, nullptr, &n_platforms);
  if (rc == -1001 || (rc == CL_SUCCESS && n_platforms == 0)) throw no_platform();
  check(rc, "clGetPlatformIDs");
  std::vector<cl_platform_id> platforms(n_platforms);
  check(clGetPlatformIDs(n_platforms, platforms.data(), nullptr), "clGetPlatformIDs");

  std::vector<device_info> out;
  for (cl_platform_id p : platforms) {
    cl_uint n = 0;
    const cl_int drc = clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &n);
    if (drc == CL_DEVICE_NOT_FOUND) continue;  // a platform without devices is not an error
    check(drc, "clGetDeviceIDs");
    std::vector<cl_device_id> devices(n);
    check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, n, devices.data(), nullptr), "clGetDeviceIDs");
    for (cl_device_id d : devices) {
      device_info info{p, d, detail::platform_string(p, CL_PLATFORM_NAME),
                       detail::device_string(d, CL_DEVICE_NAME),
                       detail::device_string(d, CL_DEVICE_VERSION),
                       detail::device_string(d, CL_DEVICE_OPENCL_C_VERSION),
                       detail::device_value<cl_uint>(d, CL_DEVICE_MAX_COMPUTE_UNITS),
                       detail::device_value<cl_device_fp_config>(d, CL_DEVICE_DOUBLE_FP_CONFIG) != 0};
      out.push_back(std::move(info));
    }
  }
  return out;
}

ZRAKA_OPENCL_FN device_info pick_device(int index) {
  auto all = list_devices();
  if (all.empty()) throw error("the OpenCL platforms have no devices");
  if (index < 0 || std::size_t(index) >= all.size())
    throw error("--device " + std::to_string(index) + " does not exist: there are " +
                std::to_string(all.size()) + " device(s), 0.." + std::to_string(all.size() - 1) +
                " (see --list)");
  return all[std::size_t(index)];
}
// [end]
#endif

// A context on one device and one in-order queue to it (Defs 3.3.3 and 3.3.4: the queue is
// made from the context *and* the device, errata D3).
struct context {
  device_info device;
  context_handle ctx;
  queue_handle queue;

  explicit context(device_info d);
  // A device buffer, filled with `bytes` of host data when host is given.
  buffer make_buffer(cl_mem_flags flags, std::size_t bytes, const void* host = nullptr) const;
  void read(const buffer& b, std::size_t bytes, void* host) const {
    check(clEnqueueReadBuffer(queue.get(), b.get(), CL_TRUE, 0, bytes, host, 0, nullptr, nullptr),
          "clEnqueueReadBuffer");
  }
  void write(const buffer& b, std::size_t bytes, const void* host) const {
    check(clEnqueueWriteBuffer(queue.get(), b.get(), CL_TRUE, 0, bytes, host, 0, nullptr, nullptr),
          "clEnqueueWriteBuffer");
  }
  void finish() const { check(clFinish(queue.get()), "clFinish"); }
};

ZRAKA_OPENCL_FN std::string read_kernel_file(const std::filesystem::path& file);
ZRAKA_OPENCL_FN program_handle build_program_files(const context& c, const std::vector<std::filesystem::path>& files,
                                                   const std::string& options = "");

#if ZRAKA_OPENCL_DEFINITIONS
ZRAKA_OPENCL_FN context::context(device_info d) : device(std::move(d)) {
  cl_int rc = CL_SUCCESS;
  ctx = context_handle(clCreateContext(nullptr, 1, &device.device, nullptr, nullptr, &rc));
  check(rc, "clCreateContext");
  // clCreateCommandQueue is the 1.2 call; 2.0 renamed it, and PoCL accepts both.
  queue = queue_handle(clCreateCommandQueue(ctx.get(), device.device, 0, &rc));
  check(rc, "clCreateCommandQueue");
}

// [listing cl-buffer]
// A device buffer; with host data it is copied at creation (CL_MEM_COPY_HOST_PTR, errata B13).
ZRAKA_OPENCL_FN buffer context::make_buffer(cl_mem_flags flags, std::size_t bytes, const void* host) const {
  if (host) flags |= CL_MEM_COPY_HOST_PTR;
  cl_int rc = CL_SUCCESS;
  buffer b(clCreateBuffer(ctx.get(), flags, bytes, const_cast<void*>(host), &rc));
  check(rc, "clCreateBuffer (" + std::to_string(bytes) + " bytes)");
  return b;
}
// [end]

// The text of a kernel file, found through the resource root ("kernels/x.cl").
ZRAKA_OPENCL_FN std::string read_kernel_file(const std::filesystem::path& file) {
  const auto path = resource_path(file.string());
  std::ifstream in(path, std::ios::binary);
  if (!in) throw error("cannot open kernel file " + path.string());
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// [listing cl-build]
// Builds one program from kernel files, joined in order (e.g. kernels/rng.cl, then a kernel
// that uses it). Each file starts with a #line directive, so the compiler's messages name the
// real file and line. On failure the error holds every file name, the options and the full log.
// PoCL caches binaries by source text and options: set POCL_KERNEL_CACHE=0 while editing.
ZRAKA_OPENCL_FN program_handle build_program_files(const context& c,
                                                   const std::vector<std::filesystem::path>& files,
                                                   const std::string& options) {
  std::vector<std::string> texts;
  std::string names;
  for (const auto& f : files) {
    texts.push_back("#line 1 \"" + f.generic_string() + "\"\n" + read_kernel_file(f));
    names += (names.empty() ? "" : ", ") + f.generic_string();
  }
  std::vector<const char*> ptrs;
  std::vector<std::size_t> lengths;
  for (const auto& t : texts) {
    ptrs.push_back(t.data());
    lengths.push_back(t.size());
  }
  cl_int rc = CL_SUCCESS;
  program_handle prog(clCreateProgramWithSource(c.ctx.get(), cl_uint(ptrs.size()), ptrs.data(),
                                                lengths.data(), &rc));
  check(rc, "clCreateProgramWithSource (" + names + ")");
  rc = clBuildProgram(prog.get(), 1, &c.device.device, options.c_str(), nullptr, nullptr);
  if (rc != CL_SUCCESS) {
    std::size_t n = 0;
    std::string log;
    if (clGetProgramBuildInfo(prog.get(), c.device.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &n) ==
        CL_SUCCESS) {
      log.resize(n);
      clGetProgramBuildInfo(prog.get(), c.device.device, CL_PROGRAM_BUILD_LOG, n, log.data(),
                            nullptr);
      while (!log.empty() && (log.back() == '\0' || log.back() == '\n')) log.pop_back();
    }
    throw error("cannot build OpenCL program " + names + " (options '" + options +
                "'): " + error_name(rc) + " (" + std::to_string(rc) + "); build log:\n" + log);
  }
  return prog;
}
// [end]
#endif

inline program_handle build_program(const context& c, const std::filesystem::path& file,
                                    const std::string& options = "") {
  return build_program_files(c, {file}, options);
}

inline kernel_handle make_kernel(const program_handle& p, const std::string& name) {
  cl_int rc = CL_SUCCESS;
  kernel_handle k(clCreateKernel(p.get(), name.c_str(), &rc));
  check(rc, "clCreateKernel '" + name + "'");
  return k;
}

// clSetKernelArg, checked; compiled once, not in each set_arg below (compiled.hpp).
ZRAKA_OPENCL_FN void set_arg_bytes(const kernel_handle& k, cl_uint index, std::size_t size, const void* value);
#if ZRAKA_OPENCL_DEFINITIONS
ZRAKA_OPENCL_FN void set_arg_bytes(const kernel_handle& k, cl_uint index, std::size_t size, const void* value) {
  check(clSetKernelArg(k.get(), index, size, value), "clSetKernelArg " + std::to_string(index));
}
#endif

// [listing cl-args]
// Kernel arguments by type: a buffer is passed as its cl_mem handle, so its size is
// sizeof(cl_mem), never the size of the data it holds (errata B13).
inline void set_arg(const kernel_handle& k, cl_uint index, const buffer& b) {
  const cl_mem m = b.get();
  set_arg_bytes(k, index, sizeof(cl_mem), &m);
}
template <class V> void set_arg(const kernel_handle& k, cl_uint index, const V& value) {
  static_assert(std::is_trivially_copyable_v<V>);
  set_arg_bytes(k, index, sizeof(V), &value);
}
template <class... A> void set_args(const kernel_handle& k, const A&... args) {
  cl_uint i = 0;
  (set_arg(k, i++, args), ...);
}
// [end]

// One-dimensional launch of `global` work items (the runtime picks the work-group size).
inline void run_1d(const context& c, const kernel_handle& k, std::size_t global) {
  check(clEnqueueNDRangeKernel(c.queue.get(), k.get(), 1, nullptr, &global, nullptr, 0, nullptr,
                               nullptr),
        "clEnqueueNDRangeKernel");
}

// Two-dimensional launch, one work item per pixel: get_global_id(0) is x, get_global_id(1) is y.
inline void run_2d(const context& c, const kernel_handle& k, std::size_t width, std::size_t height) {
  const std::size_t global[2] = {width, height};
  check(clEnqueueNDRangeKernel(c.queue.get(), k.get(), 2, nullptr, global, nullptr, 0, nullptr,
                               nullptr),
        "clEnqueueNDRangeKernel");
}

}  // namespace zraka::cl
#endif

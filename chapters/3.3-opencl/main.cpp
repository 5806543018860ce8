// Chapter 3.3 — OpenCL. The thesis's vector addition (Listings 3.6 and 3.7) as a real host
// program: list the platforms and devices, pick one, build kernels/vector_add.cl (read through
// the resource root), copy a and b to the device, run one work item per element, read c back
// and check it against the same sum computed on the CPU. With no OpenCL platform on the
// machine it says so and computes on the CPU only.
#include <zraka/core/error.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/gpu/cl.hpp>

#include <zraka/app/cli.hpp>

#include <cstdio>
#include <optional>
#include <vector>

namespace {

void print_devices() {
  const auto devices = zraka::cl::list_devices();
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const auto& d = devices[i];
    std::printf("device %zu: %s\n  platform: %s\n  %s, %s, %u compute units, fp64 %s\n", i,
                d.device_name.c_str(), d.platform_name.c_str(), d.version.c_str(),
                d.c_version.c_str(), d.compute_units, d.fp64 ? "yes" : "no");
  }
  std::printf("%zu device(s)\n", devices.size());
}

}  // namespace

int main(int argc, char** argv) {
  bool list = false;
  int device_index = 0;
  long long n_arg = 1 << 20;
  std::string kernel_file = "kernels/vector_add.cl";
  zraka::cli_app app{"Chapter 3.3: vector addition with OpenCL, checked against the CPU"};
  app.add_flag("--list", list, "list the OpenCL platforms and devices, then exit");
  app.add_option("--device", device_index, "device number from --list");
  app.add_option("-n,--n", n_arg, "number of elements");
  app.add_option("--kernel", kernel_file, "kernel file (relative to the resource root or the "
                                          "working directory); must define vector_add");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return zraka::guarded([&] {
    using namespace zraka;
    const stopwatch clock;
    if (n_arg < 1 || n_arg > (1LL << 28))
      throw error("--n must be in 1.." + std::to_string(1LL << 28) + ", got " +
                  std::to_string(n_arg));
    if (list) {
      try {
        print_devices();
      } catch (const cl::no_platform& e) {
        std::printf("%s\n0 device(s)\n", e.what());
      }
      return 0;
    }
    const auto n = cl_uint(n_arg);

    // [listing host-data]
    std::vector<float> a(n), b(n), c(n, 0.0f), expected(n);
    for (cl_uint i = 0; i < n; ++i) {
      a[i] = float(i);
      b[i] = 1.0f;
    }
    stopwatch cpu_clock;
    for (cl_uint i = 0; i < n; ++i) expected[i] = a[i] + b[i];  // the CPU loop
    const double cpu_seconds = cpu_clock.seconds();
    // [end]

    std::optional<cl::context> ctx;
    try {
      ctx.emplace(cl::pick_device(device_index));  // (1) ask for a device
    } catch (const cl::no_platform& e) {
      std::printf("%s\nfalling back to the CPU loop: c[0..3] = %g %g %g %g\n", e.what(),
                  double(expected[0]), double(expected[1]), double(expected[2]),
                  double(expected[3]));
      std::printf("summary: no OpenCL platform; %u additions on the CPU in %.4f s\n", n,
                  cpu_seconds);
      return 0;
    }
    std::printf("device %d: %s (%s, %s)\n", device_index, ctx->device.device_name.c_str(),
                ctx->device.platform_name.c_str(), ctx->device.c_version.c_str());

    // [listing host-run]
    stopwatch build_clock;
    const auto program = cl::build_program(*ctx, kernel_file);  // (2) compile the kernel
    const auto kernel = cl::make_kernel(program, "vector_add");
    const double build_seconds = build_clock.seconds();

    stopwatch run_clock;
    const std::size_t bytes = std::size_t(n) * sizeof(float);
    const auto da = ctx->make_buffer(CL_MEM_READ_ONLY, bytes, a.data());  // copied now
    const auto db = ctx->make_buffer(CL_MEM_READ_ONLY, bytes, b.data());
    const auto dc = ctx->make_buffer(CL_MEM_WRITE_ONLY, bytes);
    cl::set_args(kernel, da, db, dc, n);  // buffers as cl_mem, n as cl_uint
    cl::run_1d(*ctx, kernel, n);          // (3) the queue runs n work items
    ctx->read(dc, bytes, c.data());       // (4) blocking read: c is ready after it
    const double run_seconds = run_clock.seconds();
    // [end]

    // [listing host-check]
    std::size_t wrong = 0;
    for (cl_uint i = 0; i < n; ++i) wrong += c[i] == expected[i] ? 0 : 1;  // equal bits
    // [end]
    std::printf("c[0..3] = %g %g %g %g (expected 1 2 3 4)\n", double(c[0]), double(c[1]),
                double(c[2]), double(c[3]));
    std::printf("elements that differ from the CPU: %zu of %u\n", wrong, n);
    std::printf("build %.3f s (PoCL caches it; POCL_KERNEL_CACHE=0 rebuilds), copy+run+read "
                "%.4f s, CPU loop %.4f s\n", build_seconds, run_seconds, cpu_seconds);
    if (wrong) throw error(std::to_string(wrong) + " element(s) differ from the CPU");
    std::printf("summary: %u additions on %s agree with the CPU; %.3f s in total\n", n,
                ctx->device.device_name.c_str(), clock.seconds());
    return 0;
  });
}

// links: OpenCL
// zraka/gpu/cl.hpp on the machine's OpenCL (PoCL here): the vector add against the CPU, the kernel
// random numbers (kernels/rng.cl) bit for bit against rng.hpp, and build errors that name the
// file and carry the compiler's log. With no OpenCL platform every case says so and passes.
#include <zraka/core/rng.hpp>
#include <zraka/gpu/cl.hpp>

#include <doctest/doctest.h>

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

using namespace zraka;

namespace {
// The first device, or nothing (with a visible message) when the machine has no platform.
std::optional<cl::context> first_device() {
  try {
    return cl::context(cl::pick_device(0));
  } catch (const cl::no_platform& e) {
    MESSAGE("skipped: " << std::string(e.what()));
    return std::nullopt;
  }
}
}  // namespace

TEST_CASE("error names carry the number") {
  CHECK_THROWS_WITH_AS(cl::check(CL_INVALID_ARG_SIZE, "clSetKernelArg 0"),
                       "clSetKernelArg 0 failed: CL_INVALID_ARG_SIZE (-51)", error);
  CHECK(cl::error_name(-1001) == "CL_PLATFORM_NOT_FOUND_KHR");
  CHECK_NOTHROW(cl::check(CL_SUCCESS, "x"));
}

TEST_CASE("vector add on the device equals the CPU loop") {
  auto c = first_device();
  if (!c) return;
  MESSAGE("device: " << c->device.device_name << " (" << c->device.platform_name << ")");
  // n is not a multiple of any work-group size, so the kernel's i < n guard matters.
  const cl_uint n = 100003;
  std::vector<float> a(n), b(n), out(n, -1.0f);
  for (cl_uint i = 0; i < n; ++i) {
    a[i] = float(i) * 0.5f;
    b[i] = 1.0f / float(i + 1);
  }
  const auto prog = cl::build_program(*c, "kernels/vector_add.cl");
  const auto k = cl::make_kernel(prog, "vector_add");
  const auto da = c->make_buffer(CL_MEM_READ_ONLY, n * sizeof(float), a.data());
  const auto db = c->make_buffer(CL_MEM_READ_ONLY, n * sizeof(float), b.data());
  const auto dc = c->make_buffer(CL_MEM_WRITE_ONLY, n * sizeof(float));
  cl::set_args(k, da, db, dc, n);
  cl::run_1d(*c, k, n);
  c->read(dc, n * sizeof(float), out.data());
  // One float addition, correctly rounded on both sides (IEEE 754 single): equal bits.
  std::size_t differ = 0;
  for (cl_uint i = 0; i < n; ++i) differ += out[i] == a[i] + b[i] ? 0 : 1;
  CHECK(differ == 0);
}

TEST_CASE("a buffer argument must be passed as sizeof(cl_mem) (errata B13)") {
  auto c = first_device();
  if (!c) return;
  const auto prog = cl::build_program(*c, "kernels/vector_add.cl");
  const auto k = cl::make_kernel(prog, "vector_add");
  const float host[4] = {1, 2, 3, 4};
  const auto da = c->make_buffer(CL_MEM_READ_ONLY, sizeof host, host);
  // The thesis's clSetKernelArg(kernel, 0, sizeof(array1), ...): 16 bytes for a handle.
  const cl_mem m = da.get();
  const cl_mem wrong[2] = {m, m};
  CHECK(clSetKernelArg(k.get(), 0, sizeof host, wrong) == CL_INVALID_ARG_SIZE);
  CHECK(clSetKernelArg(k.get(), 0, sizeof(cl_mem), &m) == CL_SUCCESS);
}

TEST_CASE("kernels/rng.cl draws the same bits as rng.hpp") {
  auto c = first_device();
  if (!c) return;
  // Streams: extreme seeds, pixels and samples, then pseudo-random ones.
  std::vector<cl_ulong> seed;
  std::vector<cl_uint> pixel, sample;
  const cl_ulong seeds[] = {0, 1, 42, 0xffffffffull, 0x100000000ull, ~0ull};
  const cl_uint ends[] = {0, 1, 0x7fffffffu, 0x80000000u, 0xffffffffu};
  for (cl_ulong s : seeds)
    for (cl_uint p : ends)
      for (cl_uint q : ends) {
        seed.push_back(s);
        pixel.push_back(p);
        sample.push_back(q);
      }
  for (std::uint32_t i = 0; i < 2000; ++i) {
    seed.push_back((cl_ulong(pcg_hash(i)) << 32) | pcg_hash(i + 7777));
    pixel.push_back(pcg_hash(i ^ 0xabcdefu));
    sample.push_back(i % 64);
  }
  const cl_uint streams = cl_uint(seed.size()), count = 40;  // 40 dimensions per stream
  const std::size_t total = std::size_t(streams) * count;

  const auto prog = cl::build_program_files(*c, {"kernels/rng.cl", "kernels/rng_check.cl"});
  const auto k = cl::make_kernel(prog, "rng_check");
  const auto ds = c->make_buffer(CL_MEM_READ_ONLY, streams * sizeof(cl_ulong), seed.data());
  const auto dp = c->make_buffer(CL_MEM_READ_ONLY, streams * sizeof(cl_uint), pixel.data());
  const auto dq = c->make_buffer(CL_MEM_READ_ONLY, streams * sizeof(cl_uint), sample.data());
  const auto du = c->make_buffer(CL_MEM_WRITE_ONLY, total * sizeof(cl_uint));
  const auto df = c->make_buffer(CL_MEM_WRITE_ONLY, total * sizeof(float));
  cl::set_args(k, ds, dp, dq, count, du, df);
  cl::run_1d(*c, k, streams);
  std::vector<cl_uint> u(total);
  std::vector<float> f(total);
  c->read(du, total * sizeof(cl_uint), u.data());
  c->read(df, total * sizeof(float), f.data());

  // Exact equality: integer arithmetic, and a float conversion of a 24-bit integer times 2^-24.
  std::size_t u_differ = 0, f_differ = 0;
  for (cl_uint i = 0; i < streams; ++i) {
    rng a(seed[i], pixel[i], sample[i]), b(seed[i], pixel[i], sample[i]);
    for (cl_uint d = 0; d < count; ++d) {
      u_differ += u[std::size_t(i) * count + d] == a.next_u32() ? 0 : 1;
      f_differ += f[std::size_t(i) * count + d] == b.uniform_float() ? 0 : 1;
    }
  }
  MESSAGE(streams << " streams x " << count << " dimensions compared");
  CHECK(u_differ == 0);
  CHECK(f_differ == 0);

  if (c->device.fp64) {  // doubles: 53 bits from two draws, in the same order
    const auto kd = cl::make_kernel(prog, "rng_check_double");
    const auto dd = c->make_buffer(CL_MEM_WRITE_ONLY, total * sizeof(double));
    cl::set_args(kd, ds, dp, dq, count, dd);
    cl::run_1d(*c, kd, streams);
    std::vector<double> g(total);
    c->read(dd, total * sizeof(double), g.data());
    std::size_t g_differ = 0;
    for (cl_uint i = 0; i < streams; ++i) {
      rng a(seed[i], pixel[i], sample[i]);
      for (cl_uint d = 0; d < count; ++d) g_differ += g[std::size_t(i) * count + d] == a.uniform() ? 0 : 1;
    }
    CHECK(g_differ == 0);
  } else {
    MESSAGE("the device has no fp64: double numbers not compared");
  }
}

TEST_CASE("a 2-D launch keyed by pixel index draws the CPU's numbers; write() updates a buffer") {
  auto c = first_device();
  if (!c) return;
  const cl_uint width = 37, height = 23;  // odd sizes: no work-group size divides them
  const auto prog = cl::build_program_files(*c, {"kernels/rng.cl", "kernels/rng_check.cl"});
  const auto k = cl::make_kernel(prog, "rng_image");
  const std::size_t n = std::size_t(width) * height * 2;
  std::vector<float> out(n, -1.0f);
  const auto dout = c->make_buffer(CL_MEM_READ_WRITE, n * sizeof(float), out.data());
  for (cl_uint sample : {0u, 1u, 1000u}) {
    c->write(dout, n * sizeof(float), out.data());  // reset between launches
    cl::set_args(k, cl_ulong(99), sample, width, dout);
    cl::run_2d(*c, k, width, height);
    std::vector<float> got(n);
    c->read(dout, n * sizeof(float), got.data());
    std::size_t differ = 0;
    for (cl_uint p = 0; p < width * height; ++p) {
      rng g(99, p, sample);
      differ += got[2 * p] == g.uniform_float() ? 0 : 1;
      differ += got[2 * p + 1] == g.uniform_float() ? 0 : 1;
    }
    CHECK(differ == 0);
  }
}

TEST_CASE("a broken kernel file: the error names the file and holds the build log") {
  auto c = first_device();
  if (!c) return;
  try {
    cl::build_program(*c, "tests/broken_kernel.cl", "-DUNUSED=1");
    FAIL("the broken kernel built");
  } catch (const error& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("tests/broken_kernel.cl") != std::string::npos);   // the file, in the message
    CHECK(what.find("CL_BUILD_PROGRAM_FAILURE") != std::string::npos);
    CHECK(what.find("-DUNUSED=1") != std::string::npos);               // the options
    CHECK(what.find("results") != std::string::npos);                  // the compiler's log
    CHECK(what.find("broken_kernel.cl:5") != std::string::npos);       // #line: file and line
  }
}

TEST_CASE("missing kernel file and bad device index") {
  auto c = first_device();
  if (!c) return;
  CHECK_THROWS_WITH_AS(cl::build_program(*c, "kernels/no_such_kernel.cl"),
                       doctest::Contains("kernels/no_such_kernel.cl"), error);
  CHECK_THROWS_WITH_AS(cl::pick_device(1000), doctest::Contains("--device 1000 does not exist"),
                       error);
  CHECK_THROWS_AS(cl::pick_device(-1), error);
}

// Time to an error (issue 17, book 4.2): how many seconds each integrator and sampler needs to
// bring one scene to a given RMSE, and, when Mitsuba 3 is installed, how many Mitsuba's
// `scalar_rgb` needs on the same scene in the same run (and its JIT-compiled SIMD variant
// `llvm_ad_rgb`, with --mitsuba-variants scalar_rgb,llvm_ad_rgb). Not a test: it takes minutes.
//
// The scene is RTIOW book 3's Cornell box with a glass sphere (scenes/rtiow-cornell.yaml). The
// error is measured where RTIOW's own figures live, in its output space: a square root (gamma 2)
// and a clamp to [0, 1], over every channel of every pixel, against a long `mis` reference that
// is made once, in two halves, and cached under build/out/; the reference's own noise (from its
// halves, in the same space) is taken out of every squared error.
//
// zraka's path tracers render in passes that double the samples (render_progressive), so the
// time of a row is the time to render that many samples; BDPT renders each row afresh. Mitsuba
// renders 1, 2, 4, ... spp, each a render of its own (tools/mitsuba_reference.py --doubling),
// after zraka is done, so the two never share the cores. The time to the target is interpolated
// log-log between the rows that bracket it (seconds_to_reach, progressive.hpp).
// The path tracers and BDPT run in double and in float (scene_precision.hpp), each a row;
// --rr-depth moves where their Russian roulette (and the kernel's) starts. Each row also
// gives its rate in million samples (paths) per second, Mitsuba's too. `kernel` is book 4.3's
// OpenCL path tracer (mis, float, specialised to the scene) on the first OpenCL device, in
// launches that double the samples; on PoCL it runs on the same cores (--threads does not bind it).
//   build/bin/time_to_error [--scene S] [--target RMSE] [--max-seconds S] [--ref-spp N]
//                           [--integrators mis,nee,bdpt,kernel] [--precisions double,float] [--rr-depth N]
//                           [--mitsuba PYTHON|none] [--mitsuba-variants scalar_rgb,llvm_ad_rgb] [--threads T]
#include <zraka/app/cli.hpp>
#include <zraka/app/program_options.hpp>
#include <zraka/core/error.hpp>
#include <zraka/image/image_error.hpp>
#include <zraka/image/image_io.hpp>
#include <zraka/integrators/bdpt.hpp>
#include <zraka/integrators/path.hpp>
#include <zraka/integrators/progressive.hpp>
#include <zraka/io/mitsuba_export.hpp>
#include <zraka/sampling/convergence.hpp>
#include <zraka/sampling/pixel_sampling.hpp>
#if defined(ZRAKA_TTE_OPENCL)
#include <zraka/gpu/gpu_scene.hpp>
#include <zraka/gpu/realtime.hpp>
#endif
#include <zraka/app/reference.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/io/scene_argument.hpp>
#include <zraka/sampling/samplers.hpp>
#include <zraka/scene/scene_precision.hpp>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <signal.h>
#include <sys/types.h>

using namespace zraka;

namespace {

// RTIOW's output space: gamma 2, clamped to [0, 1] (its PPM holds 256 x this, below 256).
image output_space(const image& x) {
  image y(x.width, x.height);
  for (std::size_t i = 0; i < x.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) y.pixels[i][c] = std::clamp(std::sqrt(std::max(x.pixels[i][c], 0.0f)), 0.0f, 1.0f);
  return y;
}

// The error of an image in that space, the reference's own noise taken out.
struct output_error {
  image ref;
  double noise_mse = 0;
  explicit output_error(const mis_reference& r) : ref(output_space(r.img)) {
    const double d = rmse(output_space(r.half[0]), output_space(r.half[1]));
    noise_mse = d * d / 4;
  }
  double operator()(const image& x) const {
    const double e = rmse(output_space(x), ref);
    return std::sqrt(std::max(0.0, e * e - noise_mse));
  }
};

std::vector<std::string> split_list(const std::string& s, const char* what) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  if (out.empty()) throw error(std::string(what) + " names nothing");
  return out;
}

struct result_t {
  std::string method;
  convergence_log log;
};

// The last row's rate: its samples (spp x pixels) over its seconds; each row of bdpt and Mitsuba
// is a render of its own, a path tracer's row holds every pass so far, so this is each one's rate.
void print_row(const result_t& r, double target, double pixels) {
  const convergence_row& last = r.log.rows().back();
  const double t = seconds_to_reach(r.log, target);
  char secs[32];
  if (!std::isnan(t)) std::snprintf(secs, sizeof secs, "%.2f", t);
  else std::snprintf(secs, sizeof secs, "> %.1f", last.seconds);
  std::printf("%-26s %10s %8llu %10.5f %14.3f\n", r.method.c_str(), secs, static_cast<unsigned long long>(last.n),
              last.values[0], double(last.n) * pixels / std::max(last.seconds, 1e-9) / 1e6);
  std::fflush(stdout);
}

// Mitsuba 3 (`variant`) on the scene exported as JSON: reads the images its script writes as they
// come, measures them here, and ends the script once the target is reached.
std::optional<result_t> run_mitsuba(const std::string& python, const std::string& variant, const scene& sc, int depth,
                                    const std::string& stem, const output_error& err, double target,
                                    double max_seconds) {
  const std::string json = output_file("tte-" + stem + "-mitsuba.json").string();
  const std::string out = output_file("tte-" + stem + "-mitsuba-" + variant + ".pfm").string();
  write_file_atomically(json, mitsuba_scene_json(sc, sc.settings.width, sc.settings.height, depth));
  std::error_code ec;
  std::filesystem::remove(out + ".stop", ec);
  const std::string script = resource_path("tools/mitsuba_reference.py").string();
  // `exec` makes the shell's pid the script's, which `echo $$` printed first.
  const std::string cmd = "echo $$; exec '" + python + "' '" + script + "' '" + json + "' -o '" + out +
                          "' --variant " + variant + " --spp 65536 --doubling " + std::to_string(max_seconds);
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) throw error("cannot start " + python);
  result_t r{"mitsuba " + variant, convergence_log("mitsuba " + variant + " on " + stem, {"rmse"}, "rmse", "spp")};
  long pid = 0;
  char line[4096];
  bool stopped = false;
  while (std::fgets(line, sizeof line, pipe)) {
    if (pid == 0) {
      pid = std::strtol(line, nullptr, 10);
      continue;
    }
    unsigned long long n = 0;
    double secs = 0;
    char file[4000];
    if (std::sscanf(line, "pass %llu %lf %3999s", &n, &secs, file) != 3) {
      std::fputs(line, stdout);  // Mitsuba's own messages
      continue;
    }
    const image img = read_pfm(file);
    check_same_size(err.ref, img);
    r.log.add(n, secs, {err(img)});
    std::filesystem::remove(file, ec);
    if (!stopped && (r.log.rows().back().values[0] <= target || secs > max_seconds)) {
      write_file_atomically(out + ".stop", "");
      if (pid > 0) ::kill(pid_t(pid), SIGTERM);  // the render under way is not needed
      stopped = true;
    }
  }
  pclose(pipe);
  std::filesystem::remove(out + ".stop", ec);
  if (r.log.rows().empty()) {
    std::printf("%-26s failed: the script rendered nothing (%s)\n", r.method.c_str(), cmd.c_str());
    return std::nullopt;
  }
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  program_options cli{"Time to an RMSE for each integrator and sampler, and for Mitsuba 3 scalar_rgb (issue 17)",
                      take::scene | take::size | take::depth | take::seed | take::threads};
  cli.scene = "scenes/rtiow-cornell.yaml";
  cli.scene_settings = true;
  double target = 0.014, max_seconds = 60;
  int ref_spp = 8192, rr_depth = path_options{}.rr_depth;
  std::string integrators = "mis,nee,bdpt", samplers = "independent", precisions = "double,float";
  std::string mitsuba = "build/mitsuba-venv/bin/python", mitsuba_variants = "scalar_rgb";
  cli.app.add_option("--target", target, "the RMSE to reach, in RTIOW's output space (gamma 2, clamped to [0, 1])");
  cli.app.add_option("--max-seconds", max_seconds, "a method stops after a pass that ends later than this");
  cli.app.add_option("--ref-spp", ref_spp, "samples per pixel of the mis reference (made once, cached in build/out/)");
  cli.app.add_option("--integrators", integrators,
                     "comma-separated: naive, nee, mis (path tracing), bdpt, and kernel (book 4.3's OpenCL path tracer, mis)");
  cli.app.add_option("--samplers", samplers, std::string("comma-separated samplers for the path tracers: ") + sampler_names +
                         " (stratified is stratified over 65536 spp, the most a run may reach: a run stopped "
                         "earlier has a random subset of the cells)");
  cli.app.add_option("--rr-depth", rr_depth, "Russian roulette starts at this bounce, in the path tracers and BDPT (the reference keeps the default)");
  cli.app.add_option("--precisions", precisions, "comma-separated: double, float (the arithmetic of the path tracers and of BDPT)");
  cli.app.add_option("--mitsuba", mitsuba,
                     "the Python that has the mitsuba package (relative: to the checkout); none: leave Mitsuba out");
  cli.app.add_option("--mitsuba-variants", mitsuba_variants,
                     "comma-separated Mitsuba variants, each a row: scalar_rgb, llvm_ad_rgb (JIT-compiled SIMD; "
                     "needs LLVM 19, tools/setup.sh --extras)");
  if (const auto done = cli.parse(argc, argv)) return *done;

  return guarded([&] {
    if (!(target > 0)) throw error("--target must be positive");
    if (!(max_seconds > 0)) throw error("--max-seconds must be positive");
    const std::vector<std::string> methods = split_list(integrators, "--integrators");
    const std::vector<std::string> sampler_list = split_list(samplers, "--samplers");
    for (const std::string& s : sampler_list) parse_sampler(s);  // an unknown name: refused before any work
    const std::vector<std::string> precision_names = split_list(precisions, "--precisions");
    for (const std::string& s : precision_names)
      if (s != "double" && s != "float") throw error("unknown precision '" + s + "' (double, float)");
    const std::vector<std::string> variants = split_list(mitsuba_variants, "--mitsuba-variants");
    for (const std::string& v : variants)
      if (v != "scalar_rgb" && v != "llvm_ad_rgb") throw error("unknown Mitsuba variant '" + v + "' (scalar_rgb, llvm_ad_rgb)");
    scene sc = load_scene_argument(cli.scene).sc;
    cli.apply_to(sc.settings);
    sc.build_acceleration();
    const scene_t<float> sc_float = scene_in<float>(sc);  // the same scene, coordinates in float
    const int W = sc.settings.width, H = sc.settings.height;
    const std::string stem = std::filesystem::path(cli.scene).stem().string();
    const stopwatch total;
    render_options ro = cli.render();
    ro.progress = false;
    path_options po;
    po.max_depth = sc.settings.max_depth;

    std::uint64_t bad = 0;
    const std::string tag = reference_tag(cli.scene, W, H, po.max_depth, ref_spp);
    const mis_reference ref = make_mis_reference(
        sc, ref_spp, cli.seed, po, ro, [&](const std::string& h) { return output_file("tte" + tag + h + ".pfm").string(); },
        bad);
    const output_error err(ref);
    std::printf("%s, %dx%d, at most %d bounces (Russian roulette from %d), %d threads: seconds to RMSE %.4f in RTIOW's output space\n"
                "reference: mis, %d spp in two halves (%s), its own RMSE there %.5f, taken out\n\n%-26s %10s %8s %10s %14s\n",
                cli.scene.c_str(), W, H, po.max_depth, rr_depth, resolve_threads(cli.threads), target, ref_spp, ref.files.c_str(),
                std::sqrt(err.noise_mse), "method", "seconds", "spp", "rmse", "M samples/s");
    std::fflush(stdout);

    std::vector<result_t> results;
    for (const std::string& m : methods) {
      if (m == "bdpt") {
        for (const std::string& precision : precision_names) {
          const std::string method = "bdpt " + precision;
          result_t r{method, convergence_log(method + " on " + stem, {"rmse"}, "rmse", "spp")};
          bdpt_options bo;
          bo.max_depth = po.max_depth, bo.rr_depth = rr_depth, bo.threads = cli.threads;
          for (int n = 1; n <= 65536; n *= 2) {  // each row a render of its own
            const stopwatch clock;
            const image img = precision == "double" ? render_bdpt(sc, n, cli.seed, bo).img
                                                    : render_bdpt(sc_float, n, cli.seed, bo).img;
            r.log.add(std::uint64_t(n), clock.seconds(), {err(img)});
            if (r.log.rows().back().values[0] <= target || r.log.rows().back().seconds > max_seconds) break;
          }
          print_row(r, target, double(W) * H);
          results.push_back(std::move(r));
        }
        continue;
      }
      if (m == "kernel") {
#if defined(ZRAKA_TTE_OPENCL)
        path_options kp = po;
        kp.method = integrator::mis;
        kp.rr_depth = rr_depth;
        const gpu_scene packed = pack_scene(sc, W, H, kp);  // refuses, by name, what the kernel lacks
        cl::context ctx(cl::pick_device(0));
        gpu_renderer gpu(ctx, packed, W, H, cli.seed);
        gpu.launch(1);  // PoCL compiles the work-group function at the first launch: not timed
        gpu.finish();
        gpu.reset();
        result_t r{"kernel mis float", convergence_log("kernel on " + stem, {"rmse"}, "rmse", "spp")};
        double seconds = 0;
        while (gpu.samples() < 65536) {  // launches of 1, 1, 2, 4, ... spp: the sums double
          const stopwatch clock;
          gpu.launch(std::max<std::uint32_t>(gpu.samples(), 1));
          gpu.finish();
          seconds += clock.seconds();
          r.log.add(gpu.samples(), seconds, {err(gpu.read_image())});
          if (r.log.rows().back().values[0] <= target || seconds > max_seconds) break;
        }
        print_row(r, target, double(W) * H);
        results.push_back(std::move(r));
        continue;
#else
        throw error("--integrators kernel: this build has no OpenCL (bench/CMakeLists.txt)");
#endif
      }
      path_options p = po;
      p.method = parse_integrator(m);
      p.rr_depth = rr_depth;
      // One progressive run of path tracer `tracer` with sampler s; T is its precision.
      auto run = [&]<class T>(const path_tracer_t<T>& tracer, const typename camera_t<T>::prepared& cam,
                              const std::string& s) {
        const std::string method = m + " " + s + " " + (sizeof(T) == 4 ? "float" : "double");
        result_t r{method, convergence_log(method + " on " + stem, {"rmse"}, "rmse", "spp")};
        progressive_options prog;
        prog.max_spp = 65536, prog.seed = cli.seed, prog.render = ro;
        const sampler_kind kind = parse_sampler(s);
        render_progressive(W, H, prog, [&](sample_context& c) {
          sample_point point(kind, cli.seed, std::uint32_t(c.y * W + c.x), std::uint32_t(c.sample), std::uint32_t(c.spp));
          point.drive(c.random);
          const vec2 o = pixel_sample(pixel_pattern::uniform, c.sample, c.spp, c.random);
          return tracer(cam.generate(T((c.x + o.x) / W), T((c.y + o.y) / H)), c.random, c.rays);
        }, [&](const image& mean, const progressive_totals& t) {
          r.log.add(std::uint64_t(t.spp), t.seconds, {err(mean)});
          return r.log.rows().back().values[0] > target && t.seconds <= max_seconds;
        });
        print_row(r, target, double(W) * H);
        results.push_back(std::move(r));
      };
      for (const std::string& precision : precision_names)
        for (const std::string& s : sampler_list) {
          if (precision == "double") run(path_tracer_t<double>(sc, p), sc.prepared_camera(), s);
          else run(path_tracer_t<float>(sc_float, p), sc_float.prepared_camera(), s);
        }
    }

    std::vector<result_t> mi;  // one row per Mitsuba variant that ran
    if (mitsuba != "none") {
      std::filesystem::path py(mitsuba);
      if (py.is_relative()) py = resource_root() / py;
      std::error_code ec;
      for (const std::string& v : variants) {
        if (!std::filesystem::exists(py, ec)) {
          std::printf("%-26s not run: %s not found (bash tools/mitsuba-setup.sh)\n", ("mitsuba " + v).c_str(), py.c_str());
          continue;
        }
        if (auto r = run_mitsuba(py.string(), v, sc, po.max_depth, stem, err, target, max_seconds)) {
          print_row(*r, target, double(W) * H);
          mi.push_back(std::move(*r));
        }
      }
    }
    for (const auto* rows : {&results, &mi})
      for (const result_t& r : *rows) {
        std::string name = r.method;
        std::replace(name.begin(), name.end(), ' ', '-');
        r.log.write_csv(output_file("tte-" + stem + "-" + name + ".csv"));
      }

    // The summary: the fastest of zraka's methods, against each Mitsuba variant that ran.
    const result_t* best = nullptr;
    double best_t = 0;
    for (const result_t& r : results)
      if (const double t = seconds_to_reach(r.log, target); !std::isnan(t) && (!best || t < best_t)) best = &r, best_t = t;
    std::printf("\nsummary: %.1f s in all", total.seconds());
    if (best) std::printf("; fastest: %s, %.2f s", best->method.c_str(), best_t);
    else std::printf("; no zraka method reached %.4f", target);
    for (const result_t& r : mi) {
      if (const double t = seconds_to_reach(r.log, target); !std::isnan(t)) {
        std::printf("; %s %.2f s", r.method.c_str(), t);
        if (best) std::printf(" (%.2fx)", t / best_t);
      } else {
        std::printf("; %s did not reach it", r.method.c_str());
      }
    }
    std::printf("; %llu NaN/inf samples in the reference\n", static_cast<unsigned long long>(bad));
    return 0;
  });
}

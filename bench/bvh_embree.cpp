// Benchmark for book 5.2: zraka's triangle BVH (triangle_bvh.hpp) against Intel Embree 3's
// rtcIntersect1, one thread each, on the same rays in the same run: the teapot at several divs,
// camera rays, incoherent random rays and incoherent rays from a bounding sphere
// (chapters/5.2-bvh/teapot_rays.hpp). Prints memory per triangle, rays per second, their ratio,
// how often the two agree on the hit, and the build times and their ratio.
// Each timing is the best of --repeat passes, ours and Embree's alternating, in this thread's CPU
// time (not wall-clock time), so that a machine busy with other work disturbs both alike and
// little; builds are timed in wall-clock time (Embree may build in a thread of its own).
#include <zraka/accel/triangle_bvh.hpp>
#include <zraka/core/error.hpp>
#include <zraka/core/resources.hpp>
#include <zraka/core/stopwatch.hpp>
#include <zraka/geometry/tessellate.hpp>
#include <zraka/io/bpt.hpp>

#include "teapot_rays.hpp"

#include <zraka/app/cli.hpp>
#include <embree3/rtcore.h>

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <optional>
#include <string>
#include <vector>

using namespace zraka;

namespace {

struct embree_scene {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  embree_scene(const mesh& m, bool robust) {
    device = rtcNewDevice("threads=1");  // one thread, like ours
    if (!device) throw error("Embree: rtcNewDevice failed");
    scene = rtcNewScene(device);
    // Robust: Embree's edge-watertight (Pluecker) test and traversal instead of its default,
    // Moeller-Trumbore; closer to what our watertight leaf does.
    if (robust) rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                          3 * sizeof(float), m.positions.size()));
    for (std::size_t i = 0; i < m.positions.size(); ++i)
      for (int k = 0; k < 3; ++k) v[3 * i + k] = float(m.positions[i][k]);
    auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                               3 * sizeof(unsigned), m.triangle_count()));
    for (std::size_t i = 0; i < m.triangle_count(); ++i)
      for (int k = 0; k < 3; ++k) idx[3 * i + k] = m.triangles[i][k];
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    rtcCommitScene(scene);
    if (rtcGetDeviceError(device) != RTC_ERROR_NONE) throw error("Embree: building the scene failed");
  }
  ~embree_scene() {
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
  }
  embree_scene(const embree_scene&) = delete;
  embree_scene& operator=(const embree_scene&) = delete;
};

// CPU seconds used by this thread (POSIX).
double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct result {
  float t = infinity<float>;
  unsigned triangle = UINT32_MAX;  // UINT32_MAX: a miss
};

// [listing embree-trace]
void trace_embree(const embree_scene& e, const std::vector<rayf>& rays, std::vector<result>& out) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  for (std::size_t i = 0; i < rays.size(); ++i) {
    RTCRayHit rh{};
    rh.ray.org_x = rays[i].origin.x, rh.ray.org_y = rays[i].origin.y, rh.ray.org_z = rays[i].origin.z;
    rh.ray.dir_x = rays[i].direction.x, rh.ray.dir_y = rays[i].direction.y;
    rh.ray.dir_z = rays[i].direction.z;
    rh.ray.tnear = 0.0f;
    rh.ray.tfar = infinity<float>;
    rh.ray.mask = UINT32_MAX;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(e.scene, &context, &rh);
    out[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID ? result{} : result{rh.ray.tfar, rh.hit.primID};
  }
}
// [end]

void trace_ours(const triangle_bvh& bvh, const std::vector<rayf>& rays, std::vector<result>& out, simd_level simd) {
  for (std::size_t i = 0; i < rays.size(); ++i) {
    triangle_bvh_hit h;
    out[i] = bvh.intersect(rays[i], 0.0f, infinity<float>, h, nullptr, simd) ? result{h.t, h.triangle} : result{};
  }
}

// Same triangle, or the same t to 1e-4 relative (a ray through a shared edge may pick either
// neighbour), or both miss.
double agreement(const std::vector<result>& a, const std::vector<result>& b) {
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const bool miss_a = a[i].triangle == UINT32_MAX, miss_b = b[i].triangle == UINT32_MAX;
    if (miss_a || miss_b) same += miss_a == miss_b;
    else same += a[i].triangle == b[i].triangle || std::abs(a[i].t - b[i].t) <= 1e-4f * a[i].t;
  }
  return double(same) / double(a.size());
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> divs_list{8, 32, 128};
  int width = 256, height = 256, random_count = 65536, repeat = 3;
  std::uint64_t seed = 1;
  zraka::cli_app app{"Benchmark (book 5.2): zraka's triangle BVH vs Embree 3 rtcIntersect1, one thread"};
  app.add_option("--divs", divs_list, "teapot tessellation levels (2 divs^2 triangles per patch)");
  app.add_option("--width", width, "camera rays: image width");
  app.add_option("--height", height, "camera rays: image height");
  app.add_option("--rays", random_count, "number of incoherent rays of each kind (random, sphere)");
  app.add_option("--repeat", repeat, "timing passes per measurement (the best is kept)");
  app.add_option("--seed", seed, "seed of the random rays");
  std::string simd_name = to_string(cpu_simd());
  bool robust = false;
  app.add_flag("--embree-robust", robust, "Embree in its robust mode (RTC_SCENE_FLAG_ROBUST: watertight edges)");
  app.add_option("--simd", simd_name, "our BVH's SIMD level: avx2, sse or scalar (default: the best this CPU runs)");
  bvh_build_options opt = triangle_bvh::default_options();
  app.add_option("--leaf", opt.max_leaf_size, "our BVH: most triangles per leaf");
  app.add_option("--traversal-cost", opt.traversal_cost, "our BVH: SAH cost of a box test (a triangle test = 1)");
  app.add_option("--bins", opt.bins, "our BVH: SAH bins per axis");
  app.add_option("--leaf-block", opt.leaf_block, "our BVH: SAH prices a leaf by its blocks of this many triangles");
  app.add_option("--wide-leaf", opt.wide_leaf_size, "our BVH: most triangles in a leaf of the wide tree (collapse by cost)");
  app.add_option("--node-cost", opt.wide_node_cost, "our BVH: a wide node's cost in leaf blocks (collapse by cost)");
  std::string quantize = "auto";
  app.add_option("--quantize", quantize,
                 "our BVH: nodes in half the bytes: auto (a tree larger than eight L2 caches), on or off");
  if (const auto done = zraka::parse_command_line(app, argc, argv)) return *done;

  return guarded([&] {
    if (repeat < 1) throw error("--repeat must be at least 1");
    std::optional<simd_level> named;  // the level whose name (to_string) is --simd's
    for (const simd_level l : {simd_level::avx2, simd_level::sse, simd_level::scalar})
      if (simd_name == to_string(l)) named = l;
    if (!named) throw error("--simd must be avx2, sse or scalar, got '" + simd_name + "'");
    const simd_level simd = *named;
    if (usable_simd(simd) != simd) throw error("--simd " + simd_name + ": this processor (or build) does not run it");
    if (random_count < 1) throw error("--rays must be at least 1");
    if (quantize != "auto" && quantize != "on" && quantize != "off")
      throw error("--quantize must be auto, on or off, got '" + quantize + "'");
    opt.quantize = quantize == "auto" ? -1 : quantize == "on" ? 1 : 0;
    for (const int d : divs_list)
      if (d < 1 || d > 512) throw error("--divs must be in 1..512, got " + std::to_string(d));
    const auto patches = load_bpt(resource_path("scenes/teapot.bpt")).all_patches();
    std::printf("ours: %d-wide nodes, %s; Embree: its own choice for this processor, %s triangle test\n",
                triangle_bvh::width, to_string(simd), robust ? "robust (RTC_SCENE_FLAG_ROBUST)" : "default");
    std::printf("%6s %9s %-8s %8s %12s %12s %7s %9s\n", "divs", "triangles", "rays", "B/tri",
                "ours Mray/s", "Embree Mray/s", "ratio", "agreement");
    stopwatch total;
    for (const int divs : divs_list) {
      const mesh m = tessellate(patches, divs);
      double ours_build = infinity<double>, embree_build = infinity<double>;
      for (int k = 0; k < repeat; ++k) {  // best of --repeat, alternating
        stopwatch sw;
        const triangle_bvh b(m, opt);
        ours_build = std::min(ours_build, sw.seconds());
        sw.restart();
        const embree_scene e(m, robust);
        embree_build = std::min(embree_build, sw.seconds());
      }
      const triangle_bvh bvh(m, opt);
      const embree_scene emb(m, robust);
      const struct {
        const char* name;
        std::vector<rayf> rays;
      } sets[] = {{"camera", chapter_5_2::camera_rays(m.bounds(), width, height)},
                  {"random", chapter_5_2::random_rays(m.bounds(), random_count, seed)},
                  {"sphere", chapter_5_2::sphere_rays(m.bounds(), random_count, seed)}};
      for (const auto& set : sets) {
        std::vector<result> ours(set.rays.size()), theirs(set.rays.size());
        double best_ours = infinity<double>, best_embree = infinity<double>;
        for (int k = 0; k < repeat; ++k) {
          double t0 = thread_seconds();
          trace_ours(bvh, set.rays, ours, simd);
          best_ours = std::min(best_ours, thread_seconds() - t0);
          t0 = thread_seconds();
          trace_embree(emb, set.rays, theirs);
          best_embree = std::min(best_embree, thread_seconds() - t0);
        }
        const double n = double(set.rays.size());
        std::printf("%6d %9zu %-8s %8.1f %12.2f %12.2f %7.2f %8.3f%%\n", divs, m.triangle_count(), set.name,
                    bvh.bytes_per_triangle(), n / best_ours * 1e-6, n / best_embree * 1e-6,
                    best_embree / best_ours, 100 * agreement(ours, theirs));
      }
      std::printf("%6d build: ours %.3f s, Embree %.3f s, ours/Embree %.2f (wall clock, best of %d); our nodes %s\n",
                  divs, ours_build, embree_build, ours_build / embree_build, repeat,
                  bvh.quantized() ? "quantized (128 bytes)" : "full (256 bytes)");
    }
    std::printf("summary: ratio = our rays/s over Embree's (1 = as fast); build ratio = our build time "
                "over Embree's; %.1f s in all\n",
                total.seconds());
    return 0;
  });
}

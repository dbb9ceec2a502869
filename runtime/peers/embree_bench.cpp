// Intel Embree 3 on exactly the rays of docs/bench-protocol.md, for the side-by-side figures of
// scripts/bench. The mesh comes from the project's loaders and the rays from runtime/bench
// (protocol_rays), the same code `cohort bench` traces; only the traversal differs.
//
// Threads: a TBB task_arena of --threads workers (default 2) runs blocks of 256 rays through
// rtcIntersect1M (Embree's ray-stream API), marked coherent for primary rays and incoherent for
// diffuse rays; the BVH is built by an Embree device configured with the same thread count, at
// --build-quality (Embree's default, medium; high adds spatial splits: the anchor the large-scene work set
// the KD build against).
#include <embree3/rtcore.h>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <chrono>
#include <cstring>
#include <map>
#include <memory>

#include "runtime/bench/bench_json.h"
#include "runtime/bench/protocol_rays.h"
#include "runtime/bench/scene_bench.h"
#include "runtime/util/atomic_file.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

struct DeviceDeleter {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using EmbreeDevice = std::unique_ptr<RTCDeviceTy, DeviceDeleter>;
using EmbreeScene = std::unique_ptr<RTCSceneTy, SceneDeleter>;

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// --build-quality's names for Embree's build qualities.
const std::map<std::string, RTCBuildQuality> kBuildQualities{
    {"low", RTC_BUILD_QUALITY_LOW}, {"medium", RTC_BUILD_QUALITY_MEDIUM}, {"high", RTC_BUILD_QUALITY_HIGH}};

// The triangles of Scene::positions (3 per triangle), so primID indexes them as the protocol's
// diffuse rays expect. Returns the scene and its build time.
std::pair<EmbreeScene, double> build_bvh(RTCDevice device, std::span<const glm::vec3> positions,
                                         RTCBuildQuality quality) {
  EmbreeScene scene(rtcNewScene(device));
  rtcSetSceneBuildQuality(scene.get(), quality);
  RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  rtcSetGeometryBuildQuality(geometry, quality);
  const std::size_t tris = positions.size() / 3;
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                        3 * sizeof(float), positions.size()));
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), tris));
  if (!v || !idx) throw std::runtime_error("embree: cannot allocate the geometry buffers");
  std::memcpy(v, positions.data(), positions.size() * sizeof(glm::vec3));
  for (std::size_t i = 0; i < positions.size(); ++i) idx[i] = unsigned(i);
  const auto start = std::chrono::steady_clock::now();
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(scene.get(), geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(scene.get());
  return {std::move(scene), seconds_since(start)};
}

TraceFigures trace(RTCScene scene, std::span<const RayIn> rays, unsigned reps, unsigned threads, bool coherent) {
  std::vector<RTCRayHit> pristine(rays.size());
  for (std::size_t i = 0; i < rays.size(); ++i) {
    RTCRayHit& rh = pristine[i];
    std::memset(&rh, 0, sizeof(rh));
    rh.ray.org_x = rays[i].origin.x, rh.ray.org_y = rays[i].origin.y, rh.ray.org_z = rays[i].origin.z;
    rh.ray.dir_x = rays[i].dir.x, rh.ray.dir_y = rays[i].dir.y, rh.ray.dir_z = rays[i].dir.z;
    rh.ray.tnear = rays[i].origin.w;
    rh.ray.tfar = rays[i].dir.w;
    rh.ray.mask = ~0u;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  }
  TraceFigures f;
  f.rays = rays.size();
  std::vector<RTCRayHit> work;
  tbb::task_arena arena{static_cast<int>(threads)};
  for (unsigned r = 0; r < std::max(reps, 1u); ++r) {
    work = pristine;  // tfar and hits are overwritten by every trace
    const auto start = std::chrono::steady_clock::now();
    arena.execute([&] {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, work.size(), 256), [&](const auto& range) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
        rtcIntersect1M(scene, &context, &work[range.begin()], unsigned(range.size()), sizeof(RTCRayHit));
      });
    });
    const double s = seconds_since(start);
    f.rays_per_second.runs.push_back(s > 0 ? double(rays.size()) / s : 0.0);
  }
  f.closest.resize(rays.size());
  for (std::size_t i = 0; i < work.size(); ++i)
    if (work[i].hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      ++f.hits;
      f.closest[i] = ProtocolHit{work[i].ray.tfar, work[i].hit.primID};
    }
  return f;
}

std::string mrays(const RateFigure& f) { return fmt::format("{:.2f} ({:.2f})", f.median() * 1e-6, f.best() * 1e-6); }

int run(int argc, char** argv) {
  CLI::App app{"Embree 3 on the rays of docs/bench-protocol.md (beside `cohort bench`)", "cohort-embree-bench"};
  std::vector<std::filesystem::path> scenes;
  std::string views = "exterior", json, build_quality = "medium";
  unsigned trace_res = 1024, reps = 3, threads = 2;
  app.add_option("scenes", scenes, "Scene files")->required();
  app.add_option("--view", views, "exterior, interior or both (comma list)");
  app.add_option("--trace-res", trace_res, "Image side N (N x N primary rays)")->check(CLI::Range(1, 16384));
  app.add_option("--reps", reps, "Repetitions (median and best)")->check(CLI::Range(3, 1000));
  app.add_option("--threads", threads, "Threads for tracing and the BVH build")->check(CLI::Range(1, 1024));
  app.add_option("--build-quality", build_quality, "Embree's BVH build: low, medium (its default) or high")
      ->check(CLI::IsMember(kBuildQualities));
  app.add_option("--json", json, "Write the figures to this JSON file");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  std::vector<BenchView> view_list;
  for (const std::string& v : {std::string("exterior"), std::string("interior")})
    if (views.find(v) != std::string::npos) view_list.push_back(v == "interior" ? interior_view() : BenchView{});
  if (view_list.empty()) throw InputError(fmt::format("--view: no known view in '{}' (exterior, interior)", views));

  EmbreeDevice device(rtcNewDevice(fmt::format("threads={}", threads).c_str()));
  if (!device) throw std::runtime_error("embree: rtcNewDevice failed");
  const std::string version = fmt::format("{}.{}.{}", RTC_VERSION_MAJOR, RTC_VERSION_MINOR, RTC_VERSION_PATCH);
  fmt::print("Embree {} , {} threads, rtcIntersect1M in blocks of 256\n", version, threads);
  std::vector<SceneFigures> results;
  for (const auto& path : scenes) {
    const auto load_start = std::chrono::steady_clock::now();
    const Scene scene = load_scene(path);
    SceneFigures s;
    s.path = path;
    s.triangles = scene.triangle_count();
    s.load_seconds = seconds_since(load_start);
    s.bounds = scene.bounds();
    auto [bvh, build_seconds] = build_bvh(device.get(), scene.positions, kBuildQualities.at(build_quality));
    s.kdtree.build_seconds = build_seconds;  // here: the BVH
    for (const BenchView& view : view_list) {
      ViewFigures vf;
      vf.view = view;
      vf.camera = view_camera(s.bounds, view);
      const auto primary = protocol_primary_rays(vf.camera, trace_res);
      vf.primary = trace(bvh.get(), primary, reps, threads, true);
      const auto diffuse = protocol_diffuse_rays(primary, vf.primary->closest, scene.positions, s.bounds.diagonal());
      vf.primary->closest.clear();
      vf.diffuse = trace(bvh.get(), diffuse, reps, threads, false);
      vf.diffuse->closest.clear();
      fmt::print("{} [{} view], {} triangles, BVH build ({}) {:.3f}s\n  Mrays/s, median (best): primary {} with {} hits of "
                 "{} rays; diffuse {} over {} rays\n",
                 path.string(), view.name, s.triangles, build_quality, build_seconds, mrays(vf.primary->rays_per_second),
                 vf.primary->hits, vf.primary->rays, mrays(vf.diffuse->rays_per_second), vf.diffuse->rays);
      s.views.push_back(std::move(vf));
    }
    results.push_back(std::move(s));
  }
  if (!json.empty()) {
    nlohmann::json j;
    j["peer"] = "embree";
    j["embree"] = {{"version", version}, {"threads", threads}, {"build_quality", build_quality},
                   {"api", "rtcIntersect1M, blocks of 256, TBB task_arena; coherent primary, incoherent diffuse"}};
    j["settings"] = {{"trace_res", trace_res}, {"reps", reps}};
    j["scenes"] = scenes_json(results, "bvh");
    write_file_atomically(json, j.dump(2) + "\n");
    fmt::print("wrote {}\n", json);
  }
  return 0;
}

}  // namespace
}  // namespace cohort

int main(int argc, char** argv) {
  try {
    return cohort::run(argc, argv);
  } catch (const cohort::InputError& e) {
    fmt::print(stderr, "cohort-embree-bench: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "cohort-embree-bench: {}\n", e.what());
    return 1;
  }
}

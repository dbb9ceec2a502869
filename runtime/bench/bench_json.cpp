#include "runtime/bench/bench_json.h"

#include "runtime/backend/device_support.h"
#include "runtime/bench/build_info.h"

namespace cohort {
namespace {

nlohmann::json vec3_json(const glm::vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json trace_json(const TraceFigures& f) {
  return {{"rays", f.rays}, {"hits", f.hits}, {"mrays_per_second", rate_json(f.rays_per_second)}};
}

nlohmann::json method_json(const MethodFigures& f) {
  const RenderResult& m = f.median;
  nlohmann::json j = {{"rays", m.rays},
                      {"mrays_per_second", rate_json(f.rays_per_second)},
                      {"msamples_per_second", rate_json(f.samples_per_second)},
                      {"msamples_per_cpu_second", rate_json(f.samples_per_cpu_second)},
                      {"simd_efficiency", m.simd_efficiency},
                      {"render_seconds", m.render_seconds},
                      {"breakdown_seconds", f.breakdown},
                      {"kernel_seconds", m.kernel_seconds},
                      {"pass_seconds", {{"median", f.pass_seconds_median}, {"max", f.pass_seconds_max}}},
                      {"max_nodes_per_ray", f.max_nodes_per_ray}};
  if (m.wavefront.slots) j["wavefront_size"] = m.wavefront.slots;
  if (!m.auto_choice.method.empty()) j["auto_pick"] = m.auto_choice.method;
  if (m.coherence) j["coherence"] = coherence_json(*m.coherence);
  return j;
}

nlohmann::json view_json(const ViewFigures& v) {
  nlohmann::json j = {{"view", v.view.name},
                      {"camera", {{"eye", vec3_json(v.camera.eye)}, {"target", vec3_json(v.camera.target)},
                                  {"up", {0, 1, 0}}, {"vfov_degrees", v.camera.vfov_degrees}}}};
  if (v.view.camera_bounds) j["camera_bounds"] = *v.view.camera_bounds;
  if (v.primary) j["primary"] = trace_json(*v.primary);
  if (v.diffuse) j["diffuse"] = trace_json(*v.diffuse);
  nlohmann::json methods = nlohmann::json::object();
  for (const auto& m : v.methods) methods[m.method] = method_json(m);
  j["path_tracing"] = methods;
  return j;
}

}  // namespace

nlohmann::json rate_json(const RateFigure& f, double scale) {
  nlohmann::json runs = nlohmann::json::array();
  for (double r : f.runs) runs.push_back(r * scale);
  return {{"median", f.median() * scale}, {"best", f.best() * scale}, {"runs", runs}};
}

nlohmann::json sort_json(const SortSettings& s) {
  return {{"code", s.code},
          {"pth_levels", s.pth_levels},
          {"sort_from_bounce", s.sort_from_bounce},
          {"sort_payload", s.sort_payload}};
}

nlohmann::json coherence_json(const CoherenceFigures& c) {
  nlohmann::json j = sort_json(c.sort);
  j.update({{"key_bits", c.key_bits}, {"subtree_nodes", c.subtree_nodes}, {"speculative", c.speculative}});
  return j;
}

nlohmann::json bvh4_json(const Bvh4Stats& b) {
  return {{"nodes", b.node_count},         {"leaves", b.leaf_count},
          {"depth", b.depth},              {"average_leaf_triangles", b.average_leaf_triangles},
          {"sah_cost", b.sah_cost},        {"bytes", b.bytes},
          {"build_seconds", b.build_seconds}};
}

nlohmann::json scenes_json(const std::vector<SceneFigures>& scenes, const std::string& accel_key) {
  nlohmann::json list = nlohmann::json::array();
  for (const SceneFigures& s : scenes) {
    const auto& t = s.kdtree;
    nlohmann::json views = nlohmann::json::array();
    for (const auto& v : s.views) views.push_back(view_json(v));
    list.push_back({{"path", s.path.string()},
                    {"name", s.path.filename().string()},
                    {"triangles", s.triangles},
                    {"load_seconds", s.load_seconds},
                    {"bounds", {{"lo", vec3_json(s.bounds.lo)}, {"hi", vec3_json(s.bounds.hi)}}},
                    {accel_key, accel_key != "kdtree"
                                    ? nlohmann::json{{"build_seconds", t.build_seconds}}
                                    : nlohmann::json{{"build_seconds", t.build_seconds},
                                                     {"kind", s.tree_kind}, {"depth", t.depth},
                                                     {"nodes", t.node_count}, {"leaves", t.leaf_count},
                                                     {"average_leaf_triangles", t.average_leaf_triangles},
                                                     {"sah_cost", t.sah_cost}, {"bytes", t.bytes},
                                                     {"dropped_triangles", t.dropped_triangles}}},
                    {"views", views}});
    if (s.bvh4 && accel_key == "kdtree") list.back()[accel_key]["bvh4"] = bvh4_json(*s.bvh4);
    if (s.bvh8 && accel_key == "kdtree") list.back()[accel_key]["bvh8"] = bvh4_json(*s.bvh8);
    if (s.bvh8f && accel_key == "kdtree") list.back()[accel_key]["bvh8f"] = bvh4_json(*s.bvh8f);
  }
  return list;
}

nlohmann::json bench_json(const BenchDevice& d, const BenchOptions& o, const std::vector<SceneFigures>& scenes) {
  const BuildInfo b = build_info();
  const DeviceInfo& device = d.info;
  nlohmann::json j;
  j["cohort"] = {{"git_commit", b.git_commit}, {"build_type", b.build_type}, {"compiler", b.compiler},
                 {"cxx_flags", b.cxx_flags}, {"kernel_build_options", d.compile_options}};
  j["device"] = {{"name", device.name}, {"backend", backend_name(d.backend)},
                 {"platform", device.platform_name}, {"vendor", device.vendor},
                 {"version", device.version}, {"driver", device.driver_version}, {"is_gpu", device.is_gpu},
                 {"compute_units", device.compute_units}};
  j["settings"] = sort_json(o.sort);
  j["settings"].update({{"trace_res", o.trace_res}, {"res", o.res}, {"spp", o.spp}, {"reps", o.reps},
                        {"methods", o.methods}, {"workload", "white sky (docs/bench-protocol.md)"}, {"max_depth", 5},
                        // the order the protocol's rays are traced in, as the device's renders launch camera rays
                        {"trace_order", device_support(device).pixel_tiles ? "8x4 pixel tiles" : "rows"}});
  j["scenes"] = scenes_json(scenes);
  return j;
}

}  // namespace cohort

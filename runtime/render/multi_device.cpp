#include "runtime/render/multi_device.h"

#include <algorithm>
#include <chrono>

#include "runtime/render/launch_log.h"
#include "runtime/render/pass_driver.h"

namespace cohort {

DeviceWorkers::DeviceWorkers(const std::vector<DeviceInfo>& devices, const DeviceOpener& open,
                             const ProgramCache& cache, const PreparedScene& scene, const RenderSettings& settings,
                             PassSource& passes)
    : runs_(devices.size()) {
  for (std::size_t i = 0; i < devices.size(); ++i) {
    runs_[i].device = devices[i];
    threads_.emplace_back([this, i, open, &cache, &scene, settings, &passes] {
      try {
        DeviceRun& run = runs_[i];
        const auto t0 = std::chrono::steady_clock::now();
        const std::unique_ptr<Device> opened = open(i);
        const Device& cl = *opened;
        const DeviceScene device_scene = upload_scene(cl, scene.tree, scene.tables, scene.bvh());
        run.upload_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        RenderControl control;
        control.passes = &passes;
        run.result = render(cl, cache, device_scene, scene.camera, settings, {}, control);
      } catch (...) {
        {
          const std::lock_guard lock(failure_mutex_);
          if (!failure_) failure_ = std::current_exception();
        }
        passes.abort();
      }
    });
  }
}

DeviceWorkers::~DeviceWorkers() {
  for (auto& t : threads_)
    if (t.joinable()) t.join();
}

std::vector<DeviceRun> DeviceWorkers::join() {
  for (auto& t : threads_)
    if (t.joinable()) t.join();
  if (failure_) std::rethrow_exception(failure_);
  return runs_;
}

RenderResult merge_device_results(const std::vector<DeviceRun>& runs) {
  RenderResult merged;
  if (runs.empty()) return merged;
  const RenderResult& first = runs.front().result;
  merged.wavefront_size = first.wavefront_size;
  merged.path_state_bytes = first.path_state_bytes;
  merged.code_layout = first.code_layout;
  merged.code_key_bits = first.code_key_bits;
  merged.sort_from_bounce = first.sort_from_bounce;
  merged.auto_choice = first.auto_choice;
  merged.pth_levels = first.pth_levels;
  merged.pth_subtree_nodes = first.pth_subtree_nodes;
  merged.speculative = first.speculative;
  merged.sort_payload = first.sort_payload;
  merged.compile_from_cache = true;
  std::uint64_t groups = 0;
  double efficiency = 0;
  for (const auto& run : runs) {
    const RenderResult& r = run.result;
    merged.rays += r.rays;
    merged.passes += r.passes;
    merged.busy_seconds += r.busy_seconds;
    merged.pass_kernel_seconds.insert(merged.pass_kernel_seconds.end(), r.pass_kernel_seconds.begin(),
                                      r.pass_kernel_seconds.end());
    merged.pass_host_reads.insert(merged.pass_host_reads.end(), r.pass_host_reads.begin(), r.pass_host_reads.end());
    merged.pass_sort_launches.insert(merged.pass_sort_launches.end(), r.pass_sort_launches.begin(),
                                     r.pass_sort_launches.end());
    merged.max_nodes_per_ray = std::max(merged.max_nodes_per_ray, r.max_nodes_per_ray);
    merged.pass_stragglers.insert(merged.pass_stragglers.end(), r.pass_stragglers.begin(), r.pass_stragglers.end());
    keep_worst(merged.worst_rays, r.worst_rays, std::max<std::size_t>(r.worst_rays.size(), merged.worst_rays.size()));
    merged.compile_seconds = std::max(merged.compile_seconds, r.compile_seconds);
    merged.compile_from_cache = merged.compile_from_cache && r.compile_from_cache;
    add_seconds(merged.kernel_seconds, r.kernel_seconds);
    if (merged.iterations.size() < r.iterations.size()) merged.iterations.resize(r.iterations.size());
    for (std::size_t i = 0; i < r.iterations.size(); ++i) {
      IterationStats& into = merged.iterations[i];
      const IterationStats& from = r.iterations[i];
      into.live_paths += from.live_paths;
      into.shadow_rays += from.shadow_rays;
      into.simd_groups += from.simd_groups;
      into.simd_efficiency_sum += from.simd_efficiency_sum;
      add_seconds(into.kernel_seconds, from.kernel_seconds);
      groups += from.simd_groups;
      efficiency += from.simd_efficiency_sum;
    }
  }
  merged.simd_efficiency = groups ? efficiency / double(groups) : 0;
  return merged;
}

}  // namespace cohort

#include "runtime/render/run/multi_device.h"

#include <algorithm>
#include <chrono>

#include "runtime/render/run/launch_log.h"
#include "runtime/render/run/pass_driver.h"

namespace cohort {

// A device's thread: opens the device, then runs one task at a time until the pool stops.
struct DevicePool::Worker {
  std::mutex mutex;
  std::condition_variable wake, done;
  std::function<void()> task;  // set by the pool, cleared by the thread when it has run
  bool stopping = false;
  std::exception_ptr failure;  // the last task's (or the opening's)
  std::unique_ptr<Device> device;
  std::optional<DeviceScene> uploaded;
  const PreparedScene* uploaded_scene = nullptr;
  std::thread thread;

  Worker(const DeviceOpener& open, std::size_t index) {
    task = [this, open, index] { device = open(index); };
    thread = std::thread([this] { loop(); });
  }

  void loop() {
    std::unique_lock lock(mutex);
    for (;;) {
      wake.wait(lock, [&] { return stopping || task; });
      if (!task) return;
      lock.unlock();
      std::exception_ptr error;
      try {
        task();
      } catch (...) {
        error = std::current_exception();
      }
      lock.lock();
      failure = error;
      task = nullptr;
      done.notify_all();
    }
  }

  void post(std::function<void()> next) {
    const std::lock_guard lock(mutex);
    task = std::move(next);
    wake.notify_all();
  }

  // Waits for the task posted last; returns its failure.
  std::exception_ptr wait() {
    std::unique_lock lock(mutex);
    done.wait(lock, [&] { return !task; });
    return failure;
  }

  // The scene on the device: uploaded unless it is the one uploaded last.
  const DeviceScene& scene_for(const PreparedScene& scene) {
    if (uploaded_scene != &scene) {
      uploaded.reset();  // the old scene's buffers go first
      uploaded_scene = nullptr;
      uploaded.emplace(upload_scene(*device, scene.tree, scene.tables, scene.bvh()));
      uploaded_scene = &scene;
    }
    return *uploaded;
  }

  ~Worker() {
    {
      const std::lock_guard lock(mutex);
      stopping = true;
      wake.notify_all();
    }
    thread.join();
  }
};

DevicePool::DevicePool(const std::vector<DeviceInfo>& devices, const DeviceOpener& open) : runs_(devices.size()) {
  for (std::size_t i = 0; i < devices.size(); ++i) {
    runs_[i].device = devices[i];
    workers_.push_back(std::make_unique<Worker>(open, i));
  }
  wait_all();
}

DevicePool::DevicePool(std::size_t count, const DeviceOpener& open) : runs_(count) {
  for (std::size_t i = 0; i < count; ++i) workers_.push_back(std::make_unique<Worker>(open, i));
  wait_all();
  for (std::size_t i = 0; i < count; ++i) runs_[i].device = workers_[i]->device->info();
}

std::vector<DeviceInfo> DevicePool::infos() const {
  std::vector<DeviceInfo> out;
  for (const auto& run : runs_) out.push_back(run.device);
  return out;
}

void DevicePool::wait_all() {
  std::exception_ptr first;
  for (auto& w : workers_)
    if (auto failure = w->wait(); failure && !first) first = failure;
  if (first) std::rethrow_exception(first);
}

DevicePool::~DevicePool() = default;

void DevicePool::start(const ProgramCache& cache, const PreparedScene& scene, const RenderSettings& settings,
                       PassSource& passes) {
  for (std::size_t i = 0; i < workers_.size(); ++i) {
    Worker& w = *workers_[i];
    DeviceRun& run = runs_[i];
    run.result = {};
    run.upload_seconds = 0;
    w.post([&w, &run, &cache, &scene, settings, &passes] {
      try {
        const auto t0 = std::chrono::steady_clock::now();
        const DeviceScene& device_scene = w.scene_for(scene);
        run.upload_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        RenderControl control;
        control.passes = &passes;
        run.result = render(*w.device, cache, device_scene, scene.camera, settings, {}, control);
      } catch (...) {
        passes.abort();  // the other devices stop taking passes
        throw;
      }
    });
  }
}

std::vector<DeviceRun> DevicePool::join() {
  wait_all();
  return runs_;
}

void DevicePool::run_on(std::size_t index, const PreparedScene& scene,
                        const std::function<void(const Device&, const DeviceScene&)>& task) {
  Worker& w = *workers_.at(index);
  run_on(index, [&w, &scene, &task](const Device& device) { task(device, w.scene_for(scene)); });
}

void DevicePool::run_on(std::size_t index, const std::function<void(const Device&)>& task) {
  Worker& w = *workers_.at(index);
  w.post([&w, &task] { task(*w.device); });
  if (auto failure = w.wait()) std::rethrow_exception(failure);
}

void DevicePool::drop_scenes() {
  for (auto& w : workers_) {
    Worker& worker = *w;
    worker.post([&worker] {
      worker.uploaded.reset();
      worker.uploaded_scene = nullptr;
    });
  }
  wait_all();
}

DeviceWorkers::DeviceWorkers(DevicePool& pool, const ProgramCache& cache, const PreparedScene& scene,
                             const RenderSettings& settings, PassSource& passes)
    : pool_(pool) {
  pool_.start(cache, scene, settings, passes);
}

DeviceWorkers::~DeviceWorkers() {
  if (joined_) return;
  try {
    pool_.join();
  } catch (...) {  // unwinding already: the failure that matters is the one in flight
  }
}

std::vector<DeviceRun> DeviceWorkers::join() {
  joined_ = true;
  return pool_.join();
}

RenderResult merge_device_results(const std::vector<DeviceRun>& runs) {
  RenderResult merged;
  if (runs.empty()) return merged;
  const RenderResult& first = runs.front().result;
  merged.wavefront = first.wavefront;
  merged.coherence = first.coherence;
  merged.auto_choice = first.auto_choice;
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
      merged.iterations[i] += r.iterations[i];
      groups += r.iterations[i].simd_groups;
      efficiency += r.iterations[i].simd_efficiency_sum;
    }
  }
  merged.simd_efficiency = groups ? efficiency / double(groups) : 0;
  return merged;
}

}  // namespace cohort

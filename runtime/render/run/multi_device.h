// Several devices render one image at once. Each device has its own thread, context, scene
// upload, program build and renderer, and takes sample passes from one shared PassSource, so a slow
// device simply takes fewer passes; the source (PassJob) adds the partial films in pass order, so
// identical devices give the single-device image bit for bit.
#pragma once

#include <condition_variable>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/open_device.h"
#include "runtime/render/scene/prepared_scene.h"
#include "runtime/render/renderer.h"

namespace cohort {

struct DeviceRun {
  DeviceInfo device;
  RenderResult result;  // this device's figures: passes, rays, busy time, kernels (no image)
  double upload_seconds = 0;  // opening the device and uploading the scene in this render (0 when kept)
};

// Devices that stay open from one render to the next: each has a thread of its own that opens it
// (a CUDA context is current on the thread that made it) and keeps, between renders, the scene it
// uploaded last and the programs it built (Device::build_program), so a second render of the same
// scene loads, builds, uploads and compiles nothing.
class DevicePool {
 public:
  // Opens every device of `devices` (what `open` opens) on its own thread; throws the first failure.
  DevicePool(const std::vector<DeviceInfo>& devices, const DeviceOpener& open);
  // `count` devices, each as `open` opens it; their DeviceInfo is what the opened device reports.
  DevicePool(std::size_t count, const DeviceOpener& open);
  ~DevicePool();  // stops and joins the threads
  DevicePool(const DevicePool&) = delete;
  DevicePool& operator=(const DevicePool&) = delete;

  std::size_t size() const { return workers_.size(); }
  std::vector<DeviceInfo> infos() const;

  // Starts rendering `scene` (uploaded where it is not the scene a device holds: scenes are told
  // apart by address, so a scene must outlive its renders and stay unchanged while this pool holds
  // it) on every device, taking passes from `passes`; `cache`, `scene` and `passes` must outlive
  // join(). One render at a time.
  void start(const ProgramCache& cache, const PreparedScene& scene, const RenderSettings& settings, PassSource& passes);
  // Waits for every device of the render started; rethrows the first failure (which aborted the
  // shared passes).
  std::vector<DeviceRun> join();

  // Runs `task` on device `index`'s thread with `scene` uploaded there, and waits for it (the
  // first-hit AOVs after the passes); rethrows what it throws.
  void run_on(std::size_t index, const PreparedScene& scene,
              const std::function<void(const Device&, const DeviceScene&)>& task);
  // The same without a scene (work of the caller's own on the device, such as `cohort bench`'s
  // traversal workloads).
  void run_on(std::size_t index, const std::function<void(const Device&)>& task);

  // Every device frees the scene it uploaded last, so that a scene made later at the same address
  // is uploaded (a caller that renders several scenes one after another).
  void drop_scenes();

 private:
  struct Worker;
  void wait_all();  // for every worker's task; rethrows the first failure
  std::vector<std::unique_ptr<Worker>> workers_;
  std::vector<DeviceRun> runs_;
};

// One render on a pool, as `RenderTeam::follow` starts them: started at construction, joined by
// join() or, with any failure dropped, by the destructor.
class DeviceWorkers {
 public:
  DeviceWorkers(DevicePool& pool, const ProgramCache& cache, const PreparedScene& scene, const RenderSettings& settings,
                PassSource& passes);
  ~DeviceWorkers();
  DeviceWorkers(const DeviceWorkers&) = delete;
  DeviceWorkers& operator=(const DeviceWorkers&) = delete;
  std::vector<DeviceRun> join();

 private:
  DevicePool& pool_;
  bool joined_ = false;
};

// The figures of several devices as one render's: rays, kernel and bounce figures summed, the
// slowest compile, the first device's wavefront and coherence settings.
RenderResult merge_device_results(const std::vector<DeviceRun>& runs);

}  // namespace cohort

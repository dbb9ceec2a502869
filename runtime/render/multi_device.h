// Several devices render one image at once. Each device has its own thread, context, scene
// upload, program build and renderer, and takes sample passes from one shared PassSource, so a slow
// device simply takes fewer passes; the source (PassJob) adds the partial films in pass order, so
// identical devices give the single-device image bit for bit.
#pragma once

#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/open_device.h"
#include "runtime/render/prepared_scene.h"
#include "runtime/render/renderer.h"

namespace cohort {

struct DeviceRun {
  DeviceInfo device;
  RenderResult result;  // this device's figures: passes, rays, busy time, kernels (no image)
  double upload_seconds = 0;
};

class DeviceWorkers {
 public:
  // Starts rendering at once; `scene`, `cache` and `passes` must outlive join(). `devices` name
  // what `open` opens, for the figures.
  DeviceWorkers(const std::vector<DeviceInfo>& devices, const DeviceOpener& open, const ProgramCache& cache,
                const PreparedScene& scene, const RenderSettings& settings, PassSource& passes);
  ~DeviceWorkers();  // joins
  DeviceWorkers(const DeviceWorkers&) = delete;
  DeviceWorkers& operator=(const DeviceWorkers&) = delete;

  // Waits for every device; rethrows the first failure (which aborted the shared passes).
  std::vector<DeviceRun> join();

 private:
  std::vector<DeviceRun> runs_;
  std::vector<std::thread> threads_;
  std::mutex failure_mutex_;
  std::exception_ptr failure_;
};

// The figures of several devices as one render's: rays, kernel and bounce figures summed, the
// slowest compile, the first device's wavefront and coherence settings.
RenderResult merge_device_results(const std::vector<DeviceRun>& runs);

}  // namespace cohort

// What every method's render function receives, and the methods (one file each in this folder):
// naive, the megakernel; wavefront, sc, rg and sc+rg, the wavefront schedules; hash, the hash sort;
// pth, the paper's method, lives with the rest of the paper's pipeline in runtime/render/pth. Each
// file shows its method as the sequence of stages (runtime/render/stages) one bounce runs.
#pragma once

#include <memory>

#include "runtime/render/run/pass_driver.h"
#include "runtime/render/renderer.h"

namespace cohort {

struct WavefrontMemory;
enum class RayOrder;  // runtime/render/pth/sorted_traversal.h

struct MethodInputs {
  const Device& device;
  const ProgramCache& cache;
  const DeviceScene& scene;
  const RenderParams& params;
  const RenderSettings& settings;
  const ProgressCallback& progress;
  const RenderControl& control;
  // The pool and results buffer every wavefront method uses alike: auto sets up one for all the
  // methods it probes. Null: a wavefront method allocates its own.
  std::shared_ptr<WavefrontMemory> wavefront_memory = nullptr;
};

// Each method sets itself up on the device and returns what drive_passes drives.
std::unique_ptr<PassLauncher> naive_method(const MethodInputs& in);
std::unique_ptr<PassLauncher> wavefront_method(const MethodInputs& in);
std::unique_ptr<PassLauncher> sc_method(const MethodInputs& in);
std::unique_ptr<PassLauncher> rg_method(const MethodInputs& in);
std::unique_ptr<PassLauncher> sc_rg_method(const MethodInputs& in);
std::unique_ptr<PassLauncher> hash_method(const MethodInputs& in);
std::unique_ptr<PassLauncher> pth_method(const MethodInputs& in);
// The ray-sorting bounce with the rays sorted by `order` (runtime/render/pth/sorted_traversal_method.cpp):
// pth, and with RayOrder::hash the hash method.
std::unique_ptr<PassLauncher> sorted_traversal_method(const MethodInputs& in, RayOrder order);
std::unique_ptr<PassLauncher> auto_method(const MethodInputs& in);

}  // namespace cohort

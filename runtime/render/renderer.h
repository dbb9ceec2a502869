// Renders a scene on one device with one method and reports what it measured.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"
#include "runtime/image/image.h"
#include "runtime/render/run/checkpoint.h"
#include "runtime/render/scene/device_scene.h"
#include "runtime/render/run/pass_source.h"
#include "runtime/render/render_settings.h"

namespace cohort {

struct Progress {
  std::uint32_t samples_done = 0;
  std::uint32_t samples_target = 0;  // 0 when only --time bounds the render
  std::uint64_t rays = 0;
  double seconds = 0;
};

// One bounce of a wavefront method (one iteration of its loop), summed over passes and devices:
// a figure added here is added to the sum below and to --stats's "bounces".
struct IterationStats {
  std::uint64_t live_paths = 0;  // paths traced this iteration (= extension rays)
  std::uint64_t shadow_rays = 0;
  std::uint64_t simd_groups = 0;        // groups of 32 traced rays
  double simd_efficiency_sum = 0;       // sum over groups of mean / max nodes visited
  std::map<std::string, double> kernel_seconds;

  IterationStats& operator+=(const IterationStats& other) {
    live_paths += other.live_paths;
    shadow_rays += other.shadow_rays;
    simd_groups += other.simd_groups;
    simd_efficiency_sum += other.simd_efficiency_sum;
    for (const auto& [name, seconds] : other.kernel_seconds) kernel_seconds[name] += seconds;
    return *this;
  }
};

// An extension ray that visited many KD-tree nodes, as traced: it replays on the host
// (`cohort info SCENE --replay STATS.json`) with kd_trace_steps on [tmin, tmax].
struct StragglerRay {
  std::uint32_t nodes = 0;
  glm::vec3 org{0.f}, dir{0.f};
  float tmin = 0.f, tmax = INFINITY;
};

// Nodes visited per extension ray in one pass (RenderSettings::straggler_rays).
struct PassStragglers {
  std::uint32_t max = 0;
  std::uint32_t p9999 = 0;  // 99.99th percentile
};

// What --method auto probed and chose (runtime/render/methods/auto.cpp).
struct AutoChoice {
  std::string method;                                   // empty: not auto
  std::string reason;                                   // why: the fastest probed, or a default
  bool screen_rows = false;  // the megakernel's screen took every 8th row of one sample
  double probe_seconds = 0;  // the probing methods' launches (their samples are part of the image)
  std::map<std::string, double> probe_rays_per_second;  // the screen: every method probed
  std::map<std::string, double> final_rays_per_second;  // the final round: those near the screen's best
};

// A wavefront method's pool of path slots.
struct WavefrontFigures {
  std::size_t slots = 0;             // path slots in the pool; 0: not a wavefront method
  std::size_t path_state_bytes = 0;  // device bytes per path slot (a sorting method's sort state included)
};

// How hash and pth ordered their rays: the sort as resolved (the code used, the levels walked),
// the key's width, the PTH walk and the resumed traversal. Filled once by the sort's report,
// written by coherence_json for --stats and the bench JSON alike.
struct CoherenceFigures {
  SortSettings sort;                   // code: the layout used; pth_levels: subtree levels in local memory
  std::uint32_t key_bits = 0;          // the code's width (sorted as 32-bit keys up to 32)
  std::uint32_t subtree_nodes = 0;
  bool speculative = false;            // resumed with speculative traversal
};

struct RenderResult {
  Image image;                 // mean radiance per pixel
  std::uint32_t samples = 0;   // per pixel
  std::uint64_t rays = 0;      // extension + shadow rays
  std::uint64_t dropped_samples = 0;  // NaN or infinite, counted as zero
  double render_seconds = 0;   // wall time of the render loop
  // this process's CPU time (every thread's: the OpenCL runtime's workers too) from starting the
  // devices to the last pass (a cold kernel compile included): on a loaded machine it varies
  // less than the wall time. `cohort render` only, rank 0's process.
  double render_cpu_seconds = 0;
  double compile_seconds = 0;
  bool compile_from_cache = false;
  std::map<std::string, double> kernel_seconds;  // device time per kernel name
  std::vector<IterationStats> iterations;        // wavefront methods only
  WavefrontFigures wavefront;                    // wavefront methods
  double simd_efficiency = 0;                    // traversal: mean over max steps per 32 rays
  std::optional<CoherenceFigures> coherence;     // hash and pth
  AutoChoice auto_choice;                        // --method auto: the probe and its pick
  bool interrupted = false;                      // stopped by stop_requested before the sample count
  std::uint32_t resumed_samples = 0;             // samples taken over from a checkpoint
  std::uint32_t passes = 0;                      // sample passes this device rendered
  double busy_seconds = 0;                       // wall time inside those passes
  std::vector<double> pass_kernel_seconds;       // device time of each pass, in the order rendered
  // per launch of the pass function (a pass may take several): blocking reads of device memory
  // inside it, and device commands its ray sorts issued
  std::vector<std::uint32_t> pass_host_reads, pass_sort_launches;
  std::uint32_t max_nodes_per_ray = 0;           // the most KD-tree nodes one ray visited
  std::vector<PassStragglers> pass_stragglers;   // with settings.straggler_rays only
  std::vector<StragglerRay> worst_rays;          // the most nodes first
};

using ProgressCallback = std::function<void(const Progress&)>;

// How a render starts, and when it saves its film or stops early.
struct RenderControl {
  std::optional<FilmState> resume_from;                // continue this film (same size, same settings)
  std::function<bool()> stop_requested;                // checked after every pass
  double checkpoint_seconds = 0;                       // save every this many seconds; 0: only at the end
  std::function<void(const FilmState&)> checkpoint;    // saves the film; also called when the render ends
  // Shared work of several devices (runtime/render/run/multi_device.h): the device takes its passes
  // there and the caller combines the image. Null: this render owns all passes of the image.
  PassSource* passes = nullptr;
};

// Renders with settings.method (see methods.h).
RenderResult render(const Device& cl, const ProgramCache& cache, const DeviceScene& scene,
                    const SceneCamera& camera, const RenderSettings& settings, const ProgressCallback& progress = {},
                    const RenderControl& control = {});

}  // namespace cohort

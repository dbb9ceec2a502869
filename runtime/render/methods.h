// The rendering methods: the megakernel and the wavefront variants, which differ only in two
// scheduling choices (see kernels/wavefront.cl).
#pragma once

#include <string>
#include <vector>

#include "runtime/render/renderer.h"

namespace cohort {

// How a wavefront method orders rays before traversal.
enum class RaySort {
  none,
  hash,  // by origin and direction hash (Garanzha & Loop 2010)
  pth,   // by the coherence code with partial traversal in local memory (Wang & Deng)
};

struct Method {
  const char* name;
  const char* description;
  bool wavefront;   // false: the NAIVE megakernel
  bool compact;     // stream compaction: launches cover a queue of live paths only (Wald 2011)
  bool regenerate;  // path regeneration: free slots take new paths after every bounce (Novak 2010)
  RaySort sort = RaySort::none;
};

const std::vector<Method>& methods();
std::vector<std::string> method_names();
const Method& find_method(const std::string& name);  // throws InputError for an unknown name

RenderResult render_naive(const Device& cl, const ProgramCache& cache, const DeviceScene& scene,
                          const RenderParams& params, const RenderSettings& settings, const ProgressCallback& progress,
                          const RenderControl& control);
RenderResult render_wavefront(const Method& method, const Device& cl, const ProgramCache& cache,
                              const DeviceScene& scene, const RenderParams& params, const RenderSettings& settings,
                              const ProgressCallback& progress, const RenderControl& control);

}  // namespace cohort

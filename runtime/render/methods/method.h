// What every method's render function receives, and the methods (one file each in this folder):
// naive, the megakernel; wavefront, sc, rg and sc+rg, the wavefront schedules; hash and pth, the
// ray-sorting methods. Each file shows its method as the sequence of stages (runtime/render/stages)
// one bounce runs.
#pragma once

#include "runtime/render/renderer.h"

namespace cohort {

struct MethodInputs {
  const Device& device;
  const ProgramCache& cache;
  const DeviceScene& scene;
  const RenderParams& params;
  const RenderSettings& settings;
  const ProgressCallback& progress;
  const RenderControl& control;
};

RenderResult render_naive(const MethodInputs& in);
RenderResult render_wavefront(const MethodInputs& in);
RenderResult render_sc(const MethodInputs& in);
RenderResult render_rg(const MethodInputs& in);
RenderResult render_sc_rg(const MethodInputs& in);
RenderResult render_hash(const MethodInputs& in);
RenderResult render_pth(const MethodInputs& in);
RenderResult render_auto(const MethodInputs& in);

}  // namespace cohort

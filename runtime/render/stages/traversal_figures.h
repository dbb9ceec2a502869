// What a traversal launch measures after it ran: its SIMD efficiency (wf_simd_efficiency) and,
// with RenderSettings::straggler_rays, the rays that visited the most nodes.
#pragma once

#include <cstdint>

#include "runtime/render/stages/wavefront_loop.h"

namespace cohort {

// `slots` maps the launch's indices to path slots (the compacted queue, or the sorted order);
// null: the index is the slot.
void measure_traversal(WavefrontPass& pass, const DeviceBuffer* slots, std::uint32_t count);

}  // namespace cohort

// The wavefront pool: path slots in structure-of-arrays buffers (PATH_BUFFERS of
// kernels/common/kernel_params.h), their hits and shadow rays, the queue of live slots and the
// queue counters (COUNTER_* of kernels/common/contract.h).
#pragma once

#include <cstddef>
#include <cstdint>

#include "runtime/backend/device.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/render/render_settings.h"

namespace cohort {

struct PathPool {
  std::uint32_t slots = 0;
  PathBuffers path;
  DeviceBuffer hits, steps;  // steps: nodes visited per launch index of the last traversal launch
  ShadowBuffers shadow;
  DeviceBuffer queue, counters;

  PathPool(const Device& device, std::uint32_t slots);
};

// Enough paths in flight to fill the device: a few thousand per compute unit on a GPU, more on a
// CPU whose "compute units" are cores; never more than a quarter of the device memory, and never
// more than `items`.
std::uint32_t choose_pool_size(const Device& device, const RenderSettings& s, std::uint64_t items,
                               std::size_t bytes_per_slot);

}  // namespace cohort

// The wavefront pool: path slots in structure-of-arrays buffers (PATH_SLOT of
// kernels/common/core/path_slot.h), their hits and shadow rays, the queue of live slots and the
// queue counters (COUNTER_* of kernels/common/core/contract.h).
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

// The paths a wave holds on this device, before a pass's work items bound it: --wavefront-size, or
// enough to fill the device. On a GPU 32768 per compute unit, so a large GPU (an H200: 132 units)
// holds over 4M paths, the wave size at which sorting rays pays (`cohort bench --gate`); on a
// CPU, whose "compute units" are cores, 32768 per core up to 2M. Never more than a quarter of the
// device memory and of its largest allocation, counting the state of the most demanding method
// (pth with its deepest saved stack) for all: the same size for every wavefront method, so their
// comparison stays fair.
std::uint32_t device_pool_size(const DeviceInfo& device, const RenderSettings& s);

}  // namespace cohort

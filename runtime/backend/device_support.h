// What Cohort can do on a device, from the limits it reports: whether it runs there at all, the
// work-group sizes its launches take, how many PTH levels fit in its local memory, and whether the
// BVH walk prefetches. `cohort devices` prints it; opening a device that cannot run refuses it with
// the reason (exit 2) instead of a driver error at the first launch.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "runtime/backend/device_info.h"

namespace cohort {

struct DeviceSupport {
  bool runs = true;
  std::string refusal;              // why not, naming the device and the limit; empty when it runs
  std::size_t work_group = 1;       // the most work items a launch of the default size takes there
  std::size_t local_budget = 0;     // bytes of local memory the PTH subtree may take
  std::uint32_t pth_levels = 0;     // full levels of a tree's top that fit in local_budget
  bool prefetch = false;            // the BVH walk prefetches (kernels/common/core/port.h, co_prefetch)
  // the naive megakernel traces two samples' paths in lock step on the 8-wide BVH with float planes
  // (kernels/common/wavefront/pathtrace.h, trace_paths_paired)
  bool paired_walks = false;
  // the BVH box tests compute each slab in one fused multiply-add (kernels/common/accel/bvh4_traverse.h,
  // BVH_SLAB4); without it the host passes -DCOHORT_UNFUSED_SLABS. The same hits either way.
  bool fused_slabs = true;
  // the 4-wide BVH's step sorts every node's entered children, with no branch on how many there are
  // (kernels/common/accel/bvh4_traverse.h, bvh4_descend): the host passes -DCOHORT_BRANCH_FREE_DESCEND
  bool branch_free_descend = false;
  // the box tests of the programs that opt in (naive, trace) take min and max instructions, one each
  // where a compare and a select took two (kernels/common/core/port.h): the host passes
  // -DCOHORT_GPU_MINMAX. The same values, so the same hits either way.
  bool gpu_minmax = false;
  // a pass's work items take the image's pixels in 8x4 tiles, so that a warp's camera rays are one
  // compact patch (kernels/common/core/types.h, tiled_pixel): the host passes -DCOHORT_PIXEL_TILES,
  // and the bench traces the protocol's rays in that order. The same samples either way.
  bool pixel_tiles = false;
  // The device radix sort (hash, pth, the gate benchmark) hands tiles from one work-group to the next
  // within a launch (decoupled look-back), which needs the groups of a launch to make progress
  // independently. OpenCL reports no such property; Mesa's OpenCL (rusticl, clover) was measured
  // without it (llvmpipe: misplaced pairs with one item per group, a hang with more), so there the
  // sorting methods are left out, with this reason.
  bool sorts = true;
  std::string sort_refusal;
};

// The OpenCL C version the kernels are written in; older devices are refused.
inline constexpr int kRequiredOpenClC = 102;  // 1.2

// "OpenCL C 1.2 ..." as 102; 0 when the text says no version.
int parse_opencl_c_version(const std::string& text);

DeviceSupport device_support(const DeviceInfo& device);

}  // namespace cohort

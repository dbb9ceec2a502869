#include "runtime/backend/device_support.h"

#include <cstdio>

#include <fmt/format.h>

#include "common/core/types.h"
#include "runtime/backend/device.h"

namespace cohort {

int parse_opencl_c_version(const std::string& text) {
  const std::string prefix = "OpenCL C ";
  const auto at = text.find(prefix);
  if (at == std::string::npos) return 0;
  int major = 0, minor = 0;
  if (std::sscanf(text.c_str() + at + prefix.size(), "%d.%d", &major, &minor) != 2) return 0;
  return major * 100 + minor;
}

DeviceSupport device_support(const DeviceInfo& device) {
  DeviceSupport s;
  s.work_group = launch_group(device.max_work_group, 1, 0);
  // a scratchpad shared by the groups of a compute unit: leave room for two of them; PoCL's and
  // other CPU runtimes' local memory is cached global memory, all of it usable
  s.local_budget = device.local_memory_is_global ? device.local_memory : device.local_memory / 2;
  while (s.pth_levels < 10 && ((std::size_t(2) << s.pth_levels) - 1) * sizeof(KdNode) <= s.local_budget) ++s.pth_levels;
  // prefetch pays where the caches are all there is (local memory is global memory: PoCL, Intel's
  // CPU runtime, rusticl's llvmpipe); GPUs hide the latency with other warps; Oclgrind checks the
  // kernels and does not time them
  s.prefetch = device.local_memory_is_global && !is_oclgrind(device);
  // two walks in turn let a core wait on two nodes' loads at once where a work item runs as scalar
  // code of its own (PoCL's CPU driver). Intel's CPU runtime and llvmpipe pack work items into SIMD
  // lanes, and the pair's private state made their naive renders 5.5x and 53x slower (2026-12-06); a
  // GPU hides the latency with other warps. Oclgrind runs them so that its checks cover them.
  s.paired_walks = (is_pocl(device) && device.local_memory_is_global) || is_oclgrind(device);
  // one fma per slab where a subtract and a multiply were (2026-12-06, 4 alternated rounds: H200 CUDA
  // primary rays 1.06x, sc+rg 1.02x; PoCL naive 1.01-1.13x): where the device has it in hardware
  // (CL_FP_FMA, which PoCL reports and Intel's CPU runtime and llvmpipe do not; every CUDA device),
  // but not on OpenCL GPUs, where NVIDIA's compiler traced diffuse rays at 0.95x and sc+rg at 0.99x
  // with it, and not on Oclgrind, so that CI's checks run the unfused form too
  s.fused_slabs = device.fma && !(device.is_gpu && device.platform_name != "CUDA") && !is_oclgrind(device);
  // on GPUs the lanes of a warp enter different numbers of children, and the CPU's branches on that
  // count split the warp (H100, 2026-12-06: naive 1.02-1.03x, sc+rg 1.01x without them); Oclgrind
  // takes the GPU's form so that CI's checks cover it (CUDA devices always do: bvh4_traverse.h)
  s.branch_free_descend = device.is_gpu || is_oclgrind(device);
  // a GPU's min and max instructions in the naive and trace programs' box tests (H100, 2026-12-07:
  // docs/design.md, "Box tests"); not in the wavefront extension kernel, which ran slower with
  // them; Oclgrind again so that CI's checks cover them (CUDA devices always do: port.h)
  s.gpu_minmax = s.branch_free_descend;
  // camera rays in 8x4 pixel tiles on GPUs (docs/design.md, "Pixel order": primary rays 1.18x on an
  // H100, path tracing 1.01-1.03x; no gain on PoCL, which keeps rows);
  // Oclgrind too, so that CI renders through the tiled order to PoCL's bits (CUDA always: port.h)
  s.pixel_tiles = s.branch_free_descend;
  if (device.platform_name == "rusticl" || device.platform_name == "Clover") {
    s.sorts = false;
    s.sort_refusal = fmt::format("{} ({}) does not run the work-groups of a launch independently, which the "
                                 "device radix sort's look-back needs (docs/vendors.md)",
                                 device.name, device.platform_name);
  }
  const int c = parse_opencl_c_version(device.opencl_c_version);  // 0 for CUDA devices
  if (c != 0 && c < kRequiredOpenClC) {
    s.runs = false;
    s.refusal = fmt::format("{} compiles OpenCL C {}.{}; Cohort's kernels need OpenCL C 1.2", device.name, c / 100,
                            c % 100);
  }
  return s;
}

}  // namespace cohort

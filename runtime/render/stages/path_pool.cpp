#include "runtime/render/stages/path_pool.h"

#include <algorithm>
#include <array>
#include <vector>

#include "kernels/common/core/contract.h"

namespace cohort {

std::uint32_t device_pool_size(const DeviceInfo& device, const RenderSettings& s) {
  // every buffer of every method per slot; the largest: the saved traversal stacks of pth (twice
  // with --sort-payload gather)
  constexpr std::uint64_t kBytesPerSlot =
      WAVEFRONT_SLOT_BYTES + SORT_SLOT_BYTES + SORT_GATHER_SLOT_BYTES + 2 * PTH_MAX_LEVELS * sizeof(SavedStackEntry);
  constexpr std::uint64_t kLargestBufferPerSlot = PTH_MAX_LEVELS * sizeof(SavedStackEntry);
  std::uint64_t slots = s.wavefront_size;
  if (slots == 0) {
    const std::uint64_t most = device.is_gpu ? 1u << 23 : 1u << 21;
    slots = std::clamp<std::uint64_t>(std::uint64_t(32768) * device.compute_units, 65536, most);
    slots = std::min<std::uint64_t>(slots, device.global_memory / 4 / kBytesPerSlot);
    if (device.max_allocation) slots = std::min<std::uint64_t>(slots, device.max_allocation / kLargestBufferPerSlot);
  }
  return static_cast<std::uint32_t>(std::max<std::uint64_t>(slots, 1));
}

PathPool::PathPool(const Device& cl, std::uint32_t n) : slots(n) {
  const std::size_t f4 = std::size_t(n) * sizeof(co_float4), u = std::size_t(n) * sizeof(std::uint32_t);
  path.path_org = cl.allocate("path origins", f4);
  path.path_dir = cl.allocate("path directions", f4);
  path.path_throughput = cl.allocate("path throughput", f4);
  path.path_radiance = cl.allocate("path radiance", f4);
  path.path_prev = cl.allocate("path previous vertex", f4);
  const std::vector<std::uint32_t> free_slots(n, ITEM_NONE);
  path.path_item = cl.allocate("path work items", u, free_slots.data());
  path.path_segment = cl.allocate("path segments", u);
  path.path_status = cl.allocate("path status", u);
  hits = cl.allocate("hits", std::size_t(n) * sizeof(HitOut));
  steps = cl.allocate("traversal steps", u);
  shadow.shadow_org = cl.allocate("shadow origins", f4);
  shadow.shadow_dir = cl.allocate("shadow directions", f4);
  shadow.shadow_contribution = cl.allocate("shadow contributions", f4);
  shadow.shadow_queue = cl.allocate("shadow queue", u);
  queue = cl.allocate("path queue", u);
  const std::array<std::uint32_t, COUNTER_WORDS> zero{};
  counters = cl.allocate("queue counters and bounce figures", sizeof(zero), zero.data());
}

}  // namespace cohort

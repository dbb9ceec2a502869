#include "runtime/render/stages/path_pool.h"

#include <algorithm>
#include <array>

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
  // one buffer per entry of PATH_SLOT (kernels/common/core/path_slot.h); every slot starts free
#define CO_SLOT_ALLOCATE(A, buf, T, N, state, f, wf, what) \
  path.path_##buf = cl.allocate(what, std::size_t(n) * sizeof(CO_SLOT_TYPE(T, N)));
  PATH_SLOT(CO_SLOT_ALLOCATE, _)
#undef CO_SLOT_ALLOCATE
  cl.fill(path.path_item, ITEM_NONE, n);
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

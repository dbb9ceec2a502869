#include "runtime/render/stages/path_pool.h"

#include <algorithm>
#include <array>
#include <vector>

#include "kernels/common/contract.h"

namespace cohort {

std::uint32_t choose_pool_size(const Device& device, const RenderSettings& s, std::uint64_t items,
                               std::size_t bytes_per_slot) {
  std::uint64_t slots = s.wavefront_size;
  if (slots == 0) {
    const std::uint64_t per_cu = device.info().is_gpu ? 8192 : 32768;
    slots = std::clamp<std::uint64_t>(per_cu * device.info().compute_units, 65536, 1u << 21);
    slots = std::min<std::uint64_t>(slots, device.info().global_memory / 4 / bytes_per_slot);
  }
  slots = std::min<std::uint64_t>(slots, items);
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
  const std::array<std::uint32_t, COUNTER_COUNT> zero{};
  counters = cl.allocate("queue counters", sizeof(zero), zero.data());
}

}  // namespace cohort

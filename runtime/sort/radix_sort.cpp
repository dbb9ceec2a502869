// Host side of the device radix sort (kernels/common/radix_sort_kernels.h): tiling, buffers and the pass loop.
#include "runtime/sort/radix_sort.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "runtime/util/error.h"

namespace cohort {
namespace {

constexpr unsigned kDigitBits = 4;  // RADIX_BITS in the kernel
constexpr std::uint32_t kRadix = 1u << kDigitBits;
constexpr unsigned kMaxKeyBits = 64;
constexpr std::uint32_t kScanItems = 32;  // SCAN_ITEMS in the kernel

std::uint32_t div_up(std::uint32_t a, std::uint32_t b) { return (a + b - 1) / b; }

std::uint32_t floor_pow2(std::size_t x) {
  std::uint32_t p = 1;
  while (p * 2 <= x && p < (1u << 30)) p *= 2;
  return p;
}

// Local memory of sort_scatter and sort_scan_segments as the kernels declare it.
std::size_t scatter_local_bytes(std::uint32_t group, std::uint32_t items, bool local_exchange) {
  const std::size_t table = std::size_t(kRadix) * group;
  const std::size_t tile = local_exchange ? std::size_t(group) * items * (8 + 4) : 0;
  return tile + (table + table / 32) * 4 + std::size_t(group) * 4 + kRadix * 4;
}

std::size_t scan_local_bytes(std::uint32_t scan_group) {
  const std::size_t table = std::size_t(kScanItems) * scan_group;
  return (table + table / 32) * 4 + std::size_t(scan_group) * 4;
}

}  // namespace

// Tiling from the device.
// CPU (PoCL): one work item per work-group and 4096 pairs per item. PoCL runs the work items of a
// group as SIMD lanes, so a wider group turns every per-item run into gathers and scatters; one
// item per group is a plain sequential loop, the classic CPU radix sort pass over a chunk, and
// local memory is ordinary cached memory there, so tiles are not staged through it. Measured on
// the 2-core PoCL machine (1M pairs, 44 bits, scripts/bench-sort): 64 x 32 staged took ~5x the
// processor time of 1 x 4096 direct; 1 x 4096 .. 1 x 32768 were within noise of each other, and
// 4096 keeps 16 blocks for 64K pairs.
// GPU (and any device with real local memory): 256 work items (8 warps of 32) with the tile staged
// in local memory, and the largest odd run per item that fits it: with an odd run, the blocked
// reads tile[item * items + i] fall in distinct banks. 48 KiB (NVIDIA) gives 256 x 9 = 2304 pairs.
RadixSort::Tiling RadixSort::choose_tiling(const DeviceInfo& device) {
  const std::uint32_t max_group = floor_pow2(std::max<std::size_t>(device.max_work_group, 1));
  // 256 x 32 = 8192 table entries per scan work-group keep the scan at one level up to 512 blocks
  // (1.2M pairs with the GPU tiling): a 1M-pair pass is then 3 launches, not 5, and on the H100
  // launches, not bandwidth, bound a sort of that size (1.6 instead of 1.0 Gpairs/s).
  std::uint32_t scan_group = std::min<std::uint32_t>(256, max_group);
  while (scan_group > 1 && !device.local_memory_is_global && scan_local_bytes(scan_group) > device.local_memory)
    scan_group /= 2;
  if (device.is_cpu) return {1, 4096, scan_group, false};
  const std::uint32_t group = std::min<std::uint32_t>(256, max_group);
  std::uint32_t items = 15;
  while (items > 1 && scatter_local_bytes(group, items, true) > device.local_memory) items -= 2;
  return {group, items, scan_group, true};
}

RadixSort::RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity)
    : RadixSort(cl, cache, capacity, Tiling{}) {}

RadixSort::RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity, Tiling tiling)
    : cl_(cl), capacity_(capacity) {
  const bool chosen = tiling.group == 0;
  if (chosen) tiling = choose_tiling(cl.info());
  if (tiling.group == 0 || tiling.items == 0 || tiling.scan_group == 0 ||
      std::uint64_t(tiling.group) * tiling.items > (1u << 24))
    throw std::invalid_argument(fmt::format("radix sort tiling {} x {} (scan {}) is invalid", tiling.group,
                                            tiling.items, tiling.scan_group));
  // A kernel may allow fewer work items than the device (registers, local memory): halve the
  // work-groups until every kernel accepts its size.
  for (;;) {
    const DeviceProgram build = cl.build_program(
        cache, "radix_sort",
        fmt::format("-DSORT_WG={} -DSORT_ITEMS={} -DSCAN_WG={} -DSORT_LOCAL_EXCHANGE={}", tiling.group, tiling.items,
                    tiling.scan_group, tiling.local_exchange ? 1 : 0));
    histogram_ = build.kernel("sort_histogram");
    scan_segments_ = build.kernel("sort_scan_segments");
    scan_add_ = build.kernel("sort_scan_add");
    scatter_ = build.kernel("sort_scatter");
    auto allowed = [](const DeviceKernel& k) { return k.max_group(); };
    const std::size_t sort_allowed = std::min(allowed(histogram_), allowed(scatter_));
    const std::size_t scan_allowed = std::min(allowed(scan_segments_), allowed(scan_add_));
    if (sort_allowed >= tiling.group && scan_allowed >= tiling.scan_group) break;
    if (!chosen || (sort_allowed == 0 || scan_allowed == 0))
      throw DeviceError(fmt::format("{} runs the radix sort kernels with at most {} and {} work items, not {} and {}",
                                    cl.info().name, sort_allowed, scan_allowed, tiling.group, tiling.scan_group));
    tiling.group = std::min(tiling.group, floor_pow2(sort_allowed));
    tiling.scan_group = std::min(tiling.scan_group, floor_pow2(scan_allowed));
  }
  tiling_ = tiling;

  const std::uint32_t tile = tiling.group * tiling.items;
  const std::uint32_t scan_tile = kScanItems * tiling.scan_group;
  scratch_keys_ = cl.allocate("radix sort scratch keys", std::size_t(capacity) * 8);
  scratch_values_ = cl.allocate("radix sort scratch values", std::size_t(capacity) * 4);
  std::uint32_t entries = kRadix * std::max<std::uint32_t>(div_up(capacity, tile), 1);
  for (;;) {
    scan_levels_.push_back(cl.allocate("radix sort scan level", std::size_t(entries) * 4));
    if (entries == 1) break;
    entries = div_up(entries, scan_tile);
  }
}

void RadixSort::launch(const DeviceKernel& kernel, const char* name, std::size_t items, std::size_t group,
                       Launches& launches) {
  launches.emplace_back(name, cl_.launch(kernel, items, group));
}

// Exclusive scan of the first n entries of scan_levels_[level], in place: scan each segment and
// collect segment totals one level up, scan those recursively, add them back (Blelloch's
// scan-then-propagate, as in Merrill & Grimshaw's reduce-then-scan).
void RadixSort::scan(std::size_t level, std::uint32_t n, Launches& launches) {
  const std::uint32_t scan_tile = kScanItems * tiling_.scan_group;
  const std::uint32_t segments = div_up(n, scan_tile);
  const DeviceBuffer& data = scan_levels_[level];
  const DeviceBuffer& sums = scan_levels_[level + 1];
  scan_segments_.set_args(data, n, sums);
  launch(scan_segments_, "sort scan", std::size_t(segments) * tiling_.scan_group, tiling_.scan_group, launches);
  if (segments == 1) return;
  scan(level + 1, segments, launches);
  scan_add_.set_args(data, n, sums);
  launch(scan_add_, "sort scan", n, tiling_.scan_group, launches);
}

void RadixSort::sort(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t count, unsigned key_bits,
                     std::map<std::string, double>* seconds) {
  if (count > capacity_)
    throw std::invalid_argument(fmt::format("radix sort of {} pairs exceeds its capacity of {}", count, capacity_));
  if (key_bits > kMaxKeyBits)
    throw std::invalid_argument(fmt::format("radix sort keys have at most 64 bits, not {}", key_bits));
  if (count < 2 || key_bits == 0) return;
  if (keys.size() < std::size_t(count) * 8 || values.size() < std::size_t(count) * 4)
    throw std::invalid_argument(fmt::format("radix sort buffers are smaller than {} pairs", count));

  const std::uint32_t blocks = div_up(count, tiling_.group * tiling_.items);
  const std::uint32_t passes = div_up(key_bits, kDigitBits);
  const DeviceBuffer& table = scan_levels_[0];
  Launches launches;
  for (std::uint32_t pass = 0; pass < passes; ++pass) {
    // even passes read the caller's buffers, odd passes the scratch buffers
    const bool from_caller = pass % 2 == 0;
    const DeviceBuffer& keys_in = from_caller ? keys : scratch_keys_;
    const DeviceBuffer& values_in = from_caller ? values : scratch_values_;
    const DeviceBuffer& keys_out = from_caller ? scratch_keys_ : keys;
    const DeviceBuffer& values_out = from_caller ? scratch_values_ : values;
    const std::uint32_t shift = pass * kDigitBits;
    // the last digit is narrower when key_bits is not a multiple of 4: bits above are ignored
    const std::uint32_t digit_mask = (1u << std::min(kDigitBits, key_bits - shift)) - 1;

    histogram_.set_args(keys_in, count, shift, digit_mask, blocks, table);
    launch(histogram_, "sort histogram", std::size_t(blocks) * tiling_.group, tiling_.group, launches);

    scan(0, kRadix * blocks, launches);

    scatter_.set_args(keys_in, values_in, keys_out, values_out, count, shift, digit_mask, blocks, table);
    launch(scatter_, "sort scatter", std::size_t(blocks) * tiling_.group, tiling_.group, launches);
  }
  if (passes % 2 == 1) {
    // An odd pass count leaves the result in scratch. Copying it back moves 24 bytes per pair,
    // less than a pass (32); a third buffer pair would avoid it but double the scratch memory. Its
    // time counts as scatter: it is the last step of placing the pairs.
    launches.emplace_back("sort scatter", cl_.copy(scratch_keys_, keys, std::size_t(count) * 8));
    launches.emplace_back("sort scatter", cl_.copy(scratch_values_, values, std::size_t(count) * 4));
  }
  // Without `seconds` the sort stays asynchronous: the queue is in order, so whatever the caller
  // enqueues next sees the sorted pairs. (The kernels' arguments live in this object: one sort at
  // a time per RadixSort.)
  if (seconds)
    for (auto& [name, event] : launches) (*seconds)[name] += event.seconds();
}

}  // namespace cohort

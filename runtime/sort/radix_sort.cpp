// Host side of the device radix sort (kernels/common/sort/radix_sort_kernels.h): tiling, buffers and the
// launches of one sort.
#include "runtime/sort/radix_sort.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "runtime/util/error.h"

namespace cohort {
namespace {

constexpr std::uint32_t kBins = 256;       // SORT_BINS in the kernel
constexpr std::uint32_t kMaxPasses = 8;    // SORT_MAX_PASSES
constexpr std::uint32_t kMaxCount = (1u << 30) - 1;  // LOOKBACK_COUNT: counts live in 30 bits
constexpr std::uint32_t kNoCountWord = 0xffffffffu;  // SORT_NO_COUNT_WORD

std::uint32_t div_up(std::uint64_t a, std::uint64_t b) { return static_cast<std::uint32_t>((a + b - 1) / b); }

std::uint32_t floor_pow2(std::size_t x) {
  std::uint32_t p = 1;
  while (p * 2 <= x && p < (1u << 30)) p *= 2;
  return p;
}

// Local memory of sort_pass as the kernel declares it (padding: one word per 32).
std::size_t pass_local_bytes(std::uint32_t group, std::uint32_t items, unsigned key_bytes) {
  auto padded = [](std::size_t words) { return words + words / 32; };
  const std::size_t tile = std::size_t(group) * items * (key_bytes + 4);
  return tile + padded(16 * std::size_t(group)) * 4 + (2 * kBins + padded(kBins)) * 4 + std::size_t(group) * 4 + 4;
}

}  // namespace

RadixSort::Passes RadixSort::passes_for(unsigned key_bits) {
  if (key_bits == 0) return {};
  std::uint32_t passes = div_up(key_bits, 8);
  passes += passes % 2;  // an odd count would leave the pairs in the scratch buffers
  return {passes, div_up(key_bits, passes)};
}

std::uint32_t RadixSort::commands(unsigned key_bits) {
  const Passes p = passes_for(key_bits);
  return p.count == 0 ? 0 : 2 + p.count;
}

// Tiling from the device.
// CPU (PoCL, Intel's runtime): one work item per work-group and 4096 pairs per tile. A CPU runtime
// runs the items of a group as SIMD lanes, so a wider group turns every run into gathers and
// scatters; one item is a plain sequential counting-sort pass over a chunk, and local memory is
// ordinary cached memory there, so tiles are not staged through it (measured with the earlier
// reduce-then-scan sort on the 2-core PoCL machine: 64 x 32 staged took ~5x the processor time of
// 1 x 4096 direct).
// GPU (any device with real local memory): 256 work items (8 warps of 32), the tile staged in local
// memory, and the largest odd run per item that fits (with an odd run, the blocked reads
// tile[item * items + i] fall in distinct banks): 48 KiB gives 256 x 13 for 32-bit keys and
// 256 x 9 for 64-bit keys.
RadixSort::Tiling RadixSort::choose_tiling(const DeviceInfo& device, SortKey key) {
  if (device.is_cpu || device.local_memory_is_global) return {1, 4096, false};
  const unsigned key_bytes = key == SortKey::bits64 ? 8 : 4;
  const std::uint32_t group = std::min<std::uint32_t>(256, floor_pow2(std::max<std::size_t>(device.max_work_group, 1)));
  std::uint32_t items = 15;
  while (items > 1 && pass_local_bytes(group, items, key_bytes) > device.local_memory) items -= 2;
  return {group, items, true};
}

RadixSort::RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity, SortKey key)
    : RadixSort(cl, cache, capacity, key, Tiling{}) {}

RadixSort::RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity, SortKey key, Tiling tiling)
    : cl_(cl), capacity_(capacity), key_(key) {
  if (capacity > kMaxCount)
    throw std::invalid_argument(fmt::format("radix sort capacity {} exceeds {} pairs", capacity, kMaxCount));
  const bool chosen = tiling.group == 0;
  if (chosen) tiling = choose_tiling(cl.info(), key);
  const bool group_ok = tiling.group == 1 || (tiling.group <= kBins && kBins % tiling.group == 0);
  if (!group_ok || tiling.items == 0 || (tiling.group > 1 && !tiling.local_exchange) ||
      std::uint64_t(tiling.group) * tiling.items > (1u << 24))
    throw std::invalid_argument(fmt::format("radix sort tiling {} x {} ({}) is invalid", tiling.group, tiling.items,
                                            tiling.local_exchange ? "local" : "direct"));
  // A kernel may allow fewer work items than the device (registers, local memory): halve the
  // work-groups until both kernels accept their size.
  for (;;) {
    const DeviceProgram build = cl.build_program(
        cache, "radix_sort",
        fmt::format("-DSORT_WG={} -DSORT_ITEMS={} -DSORT_LOCAL_EXCHANGE={} -DSORT_KEY64={}", tiling.group,
                    tiling.items, tiling.local_exchange ? 1 : 0, key == SortKey::bits64 ? 1 : 0));
    histogram_ = build.kernel("sort_histogram");
    pass_ = build.kernel("sort_pass");
    const std::size_t allowed = std::min(histogram_.max_group(), pass_.max_group());
    if (allowed >= tiling.group) break;
    if (!chosen || allowed == 0)
      throw DeviceError(fmt::format("{} runs the radix sort kernels with at most {} work items, not {}",
                                    cl.info().name, allowed, tiling.group));
    tiling.group = std::max<std::uint32_t>(1, floor_pow2(allowed));
    if (tiling.group == 1) tiling = {1, 4096, false};
  }
  tiling_ = tiling;

  const std::uint32_t tiles = std::max<std::uint32_t>(div_up(capacity, tiling.group * tiling.items), 1);
  scratch_keys_ = cl.allocate("radix sort scratch keys", std::size_t(capacity) * key_bytes());
  scratch_values_ = cl.allocate("radix sort scratch values", std::size_t(capacity) * 4);
  hist_ = cl.allocate("radix sort histogram", std::size_t(kMaxPasses) * kBins * 4);
  lookback_ = cl.allocate("radix sort look-back", std::size_t(kMaxPasses) * tiles * kBins * 4);
  tickets_ = cl.allocate("radix sort tickets", kMaxPasses * 4);
}

namespace {
void add_launch_seconds(const SortLaunches& launches, std::map<std::string, double>* seconds) {
  if (seconds)
    for (const auto& [name, event] : launches) (*seconds)[name] += event.seconds();
}
}  // namespace

void RadixSort::sort(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t count, unsigned key_bits,
                     std::map<std::string, double>* seconds) {
  add_launch_seconds(run(keys, values, count, hist_, kNoCountWord, key_bits), seconds);
}

void RadixSort::sort_device_count(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t max_count,
                                  const DeviceBuffer& count_word, std::uint32_t count_index, unsigned key_bits,
                                  std::map<std::string, double>* seconds) {
  add_launch_seconds(sort_device_count_async(keys, values, max_count, count_word, count_index, key_bits), seconds);
}

SortLaunches RadixSort::sort_device_count_async(const DeviceBuffer& keys, const DeviceBuffer& values,
                                                std::uint32_t max_count, const DeviceBuffer& count_word,
                                                std::uint32_t count_index, unsigned key_bits) {
  if (count_word.size() < (std::size_t(count_index) + 1) * 4)
    throw std::invalid_argument(fmt::format("radix sort count word {} is outside its buffer", count_index));
  return run(keys, values, max_count, count_word, count_index, key_bits);
}

SortLaunches RadixSort::run(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t count,
                            const DeviceBuffer& count_word, std::uint32_t count_index, unsigned key_bits) {
  if (count > capacity_)
    throw std::invalid_argument(fmt::format("radix sort of {} pairs exceeds its capacity of {}", count, capacity_));
  if (key_bits > 8 * key_bytes())
    throw std::invalid_argument(fmt::format("radix sort keys have at most {} bits, not {}", 8 * key_bytes(), key_bits));
  if (count < 2 || key_bits == 0) return {};
  if (keys.size() < std::size_t(count) * key_bytes() || values.size() < std::size_t(count) * 4)
    throw std::invalid_argument(fmt::format("radix sort buffers are smaller than {} pairs", count));

  const Passes passes = passes_for(key_bits);
  const std::uint32_t tile = tiling_.group * tiling_.items;
  const std::uint32_t tiles = div_up(count, tile);  // at most: the count on the device may be lower
  const std::uint32_t tile_stride = std::max<std::uint32_t>(div_up(capacity_, tile), 1);
  // The histogram reads the keys in chunks of several tiles: fewer groups, fewer global atomics.
  const std::uint32_t histogram_groups = div_up(tiles, 4);
  SortLaunches launches;

  cl_.fill(hist_, 0, std::size_t(passes.count) * kBins);
  histogram_.set_args(keys, count, count_word, count_index, histogram_groups, passes.count, passes.digit_bits,
                      std::uint32_t(key_bits), hist_, lookback_, tile_stride, tickets_);
  launches.emplace_back("sort histogram",
                        cl_.launch(histogram_, std::size_t(histogram_groups) * tiling_.group, tiling_.group));

  for (std::uint32_t pass = 0; pass < passes.count; ++pass) {
    // even passes read the caller's buffers, odd passes the scratch buffers; the count is even
    const bool from_caller = pass % 2 == 0;
    const DeviceBuffer& keys_in = from_caller ? keys : scratch_keys_;
    const DeviceBuffer& values_in = from_caller ? values : scratch_values_;
    const DeviceBuffer& keys_out = from_caller ? scratch_keys_ : keys;
    const DeviceBuffer& values_out = from_caller ? scratch_values_ : values;
    const std::uint32_t shift = pass * passes.digit_bits;
    const std::uint32_t bits = shift < key_bits ? std::min(passes.digit_bits, key_bits - shift) : 0;
    pass_.set_args(keys_in, values_in, keys_out, values_out, count, count_word, count_index, shift, (1u << bits) - 1,
                   pass, tile_stride, hist_, lookback_, tickets_);
    launches.emplace_back("sort scatter", cl_.launch(pass_, std::size_t(tiles) * tiling_.group, tiling_.group));
  }
  return launches;
}

}  // namespace cohort

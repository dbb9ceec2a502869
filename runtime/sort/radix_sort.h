// Stable device radix sort of (32- or 64-bit key, 32-bit value) pairs on any backend: one histogram
// launch and one launch per digit of up to 8 bits (kernels/common/sort/radix_sort_kernels.h).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"

namespace cohort {

enum class SortKey { bits32, bits64 };

// A sort's launches by name ("sort histogram", "sort scatter"), for the caller to time when it waits.
using SortLaunches = std::vector<std::pair<const char*, DeviceEvent>>;

class RadixSort {
 public:
  // Buffers for up to `capacity` pairs are allocated once and reused. Keys are 4 or 8 bytes each.
  RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity, SortKey key = SortKey::bits64);

  // Sorts the first `count` pairs of `keys` and `values` (32-bit) in place, stably, by the low
  // `key_bits` bits of the key (higher bits are ignored and ride along). Kernel time is added to
  // `seconds` under "sort histogram" and "sort scatter" when given; without it the sort stays
  // asynchronous (whatever the caller enqueues next sees the sorted pairs).
  void sort(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t count, unsigned key_bits,
            std::map<std::string, double>* seconds = nullptr);

  // The same for a count that lives on the device: at most `max_count` pairs, taken from the 32-bit
  // word `count_index` of `count_word` when the sort runs (a queue length), so the host need not
  // read it. Launches cover max_count; work-groups past the actual count leave at once.
  void sort_device_count(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t max_count,
                         const DeviceBuffer& count_word, std::uint32_t count_index, unsigned key_bits,
                         std::map<std::string, double>* seconds = nullptr);

  // Device commands (fills and kernel launches) a sort of `key_bits` bits issues: 1 + 1 + passes.
  static std::uint32_t commands(unsigned key_bits);
  // sort_device_count that hands its launches back instead of waiting for them (a wavefront pass
  // times them when it next reads the device).
  SortLaunches sort_device_count_async(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t max_count,
                                       const DeviceBuffer& count_word, std::uint32_t count_index, unsigned key_bits);

  std::uint32_t capacity() const { return capacity_; }
  SortKey key() const { return key_; }
  unsigned key_bytes() const { return key_ == SortKey::bits64 ? 8 : 4; }

  // Digit passes for `key_bits`: even, so the pairs end where they started without a copy back.
  struct Passes {
    std::uint32_t count = 0;       // digit passes
    std::uint32_t digit_bits = 0;  // bits per digit, at most 8
  };
  static Passes passes_for(unsigned key_bits);

 private:
  // Compile-time sizes of the sort kernels, chosen per device (see choose_tiling).
  struct Tiling {
    std::uint32_t group = 0;      // SORT_WG: work items per work-group
    std::uint32_t items = 0;      // SORT_ITEMS: pairs per work item; a tile is group * items pairs
    bool local_exchange = false;  // SORT_LOCAL_EXCHANGE: stage and rank tiles in local memory (GPUs)
  };
  friend struct RadixSortTestAccess;  // tests force other devices' tilings
  RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity, SortKey key, Tiling tiling);
  static Tiling choose_tiling(const DeviceInfo& device, SortKey key);
  SortLaunches run(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t count,
                   const DeviceBuffer& count_word, std::uint32_t count_index, unsigned key_bits);

  const Device& cl_;
  std::uint32_t capacity_;
  SortKey key_;
  Tiling tiling_;
  DeviceKernel histogram_, pass_;
  DeviceBuffer scratch_keys_, scratch_values_;  // the other half of every ping-pong
  DeviceBuffer hist_;                           // 256 digit counts per pass
  DeviceBuffer lookback_;                       // 256 words per tile and pass
  DeviceBuffer tickets_;                        // one tile counter per pass
};

}  // namespace cohort

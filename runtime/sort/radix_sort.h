// Stable device radix sort of (64-bit key, 32-bit value) pairs (kernels/common/radix_sort_kernels.h) on any
// backend.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/program_cache.h"

namespace cohort {

class RadixSort {
 public:
  // Buffers for up to `capacity` pairs are allocated once and reused.
  RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity);

  // Sorts the first `count` pairs of `keys` (64-bit) and `values` (32-bit) in place, stably, by the
  // low `key_bits` bits of the key (higher bits are ignored and must be zero for a full sort).
  // Kernel time per launch name ("sort histogram", "sort scan", "sort scatter") is added to
  // `seconds` when given.
  void sort(const DeviceBuffer& keys, const DeviceBuffer& values, std::uint32_t count, unsigned key_bits,
            std::map<std::string, double>* seconds = nullptr);

  std::uint32_t capacity() const { return capacity_; }

 private:
  // Compile-time sizes of the sort kernels, chosen per device (see choose_tiling).
  struct Tiling {
    std::uint32_t group = 0;       // SORT_WG: work items per histogram/scatter work-group
    std::uint32_t items = 0;       // SORT_ITEMS: pairs per work item; a block is group * items pairs
    std::uint32_t scan_group = 0;  // SCAN_WG: work items per scan work-group (32 entries each)
    bool local_exchange = false;   // SORT_LOCAL_EXCHANGE: stage tiles in local memory (GPUs)
  };
  friend struct RadixSortTestAccess;  // tests force small tilings to reach every scan level
  RadixSort(const Device& cl, const ProgramCache& cache, std::uint32_t capacity, Tiling tiling);
  static Tiling choose_tiling(const DeviceInfo& device);

  using Launches = std::vector<std::pair<const char*, DeviceEvent>>;
  void scan(std::size_t level, std::uint32_t n, Launches& launches);
  void launch(const DeviceKernel& kernel, const char* name, std::size_t items, std::size_t group, Launches& launches);

  const Device& cl_;
  std::uint32_t capacity_;
  Tiling tiling_;
  DeviceKernel histogram_, scan_segments_, scan_add_, scatter_;
  DeviceBuffer scratch_keys_, scratch_values_;  // the other half of every ping-pong
  // scan_levels_[0] is the digit-major histogram table; scan_levels_[i + 1] holds the segment sums
  // of scan_levels_[i]; the last level has one entry.
  std::vector<DeviceBuffer> scan_levels_;
};

}  // namespace cohort

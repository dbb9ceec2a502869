// Test access to RadixSort's private constructor: a forced tiling (work-group size x pairs per work
// item), so small work-groups reach every level of the multi-level scan and other devices' tilings
// run on this one.
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/sort/radix_sort.h"

namespace cohort {

struct RadixSortTestAccess {
  static std::unique_ptr<RadixSort> make(const ClContext& cl, const ProgramCache& cache, std::uint32_t capacity,
                                         std::uint32_t group, std::uint32_t items, std::uint32_t scan_group,
                                         bool local_exchange) {
    return std::unique_ptr<RadixSort>(
        new RadixSort(cl, cache, capacity, RadixSort::Tiling{group, items, scan_group, local_exchange}));
  }
};

}  // namespace cohort

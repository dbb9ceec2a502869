// Test access to RadixSort's private constructor: a forced tiling (work-group size x pairs per work
// item), so other devices' tilings (a GPU's local-memory ranking) and many small tiles (long
// look-back chains) run on this one.
#pragma once

#include <cstdint>
#include <memory>

#include "runtime/sort/radix_sort.h"

namespace cohort {

struct RadixSortTestAccess {
  static std::unique_ptr<RadixSort> make(const ClContext& cl, const ProgramCache& cache, std::uint32_t capacity,
                                         std::uint32_t group, std::uint32_t items, bool local_exchange,
                                         SortKey key = SortKey::bits64) {
    return std::unique_ptr<RadixSort>(
        new RadixSort(cl, cache, capacity, key, RadixSort::Tiling{group, items, local_exchange}));
  }
};

}  // namespace cohort

#include "runtime/cl/host_pages.h"

#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace cohort {

void* allocate_huge_pages(std::size_t bytes) {
  const std::size_t rounded = (bytes + kHugePageBytes - 1) / kHugePageBytes * kHugePageBytes;
  void* memory = std::aligned_alloc(kHugePageBytes, rounded);
#if defined(MADV_HUGEPAGE)
  if (memory) madvise(memory, rounded, MADV_HUGEPAGE);  // advice only: failure leaves 4 KiB pages
#endif
  return memory;
}

void free_huge_pages(void* memory) noexcept { std::free(memory); }

}  // namespace cohort

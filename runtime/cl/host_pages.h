// Host memory in 2 MiB pages for the buffers of CPU devices.
//
// On a CPU device the kernels read the scene straight from host memory, and a ray's walk through
// the tree touches a new 4 KiB page at nearly every node: the TLB misses (two-level page walks in
// a virtual machine) cost as much as the cache misses. Transparent huge pages cut that: the
// 4-wide BVH's diffuse rays on Crytek Sponza ran 1.17-1.22x faster from 2 MiB pages (2026-12-03,
// results/raw/nvidia-h200-2026-12-03-79b7d2b). Linux hands them out only to memory that asks
// (madvise), so a CPU device's large
// buffers live in memory allocated here and wrapped with CL_MEM_USE_HOST_PTR.
#pragma once

#include <cstddef>

namespace cohort {

// A CPU device's buffers of at least half a huge page come from 2 MiB pages.
inline constexpr std::size_t kHugePageBytes = std::size_t{2} << 20;

// `bytes` rounded up to whole 2 MiB pages, aligned to one and advised as huge pages (a hint the
// kernel may ignore: the memory works either way). Null when the allocation fails.
void* allocate_huge_pages(std::size_t bytes);
void free_huge_pages(void* memory) noexcept;

}  // namespace cohort

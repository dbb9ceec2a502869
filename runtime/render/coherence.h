// Host side of the coherence code: its layout (`--code`), the adaptive origin grid, and the size of
// the top subtree the PTH kernel keeps in local memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "kernels/common/types.h"
#include "runtime/backend/device_info.h"
#include "runtime/render/device_scene.h"

namespace cohort {

// "origin:8,pth:10,dir:8": parts most significant first, with their widths (origin: bits per axis,
// pth: levels, dir: bits per octahedral coordinate); "origin-uniform:N" uses a uniform origin grid
// over the scene bounds instead of centroid quantiles. Throws InputError for a malformed layout or
// more than 64 bits. `pth_levels` replaces the pth width when the layout has a pth part.
CodeParams parse_code_layout(const std::string& layout, std::uint32_t pth_levels, const Bounds& bounds);

// The default layouts: the paper's order (origin | PTH | direction) and the hash sort's.
std::string default_code_layout(bool with_pth);

// Per-axis quantiles of triangle centroids: 2^bits - 1 boundaries for each of x, y, z.
std::vector<float> origin_boundaries(const DeviceScene& scene, std::uint32_t bits_per_axis);

struct SubtreeChoice {
  std::uint32_t levels = 0;  // the walk records at most this many levels
  std::uint32_t nodes = 0;   // nodes shallower than `levels`: a prefix of the breadth-first array
  std::size_t local_bytes = 0;
};

// requested = 0: the paper's 10 levels, fewer when the tree is shallower or when the subtree would
// not leave room for 2 work-groups per compute unit in local memory (devices whose local memory is
// a scratchpad; PoCL's is ordinary memory, so there only the option limits it).
SubtreeChoice choose_subtree(const DeviceInfo& device, const DeviceScene& scene, std::uint32_t requested);

}  // namespace cohort

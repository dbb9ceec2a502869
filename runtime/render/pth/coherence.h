// Host side of the coherence code: its layout (`--code`), the adaptive origin grid, and the size of
// the top subtree the PTH kernel keeps in local memory.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "kernels/common/core/types.h"
#include "runtime/backend/device_info.h"
#include "runtime/render/scene/device_scene.h"

namespace cohort {

// "origin:8,pth:10,dir:8": parts most significant first, with their widths (origin: bits per axis,
// pth: levels, dir: bits per octahedral coordinate, end: bits per axis of the estimated end point
// on the uniform grid); "origin-uniform:N" uses a uniform origin grid over the scene bounds instead
// of centroid quantiles. A layout may also be a named preset (see
// code_presets). Throws InputError for a malformed layout or more than 64 bits. `pth_levels`
// replaces the pth width when the layout has a pth part (the subtree may be shallower than asked).
CodeParams parse_code_layout(const std::string& layout, std::uint32_t pth_levels, const Bounds& bounds);

// Named layouts: "paper" (Wang & Deng's order, origin | PTH | direction, 60 bits), "hash" (Garanzha
// & Loop's origin | direction, 40 bits), "origin-first" (the 32-bit key the gate benchmark found
// fastest), "two-point" (origin and estimated end point, Meister et al. 2020, 30 bits) and
// "pth-32" (origin-first with the top 4 PTH levels, 31 bits).
struct CodePreset {
  const char* name;
  const char* layout;
};
const std::vector<CodePreset>& code_presets();

// The levels a layout's pth part asks for (0 when it has none). Throws InputError like
// parse_code_layout for a malformed layout.
std::uint32_t layout_pth_levels(const std::string& layout);

// The subtree levels a sorting method walks: `code` (--code, empty for the default) and
// `pth_levels` (--pth-levels, 0 for the default) must agree when both name them; either alone
// decides; with neither, the default layout's pth width. 0: the device and the tree decide.
std::uint32_t requested_pth_levels(const std::string& code, std::uint32_t pth_levels);

// The default layouts, of at most 32 bits (32-bit keys sort in half the time): "pth-32" for pth
// and "origin-first" for hash, after the gate benchmark (results/raw/nvidia-h200-2026-12-02-053ff97).
std::string default_code_layout(bool with_pth);

// Per-axis quantiles of triangle centroids: 2^bits - 1 boundaries for each of x, y, z.
std::vector<float> origin_boundaries(const DeviceScene& scene, std::uint32_t bits_per_axis);

struct SubtreeChoice {
  std::uint32_t levels = 0;  // the walk records at most this many levels
  std::uint32_t nodes = 0;   // nodes shallower than `levels`: a prefix of the breadth-first array
  std::size_t local_bytes = 0;
};

// requested = 0: the paper's 10 levels, fewer when the tree is shallower or when the subtree would
// not fit the device's local budget (device_support: half a scratchpad, room for 2 work-groups per
// compute unit; all of a CPU runtime's cached local memory, 32 KiB on rusticl's llvmpipe). The
// levels are the tree's: the KD-tree's binary ones, or the 4-wide BVH's (its breadth-first top,
// BVH4_TOP_LEVELS at most, 128-byte nodes), where a request is also cut to the budget.
SubtreeChoice choose_subtree(const DeviceInfo& device, const DeviceScene& scene, std::uint32_t requested);

}  // namespace cohort

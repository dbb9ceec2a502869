// Splitting a node's references along the chosen plane (partition.cpp). Internal to
// runtime/accel/kdtree.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

#include "kernels/common/core/types.h"
#include "runtime/accel/kdtree/references.h"
#include "runtime/accel/kdtree/sah.h"
#include "runtime/scene/bounds.h"

namespace cohort::kd {

// How many of `refs` each child of `plane` gets before clipping (a straddling one on both sides),
// by the rules of the partitions below.
std::array<std::size_t, 2> side_counts(std::span<const Ref> refs, const SplitPlane& plane);

// Splits the references refs[begin, end) along `plane` (kdtree_partition.cpp): the left child's
// are written over the front of the range, the right child's pushed onto `refs` (the range lies
// below its top); straddling references are clipped to each child cell. Both keep the parent's
// order. Returns the counts per child; `clipped` counts the straddling references (0: every child
// reference is a parent reference unchanged). `straddling` is working memory.
struct Straddler {
  std::uint32_t left, right;  // a straddling reference's slots in each child's output
};
std::array<std::size_t, 2> partition(RefStack& refs, std::size_t begin, std::size_t end,
                                     const Bounds& voxel, const SplitPlane& plane,
                                     std::span<const Triangle> triangles,
                                     UninitialisedArray<Straddler>& straddling,
                                     std::size_t& clipped);

// The same split for a node whose children are built as parallel tasks: each child's references
// on a stack of their own, in the parent's order, the work split in chunks across threads.
std::array<RefStack, 2> partition_apart(std::span<const Ref> refs, const Bounds& voxel,
                                        const SplitPlane& plane,
                                        std::span<const Triangle> triangles);

std::array<Bounds, 2> child_cells(const Bounds& voxel, int axis, float pos);

}  // namespace cohort::kd

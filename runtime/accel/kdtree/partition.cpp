// Splitting a node's references along a plane. The rules mirror the counting of Wald & Havran's
// sweep exactly (their ClassifyLeftRightBoth), so the children hold the references the SAH counted:
// an extent ending in the plane is left-only, one starting in it right-only, one lying in it goes
// to the side the SAH chose. Straddling references are clipped to each child cell (perfect splits),
// and one whose triangle misses a child cell is left out of that child.
//
// Both partitions place every reference without a branch (which side a reference lies on is as good
// as random, and whether it straddles nearly so): each is written to both sides and kept by the
// count of the side it lies on, a straddling one by both. The straddling ones are clipped in a
// second pass over their slots, the triangle four ahead prefetched.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

#include "runtime/accel/clip.h"
#include "runtime/accel/kdtree/partition.h"

namespace cohort::kd {

std::array<Bounds, 2> child_cells(const Bounds& voxel, int axis, float pos) {
  std::array<Bounds, 2> cells{voxel, voxel};
  cells[0].hi[axis] = pos;
  cells[1].lo[axis] = pos;
  return cells;
}

namespace {

constexpr std::size_t kParallelChunk = 32768;  // references per task of a parallel split

// An extent reaching both sides of the plane: its triangle is clipped to each child cell.
bool straddles(float lo, float hi, const SplitPlane& plane) {
  return (lo != hi) & (lo < plane.pos) & (hi > plane.pos);
}

// Whether an extent that does not straddle the plane goes left: a flat one by the plane's planar
// side, any other by which side of the plane it starts on.
bool goes_left(float lo, float hi, const SplitPlane& plane) {
  return lo == hi ? (lo < plane.pos) | ((lo == plane.pos) & plane.planar_left) : lo < plane.pos;
}

// Drops the references whose clipped box came out empty (a triangle that only grazes the cell;
// no other reference has an empty box), keeping the order.
std::size_t drop_empty(Ref* refs, std::size_t count) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    refs[kept] = refs[i];
    kept += !refs[i].box.empty();
  }
  return kept;
}

// Splits refs[first, last) into `left` and `right`, in order; returns how many each got. `room`:
// how many each side may hold, at least its side_counts (a write to a side that is full goes to
// a spare slot instead, so no output is written past its room). `left` may be refs + first
// itself: it is never written ahead of the reference being read. Two passes: the first places
// every reference without a branch (which side is as good as random), a straddling one on both
// sides with its slots noted in `straddling`; the second clips those (a reference whose triangle
// misses a child cell is then dropped from it).
std::array<std::size_t, 2> split_refs(const Ref* refs, std::size_t first, std::size_t last,
                                      const Bounds& voxel, const SplitPlane& plane,
                                      std::span<const Triangle> triangles, Ref* left, Ref* right,
                                      std::array<std::size_t, 2> room, Straddler* straddling,
                                      std::size_t& clipped) {
  std::size_t n_left = 0, n_right = 0, n_straddling = 0;
  const int axis = plane.axis;
  Ref spare;
  for (std::size_t i = first; i < last; ++i) {
    const float lo = refs[i].box.lo[axis], hi = refs[i].box.hi[axis];
    const bool both = straddles(lo, hi, plane);
    const bool go_left = goes_left(lo, hi, plane);
    *(n_right < room[1] ? right + n_right : &spare) = refs[i];
    *(n_left < room[0] ? left + n_left : &spare) = refs[i];
    straddling[n_straddling] = {static_cast<std::uint32_t>(n_left),
                                static_cast<std::uint32_t>(n_right)};
    n_left += both | go_left;
    n_right += both | !go_left;
    n_straddling += both;
  }
  clipped += n_straddling;
  bool missed = false;
  for (std::size_t k = 0; k < n_straddling; ++k) {
    if (k + 4 < n_straddling) __builtin_prefetch(&triangles[left[straddling[k + 4].left].tri]);
    Ref& to_left = left[straddling[k].left];
    const Triangle& t = triangles[to_left.tri];
    const std::array<Bounds, 2> boxes = split_triangle_bounds(
        vertex(t.v0), vertex(t.v1), vertex(t.v2), voxel, to_left.box, plane.axis, plane.pos);
    to_left.box = boxes[0];
    right[straddling[k].right].box = boxes[1];
    missed |= boxes[0].empty() | boxes[1].empty();
  }
  if (missed) {
    n_left = drop_empty(left, n_left);
    n_right = drop_empty(right, n_right);
  }
  return {n_left, n_right};
}

}  // namespace

std::array<std::size_t, 2> side_counts(std::span<const Ref> refs, const SplitPlane& plane) {
  std::size_t n_left = 0, n_right = 0;
  const int axis = plane.axis;
  for (const Ref& r : refs) {
    const float lo = r.box.lo[axis], hi = r.box.hi[axis];
    const bool both = straddles(lo, hi, plane);
    const bool go_left = goes_left(lo, hi, plane);
    n_left += both | go_left;
    n_right += both | !go_left;
  }
  return {n_left, n_right};
}

std::array<std::size_t, 2> partition(RefStack& refs, std::size_t begin, std::size_t end,
                                     const Bounds& voxel, const SplitPlane& plane,
                                     std::span<const Triangle> triangles,
                                     UninitialisedArray<Straddler>& straddling,
                                     std::size_t& clipped) {
  clipped = 0;
  // Left references overwrite the range in place, right ones go straight onto the top of the
  // stack, past its end (room for all of them first: `refs` may reallocate only then).
  const std::size_t right_begin = refs.size();
  refs.push(end - begin);
  const std::array<std::size_t, 2> counts =
      split_refs(refs.data(), begin, end, voxel, plane, triangles, refs.data() + begin,
                 refs.data() + right_begin, {end - begin, end - begin},
                 straddling.room(end - begin), clipped);
  refs.pop_to(right_begin + counts[1]);
  return counts;
}

// Fixed-size chunks, each split straight into its place in the children: a first pass counts
// each chunk's references per side before clipping, so their places are known. The result is the
// serial one whatever the thread count. Where clipping dropped a reference (rare: a triangle that
// only grazes a child cell), the chunks are closed up afterwards.
std::array<RefStack, 2> partition_apart(std::span<const Ref> refs, const Bounds& voxel,
                                        const SplitPlane& plane,
                                        std::span<const Triangle> triangles) {
  const std::size_t chunks = (refs.size() + kParallelChunk - 1) / kParallelChunk;
  struct Part {
    std::array<std::size_t, 2> room{};  // references per side before clipping
    std::array<std::size_t, 2> at{};    // where the chunk's references go in each child
    std::array<std::size_t, 2> size{};  // kept after clipping
  };
  std::vector<Part> parts(chunks);
  auto chunk = [&](std::size_t k) {
    return std::array<std::size_t, 2>{k * kParallelChunk,
                                      std::min(refs.size(), (k + 1) * kParallelChunk)};
  };
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    const auto [first, last] = chunk(k);
    parts[k].room = side_counts(refs.subspan(first, last - first), plane);
  });
  std::array<RefStack, 2> children;
  std::array<Ref*, 2> child_refs{};
  for (int c = 0; c < 2; ++c) {
    std::size_t total = 0;
    for (Part& part : parts) {
      part.at[c] = total;
      total += part.room[c];
    }
    child_refs[c] = children[c].push(total);
  }
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    const auto [first, last] = chunk(k);
    Part& part = parts[k];
    UninitialisedArray<Straddler> straddling;
    std::size_t clipped = 0;
    part.size = split_refs(refs.data(), first, last, voxel, plane, triangles,
                           child_refs[0] + part.at[0], child_refs[1] + part.at[1], part.room,
                           straddling.room(last - first), clipped);
  });
  for (int c = 0; c < 2; ++c) {
    std::size_t kept = 0;
    for (const Part& part : parts) {
      if (kept != part.at[c]) std::copy_n(child_refs[c] + part.at[c], part.size[c], child_refs[c] + kept);
      kept += part.size[c];
    }
    children[c].pop_to(kept);
  }
  return children;
}

}  // namespace cohort::kd

// Splitting a node's references along a plane. The rules mirror the counting of Wald & Havran's
// sweep exactly (their ClassifyLeftRightBoth), so the children hold the references the SAH counted:
// an extent ending in the plane is left-only, one starting in it right-only, one lying in it goes
// to the side the SAH chose. Straddling references are clipped to each child cell (perfect splits),
// and one whose triangle misses a child cell is left out of that child.
//
// Both partitions are branch-free for the references on one side (most of them, and which side is
// as good as random): each is written to both sides and kept by the count of the side it lies on.
// Only the straddling ones branch.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

#include "runtime/accel/clip.h"
#include "runtime/accel/kdtree_internal.h"

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
  return lo != hi && lo < plane.pos && hi > plane.pos;
}

// Whether an extent that does not straddle the plane goes left: a flat one by the plane's planar
// side, any other by which side of the plane it starts on.
bool goes_left(float lo, float hi, const SplitPlane& plane) {
  return lo == hi ? lo < plane.pos || (lo == plane.pos && plane.planar_left) : lo < plane.pos;
}

// A straddling reference's triangle clipped to each child cell; a side it misses is empty.
std::array<Bounds, 2> clip_straddling(const Ref& r, const SplitPlane& plane, const Bounds& voxel,
                                      std::span<const Triangle> triangles) {
  const Triangle& t = triangles[r.tri];
  return split_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), voxel, plane.axis,
                               plane.pos);
}

// Splits refs[first, last) into `left` and `right` (each with room for last - first), in order;
// returns how many each got. `left` may be refs + first itself: it is never written ahead of the
// reference being read.
std::array<std::size_t, 2> split_refs(const Ref* refs, std::size_t first, std::size_t last,
                                      const Bounds& voxel, const SplitPlane& plane,
                                      std::span<const Triangle> triangles, Ref* left, Ref* right,
                                      std::size_t& clipped) {
  std::size_t n_left = 0, n_right = 0;
  const int axis = plane.axis;
  for (std::size_t i = first; i < last; ++i) {
    const Ref r = refs[i];
    const float lo = r.box.lo[axis], hi = r.box.hi[axis];
    if (straddles(lo, hi, plane)) {
      ++clipped;
      const std::array<Bounds, 2> boxes = clip_straddling(r, plane, voxel, triangles);
      if (!boxes[0].empty()) left[n_left++] = {boxes[0], r.tri};
      if (!boxes[1].empty()) right[n_right++] = {boxes[1], r.tri};
      continue;
    }
    const bool go_left = goes_left(lo, hi, plane);
    left[n_left] = r;
    right[n_right] = r;
    n_left += go_left;
    n_right += !go_left;
  }
  return {n_left, n_right};
}

}  // namespace

std::array<std::size_t, 2> partition(RefStack& refs, std::size_t begin, std::size_t end,
                                     const Bounds& voxel, const SplitPlane& plane,
                                     std::span<const Triangle> triangles, std::size_t& clipped) {
  clipped = 0;
  // Left references overwrite the range in place, right ones go straight onto the top of the
  // stack, past its end (room for all of them first: `refs` may reallocate only then).
  const std::size_t right_begin = refs.size();
  refs.push(end - begin);
  const std::array<std::size_t, 2> counts =
      split_refs(refs.data(), begin, end, voxel, plane, triangles, refs.data() + begin,
                 refs.data() + right_begin, clipped);
  refs.pop_to(right_begin + counts[1]);
  return counts;
}

// Fixed-size chunks split on their own, then copied in chunk order (each chunk to its place, in
// parallel), so the result is the serial one whatever the thread count.
std::array<RefStack, 2> partition_apart(std::span<const Ref> refs, const Bounds& voxel,
                                        const SplitPlane& plane,
                                        std::span<const Triangle> triangles) {
  const std::size_t chunks = (refs.size() + kParallelChunk - 1) / kParallelChunk;
  struct Part {
    std::array<RefBuffer, 2> room;  // each with room for the whole chunk
    std::array<std::size_t, 2> size{};
    std::array<std::size_t, 2> at{};  // where the chunk's references go in each child
  };
  std::vector<Part> parts(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    const std::size_t first = k * kParallelChunk;
    const std::size_t last = std::min(refs.size(), first + kParallelChunk);
    Part& part = parts[k];
    std::size_t clipped = 0;
    part.size = split_refs(refs.data(), first, last, voxel, plane, triangles,
                           part.room[0].room(last - first), part.room[1].room(last - first),
                           clipped);
  });
  std::array<RefStack, 2> children;
  std::array<Ref*, 2> child_refs{};
  for (int c = 0; c < 2; ++c) {
    std::size_t total = 0;
    for (Part& part : parts) {
      part.at[c] = total;
      total += part.size[c];
    }
    child_refs[c] = children[c].push(total);
  }
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    const Part& part = parts[k];
    for (int c = 0; c < 2; ++c) {
      std::copy_n(part.room[c].data(), part.size[c], child_refs[c] + part.at[c]);
    }
  });
  return children;
}

}  // namespace cohort::kd

// Splitting a node's references along a plane. The rules mirror the counting of Wald & Havran's
// sweep exactly (their ClassifyLeftRightBoth), so the children hold the references the SAH counted:
// an extent ending in the plane is left-only, one starting in it right-only, one lying in it goes
// to the side the SAH chose. Straddling references are clipped to each child cell (perfect splits),
// and one whose triangle misses a child cell is left out of that child.
//
// Both partitions place every reference without a branch (which side a reference lies on is as good
// as random, and whether it straddles nearly so): each is written to both sides and kept by the
// count of the side it lies on, a straddling one by both. The straddling ones are clipped in a
// second pass over their slots, with the next one's triangle prefetched.
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
  return (lo != hi) & (lo < plane.pos) & (hi > plane.pos);
}

// Whether an extent that does not straddle the plane goes left: a flat one by the plane's planar
// side, any other by which side of the plane it starts on.
bool goes_left(float lo, float hi, const SplitPlane& plane) {
  return lo == hi ? (lo < plane.pos) | ((lo == plane.pos) & plane.planar_left) : lo < plane.pos;
}

// Drops the references whose clipped box came out empty (a triangle that only grazes the cell),
// keeping the order.
std::size_t drop_empty(Ref* refs, std::size_t count) {
  std::size_t kept = 0;
  for (std::size_t i = 0; i < count; ++i) {
    refs[kept] = refs[i];
    kept += !refs[i].box.empty();
  }
  return kept;
}

// Splits refs[first, last) into `left` and `right` (each with room for last - first), in order;
// returns how many each got. `left` may be refs + first itself: it is never written ahead of the
// reference being read. Two passes: the first places every reference without a branch (which
// side is as good as random), a straddling one on both sides with its slots noted in
// `straddling`; the second clips those (a reference whose triangle misses a child cell is then
// dropped from it).
std::array<std::size_t, 2> split_refs(const Ref* refs, std::size_t first, std::size_t last,
                                      const Bounds& voxel, const SplitPlane& plane,
                                      std::span<const Triangle> triangles, Ref* left, Ref* right,
                                      Straddler* straddling, std::size_t& clipped) {
  std::size_t n_left = 0, n_right = 0, n_straddling = 0;
  const int axis = plane.axis;
  for (std::size_t i = first; i < last; ++i) {
    const float lo = refs[i].box.lo[axis], hi = refs[i].box.hi[axis];
    const bool both = straddles(lo, hi, plane);
    const bool go_left = goes_left(lo, hi, plane);
    right[n_right] = refs[i];
    left[n_left] = refs[i];
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
        vertex(t.v0), vertex(t.v1), vertex(t.v2), voxel, plane.axis, plane.pos);
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
                 refs.data() + right_begin, straddling.room(end - begin), clipped);
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
    UninitialisedArray<Straddler> straddling;
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
                           part.straddling.room(last - first), clipped);
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

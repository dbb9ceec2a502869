// Splitting a node's references along a plane. The rules mirror the counting of Wald & Havran's
// sweep exactly (their ClassifyLeftRightBoth), so the children hold the references the SAH counted:
// an extent ending in the plane is left-only, one starting in it right-only, one lying in it goes
// to the side the SAH chose. Straddling references are clipped to each child cell (perfect splits),
// and one whose triangle misses a child cell is left out of that child.
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

// Where one reference goes, with its clipped extent in each child it reaches.
struct Placement {
  bool left = false, right = false;
  bool clipped = false;
  Bounds left_box, right_box;
};

Placement place(const Ref& r, const SplitPlane& plane, const Bounds& voxel,
                std::span<const Triangle> triangles) {
  const int axis = plane.axis;
  const float p = plane.pos;
  const float lo = r.box.lo[axis], hi = r.box.hi[axis];
  Placement out;
  if (lo == hi) {
    out.left = lo < p || (lo == p && plane.planar_left);
    out.right = !out.left;
  } else {
    out.left = lo < p;
    out.right = hi > p;
  }
  if (out.left && out.right) {
    out.clipped = true;
    const Triangle& t = triangles[r.tri];
    const auto [left_box, right_box] =
        split_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), voxel, axis, p);
    out.left_box = left_box;
    out.right_box = right_box;
    out.left = !out.left_box.empty();
    out.right = !out.right_box.empty();
  } else {
    out.left_box = out.right_box = r.box;
  }
  return out;
}

}  // namespace

std::array<std::size_t, 2> partition(std::vector<Ref>& refs, std::size_t begin, std::size_t end,
                                     const Bounds& voxel, const SplitPlane& plane,
                                     std::span<const Triangle> triangles, std::size_t& clipped) {
  clipped = 0;
  const std::size_t right_begin = refs.size();
  // Left references overwrite the range in place (never ahead of the one being read), right ones
  // are appended; `refs` may reallocate, so everything goes through indices.
  std::size_t write = begin;
  const int axis = plane.axis;
  for (std::size_t read = begin; read < end; ++read) {
    const Ref r = refs[read];
    // place()'s rules, inline for the references on one side (most of them): moved unchanged.
    const float lo = r.box.lo[axis], hi = r.box.hi[axis];
    if (lo != hi && !(lo < plane.pos && hi > plane.pos)) {
      if (lo < plane.pos) {
        refs[write++] = r;
      } else {
        refs.push_back(r);
      }
      continue;
    }
    const Placement where = place(r, plane, voxel, triangles);
    clipped += where.clipped;
    if (where.left) refs[write++] = {where.left_box, r.tri};
    if (where.right) refs.push_back({where.right_box, r.tri});
  }
  return {write - begin, refs.size() - right_begin};
}

}  // namespace cohort::kd

namespace cohort::kd {

// Fixed-size chunks split on their own, then concatenated in chunk order, so the result is the
// serial one whatever the thread count; each child's references are copied once, into its own
// vector.
std::array<std::vector<Ref>, 2> partition_apart(std::span<const Ref> refs, const Bounds& voxel,
                                                const SplitPlane& plane,
                                                std::span<const Triangle> triangles) {
  const std::size_t chunks = (refs.size() + kParallelChunk - 1) / kParallelChunk;
  std::vector<std::array<std::vector<Ref>, 2>> parts(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    const std::size_t first = k * kParallelChunk;
    const std::size_t last = std::min(refs.size(), first + kParallelChunk);
    // Room for the whole chunk on each side: no reallocation while it grows.
    parts[k][0].reserve(last - first);
    parts[k][1].reserve(last - first);
    for (std::size_t i = first; i < last; ++i) {
      const Placement where = place(refs[i], plane, voxel, triangles);
      if (where.left) parts[k][0].push_back({where.left_box, refs[i].tri});
      if (where.right) parts[k][1].push_back({where.right_box, refs[i].tri});
    }
  });
  std::array<std::vector<Ref>, 2> children;
  for (int c = 0; c < 2; ++c) {
    std::size_t total = 0;
    for (const auto& part : parts) total += part[c].size();
    children[c].reserve(total);
    for (auto& part : parts) {
      children[c].insert(children[c].end(), part[c].begin(), part[c].end());
      std::vector<Ref>().swap(part[c]);
    }
  }
  return children;
}

}  // namespace cohort::kd

// Splitting a node's references along a plane. The rules mirror the counting of Wald & Havran's
// sweep exactly (their ClassifyLeftRightBoth), so the children hold the references the SAH counted:
// an extent ending in the plane is left-only, one starting in it right-only, one lying in it goes
// to the side the SAH chose. Straddling references are clipped to each child cell (perfect splits),
// and one whose triangle misses a child cell is left out of that child.
#include <utility>

#include "runtime/accel/clip.h"
#include "runtime/accel/kdtree_internal.h"

namespace cohort::kd {

void push_events(EventLists& lists, const Bounds& box, std::uint32_t local) {
  for (int axis = 0; axis < 3; ++axis) {
    if (box.lo[axis] == box.hi[axis]) {
      lists[axis].push_back(Event::make(box.lo[axis], kPlanar, local));
    } else {
      lists[axis].push_back(Event::make(box.lo[axis], kStart, local));
      lists[axis].push_back(Event::make(box.hi[axis], kEnd, local));
    }
  }
}

std::array<Bounds, 2> child_cells(const Bounds& voxel, int axis, float pos) {
  std::array<Bounds, 2> cells{voxel, voxel};
  cells[0].hi[axis] = pos;
  cells[1].lo[axis] = pos;
  return cells;
}

std::array<std::size_t, 2> partition(std::vector<Ref>& refs, std::size_t begin, std::size_t end,
                                     const Bounds& voxel, const SplitPlane& plane,
                                     std::span<const Triangle> triangles) {
  const int axis = plane.axis;
  const float p = plane.pos;
  const std::array<Bounds, 2> cells = child_cells(voxel, axis, p);
  const std::size_t right_begin = refs.size();
  // Left references overwrite the range in place (never ahead of the one being read), right ones
  // are appended; `refs` may reallocate, so everything goes through indices.
  std::size_t write = begin;
  for (std::size_t read = begin; read < end; ++read) {
    const Ref r = refs[read];
    const float lo = r.box.lo[axis], hi = r.box.hi[axis];
    bool left = false, right = false;
    if (lo == hi) {
      left = lo < p || (lo == p && plane.planar_left);
      right = !left;
    } else {
      left = lo < p;
      right = hi > p;
    }
    if (left && right) {
      const Triangle& t = triangles[r.tri];
      const Bounds l = clip_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), cells[0]);
      const Bounds h = clip_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), cells[1]);
      if (!l.empty()) refs[write++] = {l, r.tri};
      if (!h.empty()) refs.push_back({h, r.tri});
    } else if (left) {
      refs[write++] = r;
    } else {
      refs.push_back(r);
    }
  }
  return {write - begin, refs.size() - right_begin};
}

}  // namespace cohort::kd

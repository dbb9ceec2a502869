// Splitting a node in linear time (Wald & Havran 2006, the O(N log N) build): classify each
// triangle as left-only, right-only or both from the events of the split axis; the event lists of
// one-sided triangles are split by a stable filter, so they stay sorted for free; only the
// straddling triangles ("both") are clipped to each child cell and get new events, which are sorted
// (they are few: O(sqrt N) for reasonable scenes, Wald & Havran's argument) and merged in.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstddef>
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

namespace {

enum Side : std::uint8_t { kBoth = 0, kLeftOnly = 1, kRightOnly = 2 };
constexpr std::uint32_t kAbsent = ~0u;
constexpr std::size_t kParallelClip = 1024;  // straddlers worth a parallel loop

// Wald & Havran's ClassifyLeftRightBoth: the rules mirror the counting of the sweep exactly, so
// the children hold the triangles the SAH counted (a triangle ending in the plane is left-only, one
// starting in it right-only, one lying in it goes to the side the SAH chose).
std::vector<Side> classify(const std::vector<Event>& events, const SplitPlane& plane,
                           std::size_t count) {
  std::vector<Side> side(count, kBoth);
  const float p = plane.pos;
  for (const Event& e : events) {
    switch (e.type()) {
      case kEnd:
        if (e.pos <= p) side[e.local()] = kLeftOnly;
        break;
      case kStart:
        if (e.pos >= p) side[e.local()] = kRightOnly;
        break;
      case kPlanar:
        if (e.pos < p || (e.pos == p && plane.planar_left))
          side[e.local()] = kLeftOnly;
        else
          side[e.local()] = kRightOnly;
        break;
    }
  }
  return side;
}

std::array<Bounds, 2> child_cells(const Bounds& voxel, const SplitPlane& plane) {
  std::array<Bounds, 2> cells{voxel, voxel};
  cells[0].hi[plane.axis] = plane.pos;
  cells[1].lo[plane.axis] = plane.pos;
  return cells;
}

// A straddling triangle and its extent inside each child cell (empty when it misses that cell).
struct Straddler {
  std::uint32_t local;
  std::array<Bounds, 2> part;
};

std::vector<Straddler> clip_straddlers(const NodeWork& work, const std::vector<Side>& side,
                                       const std::array<Bounds, 2>& cells,
                                       std::span<const Triangle> triangles, bool parallel) {
  std::vector<Straddler> straddlers;
  for (std::uint32_t local = 0; local < side.size(); ++local) {
    if (side[local] == kBoth) straddlers.push_back({local, {}});
  }
  auto clip = [&](std::size_t i) {
    const Triangle& t = triangles[work.tris[straddlers[i].local]];
    for (int c = 0; c < 2; ++c) {
      straddlers[i].part[c] =
          clip_triangle_bounds(vertex(t.v0), vertex(t.v1), vertex(t.v2), cells[c]);
    }
  };
  if (parallel && straddlers.size() >= kParallelClip) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, straddlers.size()),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) clip(i);
                      });
  } else {
    for (std::size_t i = 0; i < straddlers.size(); ++i) clip(i);
  }
  return straddlers;
}

// Child-local index of every parent-local triangle (kAbsent when it is not in that child). Assigned
// in parent order, so child triangle lists stay ascending and the remapped events stay sorted.
struct Membership {
  std::array<std::vector<std::uint32_t>, 2> index;
};

Membership assign_children(const std::vector<Side>& side, const std::vector<Straddler>& straddlers,
                           const NodeWork& parent, std::array<NodeWork, 2>& children) {
  const std::size_t count = side.size();
  std::array<std::vector<bool>, 2> inside{std::vector<bool>(count), std::vector<bool>(count)};
  for (std::size_t i = 0; i < count; ++i) {
    inside[0][i] = side[i] == kLeftOnly;
    inside[1][i] = side[i] == kRightOnly;
  }
  for (const Straddler& s : straddlers) {
    for (int c = 0; c < 2; ++c) inside[c][s.local] = !s.part[c].empty();
  }
  Membership m;
  for (int c = 0; c < 2; ++c) {
    m.index[c].assign(count, kAbsent);
    for (std::size_t i = 0; i < count; ++i) {
      if (!inside[c][i]) continue;
      m.index[c][i] = static_cast<std::uint32_t>(children[c].tris.size());
      children[c].tris.push_back(parent.tris[i]);
    }
  }
  return m;
}

// The events of the triangles that stay entirely on one side, renamed to child-local indices.
// A stable filter of a sorted list is sorted (the renaming is monotone).
std::vector<Event> filter_events(const std::vector<Event>& events, const std::vector<Side>& side,
                                 Side keep, const std::vector<std::uint32_t>& index) {
  std::size_t kept = 0;
  for (const Event& e : events) kept += side[e.local()] == keep;
  std::vector<Event> out;
  out.reserve(kept);
  for (const Event& e : events) {
    if (side[e.local()] != keep) continue;
    out.push_back({e.pos, (e.code & ~kLocalMask) | index[e.local()]});
  }
  return out;
}

// New events of the clipped straddlers in child c, sorted per axis.
EventLists straddler_events(const std::vector<Straddler>& straddlers, int c,
                            const std::vector<std::uint32_t>& index) {
  EventLists lists;
  for (const Straddler& s : straddlers) {
    if (!s.part[c].empty()) push_events(lists, s.part[c], index[s.local]);
  }
  for (auto& list : lists) std::sort(list.begin(), list.end());
  return lists;
}

std::vector<Event> merge_events(std::vector<Event>&& a, std::vector<Event>&& b) {
  if (b.empty()) return std::move(a);
  std::vector<Event> out(a.size() + b.size());
  std::merge(a.begin(), a.end(), b.begin(), b.end(), out.begin());
  return out;
}

}  // namespace

std::array<NodeWork, 2> partition(NodeWork work, const SplitPlane& plane,
                                  std::span<const Triangle> triangles, bool parallel) {
  const std::vector<Side> side = classify(work.events[plane.axis], plane, work.tris.size());
  const std::array<Bounds, 2> cells = child_cells(work.voxel, plane);
  const std::vector<Straddler> straddlers = clip_straddlers(work, side, cells, triangles, parallel);

  std::array<NodeWork, 2> children;
  children[0].voxel = cells[0];
  children[1].voxel = cells[1];
  const Membership member = assign_children(side, straddlers, work, children);
  std::array<EventLists, 2> fresh{straddler_events(straddlers, 0, member.index[0]),
                                  straddler_events(straddlers, 1, member.index[1])};

  auto split_axis = [&](int axis) {
    std::vector<Event>& parent = work.events[axis];
    std::vector<Event> left = filter_events(parent, side, kLeftOnly, member.index[0]);
    std::vector<Event> right = filter_events(parent, side, kRightOnly, member.index[1]);
    std::vector<Event>().swap(parent);  // free the parent's list before the merges allocate
    children[0].events[axis] = merge_events(std::move(left), std::move(fresh[0][axis]));
    children[1].events[axis] = merge_events(std::move(right), std::move(fresh[1][axis]));
  };
  if (parallel) {
    tbb::parallel_for(0, 3, split_axis);
  } else {
    for (int axis = 0; axis < 3; ++axis) split_axis(axis);
  }
  return children;
}

}  // namespace cohort::kd

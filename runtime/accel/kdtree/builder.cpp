// The recursive SAH build over triangle references. Large nodes pick their plane from binned
// counts (linear time); nodes of at most KdBuildOptions::exact_triangles references evaluate every
// candidate (Wald & Havran 2006's exact SAH), counted directly up to 128 references, else swept over
// sorted extents. References live in one growing array per task, used as a stack: a node's left
// child overwrites it in place and its right child is appended, so the recursion allocates nothing
// per node. Subtrees of large nodes are TBB tasks, built into their own pointer-free Subtree kept
// in a fixed slot of their parent's, so the tree is the same bits whatever the thread count and
// timing.
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "runtime/accel/kdtree/partition.h"
#include "runtime/accel/kdtree/sah.h"
#include "runtime/accel/kdtree/subtree.h"

namespace cohort::kd {
namespace {

// Below this a node's subtree is built serially: a task would cost more than it saves.
constexpr std::size_t kParallelTriangles = 4096;

// Up to this many references the exact search counts its candidates directly (count_candidates)
// instead of sorting and merging the extents: the same plane, in 0.8x the build time (Crytek
// Sponza's compact tree on one thread: 1.32 s against 1.68 s at 64). 128, where exact_triangles
// now ends, builds Sponza x4 and the bunny x16 as fast as 192 does.
constexpr std::size_t kCountedTriangles = 128;

// Wald & Havran's "bad refines" guard: a split after which both children still hold every triangle
// makes no progress; after this many in a row the node becomes a leaf. With the strict
// "split only when C_best <= K_I N" rule such a split cannot win (P_L + P_R > 1), so this is a
// second line of defence for the degenerate inputs (copies of one triangle, coplanar sheets) in
// case the cost rule is ever relaxed.
constexpr int kMaxBadRefines = 3;

// One task's working memory: the reference stack and the event lists of the exact sweep, reused
// from node to node.
struct Scratch {
  RefStack refs;
  PlaneScratch plane;
  UninitialisedArray<Straddler> straddling;  // the partition's
  // plane.candidates are already the merged candidates of the next node's references: its parent
  // swept them and handed all of them on unchanged (an empty-space cut with nothing clipped, the most
  // common split in a KD-tree), so the child skips gathering and sorting them again.
  bool extents_inherited = false;
};

class Builder {
 public:
  Builder(std::span<const Triangle> triangles, const KdBuildOptions& options, int max_depth)
      : triangles_(triangles), options_(options), max_depth_(max_depth) {}

  // Builds the subtree of the references s.refs[begin, end) (with cell `voxel`) into `out`;
  // returns the index of its root there. Leaves s.refs at its size on entry, or empty and freed
  // when the node was split in parallel.
  std::uint32_t build(Subtree& out, Scratch& s, std::size_t begin, std::size_t end,
                      const Bounds& voxel, int depth, int bad_refines) const;

 private:
  bool exact(std::size_t count) const {
    return count <= static_cast<std::size_t>(std::max(options_.exact_triangles, 0));
  }
  SplitPlane find_plane(Scratch& s, std::size_t begin, std::size_t end, const SahContext& c,
                        bool parallel, bool inherited) const;
  void build_children_parallel(Subtree& out, std::uint32_t index, Scratch& s,
                               std::array<RefStack, 2> children,
                               const std::array<Bounds, 2>& cells, int depth,
                               int bad_refines) const;
  // The split of build() that puts every reference on one side (all_left or not); hand_on: the
  // search was exact, so its candidates are the child's too.
  std::uint32_t build_one_sided(Subtree& out, Scratch& s, std::size_t begin, std::size_t end,
                                bool all_left, bool hand_on, const std::array<Bounds, 2>& cells,
                                const SplitPlane& plane, const Bounds& voxel, int depth,
                                int bad_refines) const;
  static std::uint32_t make_leaf(Subtree& out, const Scratch& s, std::size_t begin,
                                 std::size_t end, const Bounds& voxel, int depth);
  static std::uint32_t add_inner(Subtree& out, const SplitPlane& plane, const Bounds& voxel,
                                 int depth);

  std::span<const Triangle> triangles_;
  const KdBuildOptions& options_;
  int max_depth_;
};

// The intermediate tree's indices (BuildNode) hold fewer bits than a size_t; layout.cpp
// checks the device layout's limits, this only keeps the indices from wrapping before it gets
// there.
std::uint32_t checked_index(std::size_t value, std::size_t limit, const char* what) {
  if (value > limit) {
    throw std::length_error(
        fmt::format("KD-tree has {} {} in one subtree; at most {} fit", value, what, limit));
  }
  return static_cast<std::uint32_t>(value);
}

std::uint32_t Builder::make_leaf(Subtree& out, const Scratch& s, std::size_t begin,
                                 std::size_t end, const Bounds& voxel, int depth) {
  const std::uint32_t index = checked_index(out.nodes.size(), BuildNode::kMaxIndex, "nodes");
  checked_index(out.leaf_triangles.size() + (end - begin), std::numeric_limits<std::uint32_t>::max(),
                "leaf references");
  out.nodes.push_back(BuildNode::leaf(
      checked_index(end - begin, BuildNode::kMaxCount, "references in a leaf"),
      static_cast<std::uint32_t>(out.leaf_triangles.size())));
  for (std::size_t i = begin; i < end; ++i) out.leaf_triangles.push_back(s.refs[i].tri);
  SubtreeSums& sums = out.sums;
  ++sums.leaves;
  sums.empty_leaves += begin == end;
  sums.references += end - begin;
  if (end > begin) sums.leaf_reference_area += cell_area(voxel) * static_cast<double>(end - begin);
  sums.depth = std::max(sums.depth, depth);
  sums.add_node(depth, end - begin);
  return index;
}

std::uint32_t Builder::add_inner(Subtree& out, const SplitPlane& plane, const Bounds& voxel,
                                 int depth) {
  const std::uint32_t index = checked_index(out.nodes.size(), BuildNode::kMaxIndex, "nodes");
  out.nodes.push_back(BuildNode::inner(plane.axis, plane.pos));
  ++out.sums.inner;
  out.sums.inner_area += cell_area(voxel);
  out.sums.add_node(depth, 0);
  return index;
}

SplitPlane Builder::find_plane(Scratch& s, std::size_t begin, std::size_t end,
                               const SahContext& c, bool parallel, bool inherited) const {
  const std::size_t count = end - begin;
  const std::span<const Ref> refs = s.refs.span(begin, count);
  if (!exact(count)) {
    // A bin per four references is enough: the exact sweep inside the best bins and at the ends
    // of the geometry finds the planes that matter (on the bunny: 3% fewer instructions than a
    // bin per reference, SAH 75.03 against 75.09). At most 65536: bin indices are kept as 16 bits.
    const int bins = static_cast<int>(std::clamp<std::size_t>(
        count / 4, 8, static_cast<std::size_t>(std::clamp(options_.bins, 8, 65536))));
    return find_binned_plane(c, refs, bins, parallel, s.plane);
  }
  // An inherited node evaluates its parent's candidates again (in its own cell).
  if (!inherited && count <= kCountedTriangles) {
    count_candidates(refs, s.plane.candidates);
  } else if (!inherited) {
    NodeExtents& extents = s.plane.extents;
    for (AxisExtents& x : extents) x.clear();
    for (const Ref& r : refs) {
      for (int axis = 0; axis < 3; ++axis) extents[axis].add(r.box.lo[axis], r.box.hi[axis]);
    }
    for (int axis = 0; axis < 3; ++axis) extents[axis].sort(c.lo[axis], c.hi[axis]);
    sweep_candidates(extents, c.count, s.plane.candidates);
  }
  return find_best_plane(c, s.plane.candidates, s.plane.costs);
}

std::uint32_t Builder::build(Subtree& out, Scratch& s, std::size_t begin, std::size_t end,
                             const Bounds& voxel, int depth, int bad_refines) const {
  const bool inherited = std::exchange(s.extents_inherited, false);
  const std::size_t count = end - begin;
  const auto leaf_size = static_cast<std::size_t>(std::max(options_.leaf_triangles, 0));
  SahContext context;
  if (count <= leaf_size || depth >= max_depth_ ||
      !make_sah_context(voxel, count, options_, context)) {
    return make_leaf(out, s, begin, end, voxel, depth);
  }
  // The compact criterion judges a small node by its chosen plane, which for most nodes of 2-6
  // references makes them leaves; a bound that costs a tenth of the search finds most of those.
  const bool small = count <= static_cast<std::size_t>(std::max(options_.plain_sah_triangles, 0));
  if (options_.compact && small &&
      split_cannot_pay(context, s.refs.span(begin, count))) {
    return make_leaf(out, s, begin, end, voxel, depth);
  }
  const bool parallel = options_.parallel && count >= kParallelTriangles;
  const SplitPlane plane = find_plane(s, begin, end, context, parallel, inherited);
  // Wald & Havran's termination criterion, split only when the plane beats the leaf (K_I N), with
  // the plain SAH (see KdBuildOptions::plain_sah_triangles): for small nodes the chosen plane's,
  // for the others the best of any candidate's.
  const float split_cost = !options_.compact ? plane.cost : small ? plane.plain_cost : plane.lowest_plain_cost;
  if (!plane.valid() || !(split_cost <= options_.intersection_cost * static_cast<float>(count))) {
    return make_leaf(out, s, begin, end, voxel, depth);
  }
  const bool no_progress = plane.left_count == count && plane.right_count == count;
  bad_refines = no_progress ? bad_refines + 1 : 0;
  if (bad_refines >= kMaxBadRefines) return make_leaf(out, s, begin, end, voxel, depth);

  // A plane with nothing on one side (an empty-space cut, most of the nodes of the deep tree, and
  // a third of the binned nodes' references in the compact one): every reference goes to the other
  // side unchanged (none straddles, so none is clipped), so that child takes this node's
  // references in place instead of a partition copying them, and after an exact search its
  // sorted extents too. An exact search's counts are the partition's; a binned search's are
  // checked against the partition's rules first (side_counts).
  const std::array<Bounds, 2> cells = child_cells(voxel, plane.axis, plane.pos);
  if (plane.left_count == 0 || plane.right_count == 0) {
    const bool exact_counts = exact(count);
    const std::array<std::size_t, 2> sides =
        exact_counts ? std::array<std::size_t, 2>{plane.left_count, plane.right_count}
                     : side_counts(s.refs.span(begin, count), plane);
    if (sides[0] == 0 || sides[1] == 0) {
      const bool all_left = sides[1] == 0;
      if (!parallel) {
        return build_one_sided(out, s, begin, end, all_left, exact_counts, cells, plane, voxel,
                               depth, bad_refines);
      }
      // A node this large has the stack to itself (build_children_parallel).
      assert(begin == 0 && end == s.refs.size());
      std::array<RefStack, 2> children;
      children[all_left ? 0 : 1] = std::move(s.refs);
      const std::uint32_t index = add_inner(out, plane, voxel, depth);
      build_children_parallel(out, index, s, std::move(children), cells, depth, bad_refines);
      return index;
    }
  }
  if (parallel) {
    std::array<RefStack, 2> children =
        partition_apart(s.refs.span(begin, count), voxel, plane, triangles_);
    const std::uint32_t index = add_inner(out, plane, voxel, depth);
    build_children_parallel(out, index, s, std::move(children), cells, depth, bad_refines);
    return index;
  }
  const std::size_t right_begin = s.refs.size();
  std::size_t clipped = 0;
  const std::array<std::size_t, 2> counts =
      partition(s.refs, begin, end, voxel, plane, triangles_, s.straddling, clipped);
  // The extents of this node are those of a child that got every reference unchanged.
  const bool hand_on = exact(count) && clipped == 0 && (counts[0] == 0 || counts[1] == 0);
  const std::uint32_t index = add_inner(out, plane, voxel, depth);
  s.extents_inherited = hand_on && counts[0] > 0;
  build(out, s, begin, begin + counts[0], cells[0], depth + 1, bad_refines);  // at index + 1
  s.extents_inherited = hand_on && counts[1] > 0;
  const std::uint32_t right = build(out, s, right_begin, right_begin + counts[1], cells[1],
                                    depth + 1, bad_refines);
  s.refs.pop_to(right_begin);
  out.nodes[index].set_right(right);  // re-indexed: the recursion grew the vector
  return index;
}

// The split of build() that puts every reference on one side: the same nodes, in the same order,
// as partitioning them would give.
std::uint32_t Builder::build_one_sided(Subtree& out, Scratch& s, std::size_t begin,
                                       std::size_t end, bool all_left, bool hand_on,
                                       const std::array<Bounds, 2>& cells,
                                       const SplitPlane& plane, const Bounds& voxel, int depth,
                                       int bad_refines) const {
  const std::uint32_t index = add_inner(out, plane, voxel, depth);
  s.extents_inherited = hand_on && all_left;
  if (all_left) {  // the left child at index + 1
    build(out, s, begin, end, cells[0], depth + 1, bad_refines);
  } else {
    make_leaf(out, s, begin, begin, cells[0], depth + 1);
  }
  s.extents_inherited = hand_on && !all_left;
  const std::uint32_t right = all_left
                                  ? make_leaf(out, s, begin, begin, cells[1], depth + 1)
                                  : build(out, s, begin, end, cells[1], depth + 1, bad_refines);
  s.extents_inherited = false;
  out.nodes[index].set_right(right);
  return index;
}

// Each child gets its references (partition_apart) as a stack of its own and is built as a task
// into its own Subtree, kept in the parent's `spawned` (never copied: layout.cpp walks them
// in place); the parent's stack is freed first (a node large enough for this has the stack to
// itself: it is the root or a child of another parallel split).
void Builder::build_children_parallel(Subtree& out, std::uint32_t index, Scratch& s,
                                      std::array<RefStack, 2> children,
                                      const std::array<Bounds, 2>& cells, int depth,
                                      int bad_refines) const {
  s.refs = RefStack();
  std::array<Scratch, 2> child;
  std::array<std::size_t, 2> counts{};
  for (int c = 0; c < 2; ++c) {
    counts[c] = children[c].size();
    child[c].refs = std::move(children[c]);
  }
  const auto first_spawned =
      checked_index(out.spawned.size() + 1, BuildNode::kMaxIndex, "spawned subtrees") - 1;
  out.spawned.resize(out.spawned.size() + 2);
  Subtree* trees = out.spawned.data() + first_spawned;
  auto build_child = [&](int c) {
    build(trees[c], child[c], 0, counts[c], cells[c], depth + 1, bad_refines);
    child[c] = {};
  };
  tbb::parallel_invoke([&] { build_child(0); }, [&] { build_child(1); });
  out.nodes[index].set_spawned(first_spawned);
}

// The root: every kept triangle with its own bounds, in input order.
RefStack root_refs(std::span<const Triangle> triangles, bool parallel) {
  RefStack stack;
  Ref* const refs = stack.push(triangles.size());
  auto fill = [&](std::size_t first, std::size_t last) {
    for (std::size_t i = first; i < last; ++i) {
      Bounds box;
      box.extend(vertex(triangles[i].v0));
      box.extend(vertex(triangles[i].v1));
      box.extend(vertex(triangles[i].v2));
      refs[i] = {box, static_cast<std::uint32_t>(i)};
    }
  };
  if (parallel) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, triangles.size(), kParallelTriangles),
                      [&](const tbb::blocked_range<std::size_t>& r) { fill(r.begin(), r.end()); });
  } else {
    fill(0, triangles.size());
  }
  return stack;
}

}  // namespace

int effective_max_depth(const KdBuildOptions& options, std::size_t triangle_count) {
  int depth = options.max_depth;
  if (depth <= 0) {
    const double n = static_cast<double>(std::max<std::size_t>(triangle_count, 1));
    depth = static_cast<int>(std::lround(8.0 + 1.8 * std::log2(n)));
  }
  return std::clamp(depth, 0, kDepthCap);
}

Subtree build_subtree(std::span<const Triangle> triangles, const Bounds& bounds,
                      const KdBuildOptions& options) {
  Subtree out;
  const int max_depth = effective_max_depth(options, triangles.size());
  const Builder builder(triangles, options, max_depth);
  Scratch scratch;
  scratch.refs = root_refs(triangles, options.parallel);
  builder.build(out, scratch, 0, triangles.size(), bounds, 0, 0);
  return out;
}

}  // namespace cohort::kd

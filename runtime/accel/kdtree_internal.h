// Internals of the KD-tree build shared by kdtree_builder.cpp, kdtree_sah.cpp,
// kdtree_binned_sah.cpp, kdtree_partition.cpp, kdtree_layout.cpp and kdtree_stats.cpp. Not part of
// the public contract.
//
// The build works on triangle references (a triangle and its extent clipped to the node's cell).
// Large nodes pick their plane from binned counts in linear time; nodes of at most
// KdBuildOptions::exact_triangles references evaluate every candidate exactly as Wald & Havran do
// with their events ("On building fast kd-trees for ray tracing, and on doing that in O(N log N)",
// IEEE RT 2006): small ones by counting each candidate's references directly, larger ones by
// sweeping their sorted extents.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include "kernels/common/accel/kdtree_traverse.h"
#include "runtime/accel/kdtree.h"
#include "runtime/scene/bounds.h"

namespace cohort::kd {

// ---- Sorted extents ----------------------------------------------------------------------------
// One axis of a node's references for the exact sweep: where each extent of non-zero width starts
// and ends, and where each flat one (a triangle lying in a plane across the axis) lies. Sorted, these
// are Wald & Havran's event lists without the events: their sweep needs only how many extents
// start, end or lie at each position, so three float arrays sort faster than tagged events and give
// the same planes.
struct AxisExtents {
  std::vector<float> starts, ends, flats;

  void clear() {
    starts.clear();
    ends.clear();
    flats.clear();
  }
  // -0 is taken as +0, so equal positions compare equal and the plane is never -0.
  void add(float lo, float hi) {
    if (lo == hi) {
      flats.push_back(lo + 0.f);
    } else {
      starts.push_back(lo + 0.f);
      ends.push_back(hi + 0.f);
    }
  }
  // Sorts the three lists, every position of which lies in the cell's [lo, hi] along the axis.
  void sort(float lo, float hi);
};

using NodeExtents = std::array<AxisExtents, 3>;

// A triangle reference: a kept triangle and its extent clipped to the cell of the node that holds
// it (Havran's perfect splits). A node's references keep ascending triangle order, so leaf lists
// are ascending and the tree does not depend on which thread moved the references.
struct Ref {
  Bounds box;
  std::uint32_t tri;
};

// Uninitialised room for n values, for buffers whose every entry is written before it is read:
// the references the branch-free partitions write (each written to both sides and kept by the
// count of the side it lies on), the binned search's per-reference bins and gathered extents.
// (T is an implicit-lifetime type, so its allocator's storage holds Ts once they are written; a
// vector would first initialise every element, on one thread.) Grows, by at least doubling,
// without keeping its contents.
template <class T>
class UninitialisedArray {
 public:
  UninitialisedArray() = default;
  UninitialisedArray(UninitialisedArray&& other) noexcept { swap(other); }
  UninitialisedArray& operator=(UninitialisedArray&& other) noexcept {
    UninitialisedArray(std::move(other)).swap(*this);
    return *this;
  }
  ~UninitialisedArray() { release(); }

  // Room for at least n values.
  T* room(std::size_t n) {
    if (n > capacity_) {
      const std::size_t capacity = std::max(n, 2 * capacity_);
      release();
      data_ = allocator_.allocate(capacity);
      capacity_ = capacity;
    }
    return data_;
  }
  T* data() { return data_; }
  const T* data() const { return data_; }
  std::size_t capacity() const { return capacity_; }

 private:
  void swap(UninitialisedArray& other) noexcept {
    std::swap(data_, other.data_);
    std::swap(capacity_, other.capacity_);
  }
  void release() {
    if (data_ != nullptr) allocator_.deallocate(data_, capacity_);
    data_ = nullptr;
    capacity_ = 0;
  }
  std::allocator<T> allocator_;
  T* data_ = nullptr;
  std::size_t capacity_ = 0;
};

using RefBuffer = UninitialisedArray<Ref>;

// A task's references as a stack (kdtree_builder.cpp): a node's range, with its children's
// pushed on top. Grown uninitialised (RefBuffer), so the parallel splits fill it from several
// threads, page faults included, where a vector would first initialise it on one thread.
class RefStack {
 public:
  RefStack() = default;
  RefStack(RefStack&& other) noexcept
      : storage_(std::move(other.storage_)), size_(std::exchange(other.size_, 0)) {}
  RefStack& operator=(RefStack&& other) noexcept {
    storage_ = std::move(other.storage_);
    size_ = std::exchange(other.size_, 0);
    return *this;
  }

  std::size_t size() const { return size_; }
  Ref* data() { return storage_.data(); }
  const Ref* data() const { return storage_.data(); }
  const Ref& operator[](std::size_t i) const { return storage_.data()[i]; }
  std::span<const Ref> span(std::size_t first, std::size_t count) const {
    return {storage_.data() + first, count};
  }
  // Makes the stack n references longer and returns the first of them, not yet written.
  Ref* push(std::size_t n) {
    if (size_ + n > storage_.capacity()) {
      RefBuffer grown;
      std::copy_n(storage_.data(), size_, grown.room(std::max(size_ + n, 2 * storage_.capacity())));
      storage_ = std::move(grown);
    }
    size_ += n;
    return storage_.data() + size_ - n;
  }
  void pop_to(std::size_t size) { size_ = std::min(size, size_); }

 private:
  RefBuffer storage_;
  std::size_t size_ = 0;
};

// ---- SAH ---------------------------------------------------------------------------------------
struct SplitPlane {
  int axis = -1;  // -1: no candidate
  float pos = 0.f;
  bool planar_left = true;  // where triangles lying in the plane go
  float cost = 0.f;        // SAH with the empty-space bonus: what chooses the plane
  float plain_cost = 0.f;  // the same without the bonus
  // The lowest plain cost of every candidate the search evaluated (not only of the chosen one):
  // whether splitting pays at all (see KdBuildOptions::plain_sah_triangles).
  float lowest_plain_cost = std::numeric_limits<float>::infinity();
  std::uint32_t left_count = 0;  // references on each side, as the search counted them
  std::uint32_t right_count = 0;
  bool valid() const { return axis >= 0; }
};

// What every candidate plane of one node shares.
struct SahContext {
  glm::vec3 lo, hi, extent;
  float inv_area;  // 1 / surface area of the cell
  float traversal_cost;
  float intersection_cost;
  float empty_factor;   // 1 - empty_bonus
  std::uint32_t count;  // references in the node
};

// False for a cell without area (nothing to split), with an infinite one, or with one too small
// for 1 / area to be finite.
bool make_sah_context(const Bounds& voxel, std::size_t count, const KdBuildOptions& options,
                      SahContext& out);

// Wald & Havran's C_V(p) with their lambda(p): cutting off empty space is rewarded, but only when
// the empty side has volume, otherwise every flat cut at the cell boundary would look like a win.
// `plain` gets the cost without the bonus.
inline float plane_cost(const SahContext& c, float p_left, float p_right, std::uint32_t n_left,
                        std::uint32_t n_right, float width_left, float width_right, float& plain) {
  plain = c.traversal_cost + c.intersection_cost * (p_left * static_cast<float>(n_left) +
                                                    p_right * static_cast<float>(n_right));
  const bool empty_cut = (n_left == 0 && width_left > 0.f) || (n_right == 0 && width_right > 0.f);
  return empty_cut ? plain * c.empty_factor : plain;
}

// Keeps the cheaper of `best` and `other` (ties keep `best`) and the lowest plain cost of both.
inline void keep_better(SplitPlane& best, const SplitPlane& other) {
  const float lowest = std::min(best.lowest_plain_cost, other.lowest_plain_cost);
  if (other.valid() && (!best.valid() || other.cost < best.cost)) best = other;
  best.lowest_plain_cost = lowest;
}

// The parts of a candidate's cost that depend only on its axis.
struct AxisSah {
  int axis;
  float lo, hi;  // the cell along the axis
  float face;    // area of the cell's face across the axis
  float rim;     // the two other extents, summed
};

inline AxisSah axis_sah(const SahContext& c, int axis) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  return {axis, c.lo[axis], c.hi[axis], c.extent[u] * c.extent[v], c.extent[u] + c.extent[v]};
}

// Evaluates plane `pos` both with the planar triangles on the left and on the right (Wald & Havran's
// SAH(p, V, N_L, N_R, N_P)), keeping the cheaper; ties keep the earlier candidate, so the order of
// the candidates alone decides and the result is deterministic. Inline: the searches call it once
// per candidate.
inline void evaluate_plane(const SahContext& c, const AxisSah& a, float pos, std::uint32_t n_left,
                           std::uint32_t n_right, std::uint32_t n_planar, SplitPlane& best) {
  const float width_left = pos - a.lo, width_right = a.hi - pos;
  const float p_left = 2.f * (a.face + width_left * a.rim) * c.inv_area;
  const float p_right = 2.f * (a.face + width_right * a.rim) * c.inv_area;
  auto consider = [&](std::uint32_t l, std::uint32_t r, bool planar_left) {
    float plain;
    const float cost = plane_cost(c, p_left, p_right, l, r, width_left, width_right, plain);
    const float lowest = std::min(best.lowest_plain_cost, plain);
    if (!best.valid() || cost < best.cost) best = {a.axis, pos, planar_left, cost, plain, lowest, l, r};
    best.lowest_plain_cost = lowest;
  };
  consider(n_left + n_planar, n_right, true);
  if (n_planar > 0) consider(n_left, n_right + n_planar, false);
}

// Candidates are counted and evaluated a vector of this many at a time, with no scalar tail.
constexpr std::size_t kCandidateLanes = 8;

// n rounded up to whole vectors of kCandidateLanes.
constexpr std::size_t whole_lanes(std::size_t n) {
  return (n + kCandidateLanes - 1) / kCandidateLanes * kCandidateLanes;
}

// One axis's candidate planes in ascending order with the counts Wald & Havran's sweep gives each:
// references entirely left of the plane, reaching right of it, and lying in it. They depend on the
// references only, not on the cell, so a child that gets every reference unchanged (an empty-space
// cut) evaluates its parent's candidates again in its own cell without sorting or merging.
// Each candidate is evaluated twice, with the planar references on the left (a) and on the right
// (b); the counts are floats, as the SAH uses them (exact below 2^24), so the evaluation is a
// plain loop the compiler vectorises.
struct AxisCandidates {
  std::vector<float> pos;
  std::vector<float> left_a, right_a, left_b, right_b;
  std::size_t size = 0;
  bool planar = false;  // some candidate has planar references (else b equals a)
  std::vector<float> flats;  // count_candidates' working memory: where flat references lie

  void clear() {
    size = 0;
    planar = false;
  }
  // Room for `more` candidates after the first `size`, rounded up to whole vectors of
  // kCandidateLanes: the counting and the evaluation read and write whole vectors (the lanes past
  // the candidates hold finite stale values and are ignored).
  void reserve_more(std::size_t more) {
    const std::size_t needed = whole_lanes(size + more);
    if (pos.size() < needed) {
      for (std::vector<float>* v : {&pos, &left_a, &right_a, &left_b, &right_b}) {
        v->resize(std::max(needed, 2 * v->size()));
      }
    }
  }
};

using NodeCandidates = std::array<AxisCandidates, 3>;

// Wald & Havran's incremental sweep over one axis's sorted extents, starting from n_left references
// entirely before the first position and n_right reaching past it: at each position the extents
// ending there leave the right side, the flat ones sit in the plane, and those starting there join
// the left side. Appends the candidates to `out` (kdtree_sah.cpp).
void merge_candidates(std::span<const float> starts, std::span<const float> ends,
                      std::span<const float> flats, std::uint32_t n_left, std::uint32_t n_right,
                      AxisCandidates& out);

// The candidates of a small node counted directly instead of swept: each boundary of a
// reference's extent with the references starting before it, ending after it and lying in it,
// from comparisons with every reference (n^2 of them, branch-free and vectorised), in no order and
// with repeats. Below a few dozen references this costs less than sorting and merging, and it
// gives the counts the sweep gives, so evaluate_candidates chooses the same plane (kdtree_sah.cpp).
void count_candidates(std::span<const Ref> refs, NodeCandidates& out);

// evaluate_plane over the candidates of `axis` in ascending order of position: the same plane
// (first of the cheapest) and lowest plain cost whatever the candidates' order and repeats,
// computed a vector of candidates at a time (kdtree_sah.cpp).
void evaluate_candidates(const SahContext& c, int axis, const AxisCandidates& candidates,
                         std::vector<float>& costs, SplitPlane& best);

// Working memory of the plane searches, reused from node to node by one task.
struct PlaneScratch {
  std::vector<std::uint32_t> starts, ends;  // binned counts, [axis * bins + bin]
  std::vector<std::uint8_t> refined;        // 1 for the bins the exact sweep covers, same index
  // Per reference: start and end bin of each axis (a cleared array cost the root's count a serial
  // pass over 13 MB of fresh pages for Sponza x4).
  UninitialisedArray<std::uint16_t> ref_bins;
  // The refinement's gathering of every extent end, 9 per reference, before it keeps those in the
  // refined bins (a cleared vector cost 2.4% of the build in memset).
  UninitialisedArray<float> gathered;
  NodeExtents extents;
  NodeCandidates candidates;
  std::vector<float> costs;  // evaluate_candidates' working memory
  // Tests: the refined bins' candidates always sorted and swept, never counted (the two must agree).
  bool sweep_refined = false;
};

// Wald & Havran's sweep (their FindPlane) over a node of `count` references' sorted extents:
// every boundary of a reference's extent is a candidate, with its counts (kdtree_sah.cpp).
void sweep_candidates(const NodeExtents& extents, std::uint32_t count, NodeCandidates& out);

// The best plane of a node's candidates, swept or counted (kdtree_sah.cpp). They are kept for a
// child that inherits them.
SplitPlane find_best_plane(const SahContext& context, const NodeCandidates& candidates,
                           std::vector<float>& costs);

// The best of `bins - 1` evenly spaced planes per axis, counted from binned reference extents in
// time linear in the node, and of the exact candidates inside the two bins around each axis's best
// boundary (kdtree_binned_sah.cpp). For large nodes, where sorting every extent would dominate the
// build.
SplitPlane find_binned_plane(const SahContext& context, std::span<const Ref> refs, int bins,
                             bool parallel, PlaneScratch& scratch);

// What the plain SAH cost (K_T + K_I (P_L N_L + P_R N_R)) of a node's planes can be, without
// searching them (kdtree_sah.cpp):
// - `any`: a lower bound for every plane through the cell. A reference going left lies in
//   [lo, plane], so P_L is at least that of the cell cut at its end, and likewise on the right.
// - `empty_cut`: the least plain cost of the candidates that cut off empty space (the planes where
//   the references start or end; infinite when they reach every face of the cell).
// Computed in float: every term is a sum or product of non-negative values, so these are within
// a few ulps of the exact bounds, as the search's costs are of the exact costs.
struct PlainCostBounds {
  double any = std::numeric_limits<double>::infinity();
  double empty_cut = std::numeric_limits<double>::infinity();
};
PlainCostBounds plain_cost_bounds(const SahContext& context, std::span<const Ref> refs);

// Whether the compact criterion for small nodes (split only when the chosen plane's plain cost is
// at most K_I N) makes a node of these references a leaf whatever plane the search finds, from
// plain_cost_bounds (kdtree_sah.cpp).
bool split_cannot_pay(const SahContext& context, std::span<const Ref> refs);

// ---- Partition ---------------------------------------------------------------------------------
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

// ---- Intermediate tree -------------------------------------------------------------------------
// Pointer-free, so a subtree built on another thread is a plain value that its parent keeps in a
// fixed slot: the result is the same bits whatever the thread timing.
// A node in 8 bytes, as the device's KdNode: the build writes, and lay_out reads, half what 16
// bytes took (a 32-byte node made the build of Sponza x4 1.06x slower). The build is depth-first,
// so an inner node's left child is the next node of its Subtree; `word` names the right child,
// or, with kSpawnedFlag, the first of the two consecutive Subtree::spawned slots that hold its
// children (each built by another task).
struct BuildNode {
  std::uint32_t word = KD_LEAF;  // bits 0-1: axis 0..2 or KD_LEAF; then a leaf's count, or
                                 // kSpawnedFlag (bit 2) and the index above it
  std::uint32_t payload = 0;     // inner: the split position's bits; leaf: its first entry in
                                 // Subtree::leaf_triangles

  static BuildNode leaf(std::uint32_t count, std::uint32_t first) {
    return {count << 2 | KD_LEAF, first};
  }
  static BuildNode inner(int axis, float split) {
    return {static_cast<std::uint32_t>(axis), std::bit_cast<std::uint32_t>(split)};
  }
  bool is_leaf() const { return (word & 3u) == KD_LEAF; }
  std::uint32_t axis() const { return word & 3u; }
  float split() const { return std::bit_cast<float>(payload); }
  std::uint32_t count() const { return word >> 2; }
  std::uint32_t first() const { return payload; }
  bool spawned() const { return (word & kSpawnedFlag) != 0; }
  std::uint32_t index() const { return word >> 3; }  // the right child, or the first slot
  void set_right(std::uint32_t right) { word = axis() | right << 3; }
  void set_spawned(std::uint32_t first_slot) { word = axis() | kSpawnedFlag | first_slot << 3; }

  static constexpr std::uint32_t kSpawnedFlag = 4u;
  static constexpr std::uint32_t kMaxIndex = (1u << 29) - 1u;  // nodes or slots in one Subtree
  static constexpr std::uint32_t kMaxCount = (1u << 30) - 1u;  // references in one leaf
};
static_assert(sizeof(BuildNode) == 8);

// In lay_out's walk, a pending child with this bit set is the root of
// Subtree::spawned[child & ~kSpawnedBit], else a node of the same Subtree.
constexpr std::uint32_t kSpawnedBit = 1u << 31;

// A cell's surface area in double precision, as the SAH statistics sum it.
inline double cell_area(const Bounds& box) {
  const glm::dvec3 e = glm::dvec3(box.hi) - glm::dvec3(box.lo);
  return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
}

// What the statistics need of the nodes, summed as the builder makes them (each node's cell is at
// hand there), so no pass over the finished tree is needed. Sums of cell areas, not yet divided by
// the root's: the SAH cost is (K_T inner_area + K_I leaf_reference_area) / area(root).
// Depths a node can have (root = 0); the builder stops below KD_MAX_DEPTH (kDepthCap).
constexpr std::size_t kLevels = KD_MAX_DEPTH;

struct SubtreeSums {
  double inner_area = 0;           // the cells of the inner nodes
  double leaf_reference_area = 0;  // each leaf's cell times its triangle count
  std::size_t inner = 0, leaves = 0, empty_leaves = 0, references = 0;
  int depth = 0;  // deepest leaf (root = depth 0)
  // Nodes and leaf-list entries per depth: where each level of the breadth-first layout starts,
  // and how far a subtree built by another task moves the nodes right of it (kdtree_layout.cpp).
  std::array<std::size_t, kLevels> level_nodes{}, level_leaf_entries{};

  void add_node(int at_depth, std::size_t leaf_entries) {
    ++level_nodes[static_cast<std::size_t>(at_depth)];
    level_leaf_entries[static_cast<std::size_t>(at_depth)] += leaf_entries;
  }
  void add(const SubtreeSums& other) {
    inner_area += other.inner_area;
    leaf_reference_area += other.leaf_reference_area;
    inner += other.inner;
    leaves += other.leaves;
    empty_leaves += other.empty_leaves;
    references += other.references;
    depth = std::max(depth, other.depth);
    for (std::size_t d = 0; d < kLevels; ++d) {
      level_nodes[d] += other.level_nodes[d];
      level_leaf_entries[d] += other.level_leaf_entries[d];
    }
  }
};

struct Subtree {
  std::vector<BuildNode> nodes;  // nodes[0] is the root
  std::vector<std::uint32_t> leaf_triangles;
  std::vector<Subtree> spawned;  // subtrees built in parallel, kept in place instead of copied
  SubtreeSums sums;              // of `nodes` only, not of `spawned`
};

// The subtree's sums and those of everything it spawned, in their fixed order (kdtree_stats.cpp).
SubtreeSums total_sums(const Subtree& subtree);

// The recursive SAH build over the kept triangles (kdtree_builder.cpp).
Subtree build_subtree(std::span<const Triangle> triangles, const Bounds& bounds,
                      const KdBuildOptions& options);

// Deepest leaf the builder makes (root = depth 0). The traversal pushes at most one stack entry per
// inner node on the path, so depth KD_MAX_DEPTH would just fit its 48-entry stack; the margin keeps
// room for traversal variants that push one more entry (a restart point, the PTH subtree root).
constexpr int kDepthCap = KD_MAX_DEPTH - 4;
static_assert(kDepthCap < static_cast<int>(kLevels));

// The depth limit actually used: options.max_depth, or 8 + 1.8 log2(N), capped (see kDepthCap). The
// factor was 1.3 until GPU runs showed the limit binding: on the H100, 1.8 gave 1.8x the diffuse
// rays/s of the armadillo and the Sponza interior (results/raw/pocl-2026-11-23-f393cc7); 2.0 to 3.0 gained nothing more.
int effective_max_depth(const KdBuildOptions& options, std::size_t triangle_count);

// Breadth-first device layout of the subtree and those it spawned (kdtree_layout.cpp), written by
// a depth-first walk. Throws std::length_error when an index does not fit the 30 bits of
// KdNode::word0.
void flatten(const Subtree& subtree, KdTree& tree);

// Fills tree.stats from the sums of the subtree and those it spawned (joined in their fixed
// order: the same figures for any thread count), except dropped_triangles and build_seconds.
void compute_stats(const Subtree& subtree, KdTree& tree, const KdBuildOptions& options);

inline glm::vec3 vertex(const co_float4& v) { return {v.x, v.y, v.z}; }

}  // namespace cohort::kd

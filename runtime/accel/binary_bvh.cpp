// The binary BVH the wide BVHs collapse: references by early split clipping, then a binned-SAH
// tree with spatial splits, built in parallel into positions and slots each subtree owns before it
// starts (so the tree does not depend on the thread count), then compacted.
#include "runtime/accel/binary_bvh.h"

#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <bit>
#include <numeric>

#include "runtime/accel/clip.h"

namespace cohort::binary_bvh {
namespace {

constexpr int kBins = 32;
constexpr int kMedianDepth = 32;                 // below this, object-median splits bound the depth
constexpr double kSplitAreaFactor = 1.0;         // split references whose box area is over the mean
constexpr int kMaxSplitDepth = 6;                // at most 64 references per triangle
constexpr int kSpatialBins = 16;                 // spatial split planes: the borders of this many bins
constexpr double kSpatialBudget = 0.25;          // spatial splits add at most this share of references
constexpr float kSpatialOverlap = 1e-5f;         // ... where the object split's children overlap so much
static_assert(kMedianDepth + 27 == kMaxDepth, "object medians below kMedianDepth halve at most 2^27 references");

Box triangle_box(const Triangle& t) {
  Box b;
  for (const co_float4* p : {&t.v0, &t.v1, &t.v2}) b.extend(std::array<float, 3>{p->x, p->y, p->z});
  return b;
}

// The parts of triangle t within `cell` on each side of x[axis] = plane (kd::split_triangle_bounds,
// conservative): what early split clipping and the spatial splits cut references with.
std::array<Bounds, 2> split_triangle(const Triangle& t, const Bounds& cell, int axis, float plane) {
  return kd::split_triangle_bounds({t.v0.x, t.v0.y, t.v0.z}, {t.v1.x, t.v1.y, t.v1.z}, {t.v2.x, t.v2.y, t.v2.z}, cell,
                                   cell, axis, plane);
}


}  // namespace

// Early split clipping (Ernst & Greiner, "Early Split Clipping for Bounding Volume Hierarchies",
// 2007): a triangle whose box is larger than the average triangle's (long thin or diagonal
// triangles, the walls and pillars of an interior) enters the tree as several references, each with
// the box of its part in one half of the box before (kd::split_triangle_bounds, conservative),
// halved along the longest side until no larger than the average or six times. On the Sponza
// interior this made renders 1.16x faster on 2 CPU cores for 27 % more references; a threshold of
// 16 times the average gained 1.07x, and on the other bench scenes every threshold was within the
// noise (results/raw/pocl-2026-12-03-ee75f6e). A ray then opens the leaves near where it meets the triangle
// rather than every leaf the triangle's whole box overlaps. Several references to one triangle
// change no hit: the closest hit is the least (t, index) however often a triangle is tested.
// In fixed chunks of triangles, each with its references; joined in chunk order (Builder), the
// same references for any thread count.

ReferenceChunks make_references(std::span<const Triangle> triangles) {
  const std::size_t n = triangles.size();
  double mean_area = 0;
  for (const Triangle& t : triangles) mean_area += triangle_box(t).area();
  mean_area /= static_cast<double>(n);
  const float threshold = static_cast<float>(kSplitAreaFactor * mean_area);
  constexpr std::size_t kChunk = 16384;
  const std::size_t chunks = (n + kChunk - 1) / kChunk;
  std::vector<std::vector<Reference>> parts(chunks);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t c) {
    std::vector<Reference>& out = parts[c];
    const auto split = [&](auto& self, const Triangle& t, std::uint32_t index, const Box& box, int depth) -> void {
      if (!(box.area() > threshold) || depth == kMaxSplitDepth) {
        out.push_back({box, index});
        return;
      }
      int axis = 0;
      for (int a = 1; a < 3; ++a)
        if (box.hi[a] - box.lo[a] > box.hi[axis] - box.lo[axis]) axis = a;
      Bounds cell;
      cell.lo = {box.lo[0], box.lo[1], box.lo[2]};
      cell.hi = {box.hi[0], box.hi[1], box.hi[2]};
      const float mid = 0.5f * (box.lo[axis] + box.hi[axis]);
      for (const Bounds& h : split_triangle(t, cell, axis, mid)) {
        if (h.empty()) continue;
        self(self, t, index, Box{{h.lo.x, h.lo.y, h.lo.z}, {h.hi.x, h.hi.y, h.hi.z}}, depth + 1);
      }
    };
    for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i)
      split(split, triangles[i], static_cast<std::uint32_t>(i), triangle_box(triangles[i]), 0);
  });
  ReferenceChunks out{std::move(parts), 0};
  for (const auto& p : out.chunks) out.size += p.size();
  return out;
}

namespace {

// Four floats in one SSE register (GCC and Clang vector extensions): a reference's box corner,
// x y z and an unused lane. The binning below extends bin boxes with one min and one max of these
// instead of six scalar ones. vmin and vmax choose exactly as std::min and std::max (the first
// argument unless the second is smaller, or larger), so the tree is the bits of a scalar build.
typedef float Vec4 __attribute__((vector_size(16)));
typedef int Int4 __attribute__((vector_size(16)));
inline Vec4 vmin(Vec4 a, Vec4 b) { return b < a ? b : a; }
inline Vec4 vmax(Vec4 a, Vec4 b) { return a < b ? b : a; }

struct alignas(32) RefBox {
  Vec4 lo, hi;  // w lanes 0
};

constexpr RefBox kEmptyRefBox{Vec4{INFINITY, INFINITY, INFINITY, INFINITY},
                              Vec4{-INFINITY, -INFINITY, -INFINITY, -INFINITY}};

inline void extend(RefBox& box, const RefBox& other) {
  box.lo = vmin(box.lo, other.lo);
  box.hi = vmax(box.hi, other.hi);
}

// Box::area's arithmetic, term for term, on the x y z lanes.
inline float area_of(const RefBox& b) {
  const Vec4 d = b.hi - b.lo;
  const float x = std::max(0.0f, d[0]), y = std::max(0.0f, d[1]), z = std::max(0.0f, d[2]);
  return x * y + y * z + z * x;
}

// A reference's centroid, lane a on axis a: what the binning, the partition and the median split
// all sort by, so one expression gives each of them the same bits.
inline Vec4 centroid_of(const RefBox& b) { return 0.5f * (b.lo + b.hi); }

// A node's bounds: the box of its references and the box of their centroids.
struct NodeBounds {
  RefBox box = kEmptyRefBox;
  RefBox centroids = kEmptyRefBox;
  void add(const RefBox& r) {
    extend(box, r);
    const Vec4 c = centroid_of(r);
    centroids.lo = vmin(centroids.lo, c);
    centroids.hi = vmax(centroids.hi, c);
  }
};

struct Builder {
  // Per reference position, in tree order: the partitions move a reference's box with its triangle,
  // so every pass over a node reads its boxes in sequence (indices into one array of boxes made the
  // top levels' passes a gather over the whole scene).
  // Arrays of trivial types allocated without clearing (filled in parallel below, or written by
  // the build before they are read): clearing them was a serial pass over 200 MB for 1.6M references.
  // A subtree owns `cap` positions from its first (at least its references; spatial splits add
  // references into the rest) and the 2 cap - 1 node slots from its root's: its left child's subtree
  // starts one after the root, its right child's after the left's 2 cap_left - 1. Unused positions
  // and slots stay unwritten; `compact` closes the gaps.
  std::size_t size;      // references made by early split clipping
  std::size_t capacity;  // positions: size and the spatial splits' budget
  std::unique_ptr<RefBox[]> box;
  std::unique_ptr<std::uint32_t[]> tri;  // per position: the reference's triangle
  std::unique_ptr<Node[]> nodes;
  std::span<const Triangle> triangles;
  LeafShape shape;  // what a leaf may hold and what its triangle tests cost
  float root_area = 0;

  // The references of the chunks in chunk order, each chunk copied by its own task.
  Builder(const ReferenceChunks& references, std::span<const Triangle> triangles_, LeafShape shape_,
          bool spatial_splits)
      : size(references.size),
        capacity(spatial_splits ? std::min<std::size_t>(size + static_cast<std::size_t>(kSpatialBudget * double(size)),
                                                        0x7fffffffu)
                                : size),
        box(std::make_unique_for_overwrite<RefBox[]>(capacity)),
        tri(std::make_unique_for_overwrite<std::uint32_t[]>(capacity)),
        nodes(std::make_unique_for_overwrite<Node[]>(2 * capacity - 1)),
        triangles(triangles_),
        shape(shape_) {
    const auto& chunks = references.chunks;
    std::vector<std::size_t> offset(chunks.size() + 1, 0);
    for (std::size_t c = 0; c < chunks.size(); ++c) offset[c + 1] = offset[c] + chunks[c].size();
    tbb::parallel_for(std::size_t{0}, chunks.size(), [&](std::size_t c) {
      for (std::size_t j = 0; j < chunks[c].size(); ++j) {
        const std::size_t i = offset[c] + j;
        const Box& b = chunks[c][j].box;
        box[i] = {Vec4{b.lo[0], b.lo[1], b.lo[2], 0.0f}, Vec4{b.hi[0], b.hi[1], b.hi[2], 0.0f}};
        tri[i] = chunks[c][j].triangle;
      }
    });
  }

  NodeBounds bounds_of(std::uint32_t first, std::uint32_t count) const {
    NodeBounds b;
    for (std::uint32_t i = first; i < first + count; ++i) b.add(box[i]);
    return b;
  }

  void swap_references(std::uint32_t i, std::uint32_t j) {
    std::swap(box[i], box[j]);
    std::swap(tri[i], tri[j]);
  }

  struct Split {
    int axis = -1;
    int bin = 0;
    float cost = INFINITY;
    RefBox left = kEmptyRefBox, right = kEmptyRefBox;  // the two children's boxes
  };

  Split best_split(std::uint32_t first, std::uint32_t count, const Box& centroids) const {
    // one pass over the references bins all three axes (an axis without extent is left out);
    // each axis's bins see the references in the same order as three passes would
    bool used[3];
    float scale_a[3];
    for (int a = 0; a < 3; ++a) {
      const float extent = centroids.hi[a] - centroids.lo[a];
      used[a] = extent > 0.0f;
      scale_a[a] = used[a] ? kBins / extent : 0.0f;
    }
    const Vec4 lo{centroids.lo[0], centroids.lo[1], centroids.lo[2], 0.0f};
    const Vec4 scale{scale_a[0], scale_a[1], scale_a[2], 0.0f};
    // A bin's box and count are set by its first reference (what extending an empty box gives)
    // and a bit per axis marks the bins in use, so nothing is cleared and the sweeps below find
    // the non-empty bins from the bits: most nodes hold far fewer references than bins, and
    // clearing and scanning 3 x 32 bins was most of their time.
    static_assert(kBins <= 32, "a bin per bit of an occupancy mask");
    std::array<std::array<RefBox, kBins>, 3> bin_box;
    std::array<std::array<std::uint32_t, kBins>, 3> bin_count;
    std::array<std::uint32_t, 3> occupied{};
    for (std::uint32_t i = first; i < first + count; ++i) {
      const RefBox& r = box[i];
      const Vec4 c = centroid_of(r);
      const Int4 bins = __builtin_convertvector((c - lo) * scale, Int4);
      for (int a = 0; a < 3; ++a) {
        if (!used[a]) continue;
        const int b = std::min(kBins - 1, bins[a]);
        const std::uint32_t bit = 1u << b;
        if (!(occupied[a] & bit)) {
          occupied[a] |= bit;
          bin_count[a][b] = 1;
          bin_box[a][b] = r;
        } else {
          ++bin_count[a][b];
          extend(bin_box[a][b], r);
        }
      }
    }
    // The sweeps visit the non-empty bins only: a cut after an empty bin splits the references as
    // the cut after the non-empty bin before it, at the same cost, and the first of equal costs
    // wins, so this is the split of a sweep over all 32 bins at a fraction of the work on the many
    // small nodes (fewer references than bins).
    Split best;
    for (int a = 0; a < 3; ++a) {
      if (!used[a]) continue;
      std::array<int, kBins> full;
      int m = 0;
      for (std::uint32_t bits = occupied[a]; bits; bits &= bits - 1) full[m++] = std::countr_zero(bits);
      std::array<float, kBins> right_area;  // [1, m) written before read
      std::array<RefBox, kBins> right_box;
      std::array<std::uint32_t, kBins> right_count;
      RefBox acc = kEmptyRefBox;
      std::uint32_t n = 0;
      for (int j = m - 1; j > 0; --j) {
        extend(acc, bin_box[a][full[j]]);
        n += bin_count[a][full[j]];
        right_area[j] = area_of(acc);
        right_box[j] = acc;
        right_count[j] = n;
      }
      acc = kEmptyRefBox;
      n = 0;
      for (int j = 0; j < m - 1; ++j) {
        extend(acc, bin_box[a][full[j]]);
        n += bin_count[a][full[j]];
        const float cost = area_of(acc) * shape.tests(n) + right_area[j + 1] * shape.tests(right_count[j + 1]);
        if (cost < best.cost) best = {a, full[j], cost, acc, right_box[j + 1]};
      }
    }
    return best;
  }

  static Box to_box(const RefBox& r) { return Box{{r.lo[0], r.lo[1], r.lo[2]}, {r.hi[0], r.hi[1], r.hi[2]}}; }

  // std::partition's algorithm (the bidirectional one libstdc++ uses for random-access ranges:
  // the same swaps, so the same tree as partitioning indices with it), moving boxes with their
  // references and taking each side's bounds on the way: every reference is classified once.
  template <class InLeft>
  std::uint32_t partition(std::uint32_t first, std::uint32_t last, InLeft in_left, NodeBounds& left,
                          NodeBounds& right) {
    while (true) {
      while (true) {
        if (first == last) return first;
        if (!in_left(box[first])) break;
        left.add(box[first++]);
      }
      --last;
      while (true) {
        if (first == last) {
          right.add(box[first]);  // the reference the loop above stopped at
          return first;
        }
        if (in_left(box[last])) break;
        right.add(box[last--]);
      }
      // box[first] goes right and box[last] left: swapped, each is on its side
      swap_references(first, last);
      left.add(box[first]);
      right.add(box[last]);
      ++first;
    }
  }

  // A spatial split (Stich, Friedrich & Dietrich, "Spatial Splits in Bounding Volume Hierarchies",
  // 2009): a plane at a bin border of the node's box, each reference that straddles it cut in two
  // (kd::split_triangle_bounds, conservative), so both children may hold a part of one triangle.
  struct SpatialSplit {
    int axis = -1;
    float plane = 0;
    float cost = INFINITY;
  };

  static Bounds to_bounds(const RefBox& r) {
    Bounds b;
    b.lo = {r.lo[0], r.lo[1], r.lo[2]};
    b.hi = {r.hi[0], r.hi[1], r.hi[2]};
    return b;
  }
  static RefBox to_ref_box(const Bounds& b) {
    return {Vec4{b.lo.x, b.lo.y, b.lo.z, 0.0f}, Vec4{b.hi.x, b.hi.y, b.hi.z, 0.0f}};
  }

  // The plane of bin border b (1 .. kSpatialBins - 1) of an axis from lo in steps of width: one
  // expression, so the boxes the bins price and the split the node makes cut at the same float.
  static float border(float lo, float width, int b) { return lo + width * static_cast<float>(b); }

  SpatialSplit best_spatial(std::uint32_t first, std::uint32_t count, const Box& node) const {
    SpatialSplit best;
    for (int a = 0; a < 3; ++a) {
      const float lo = node.lo[a], width = (node.hi[a] - node.lo[a]) / kSpatialBins;
      if (!(width > 0.0f)) continue;
      std::array<RefBox, kSpatialBins> bin;
      bin.fill(kEmptyRefBox);
      std::array<std::uint32_t, kSpatialBins> enter{}, leave{};
      const float inverse = kSpatialBins / (node.hi[a] - node.lo[a]);
      const auto bin_of = [&](float x) {
        return std::clamp(static_cast<int>((x - lo) * inverse), 0, kSpatialBins - 1);
      };
      for (std::uint32_t p = first; p < first + count; ++p) {
        const int b0 = bin_of(box[p].lo[a]), b1 = std::max(b0, bin_of(box[p].hi[a]));
        ++enter[b0];
        ++leave[b1];
        if (b0 == b1) {
          extend(bin[b0], box[p]);
          continue;
        }
        // the reference's box cut at the bin borders, not its triangle: an estimate for the SAH
        // (clipping the triangle at every border was most of a build's time); the split itself cuts
        // the triangle
        for (int b = b0; b <= b1; ++b) {
          RefBox part = box[p];
          if (b > b0) part.lo[a] = border(lo, width, b);
          if (b < b1) part.hi[a] = border(lo, width, b + 1);
          extend(bin[b], part);
        }
      }
      std::array<RefBox, kSpatialBins> right;
      std::array<std::uint32_t, kSpatialBins> right_count;
      RefBox acc = kEmptyRefBox;
      std::uint32_t n = 0;
      for (int b = kSpatialBins - 1; b > 0; --b) {
        extend(acc, bin[b]);
        n += leave[b];
        right[b] = acc;
        right_count[b] = n;
      }
      acc = kEmptyRefBox;
      n = 0;
      for (int b = 0; b + 1 < kSpatialBins; ++b) {
        extend(acc, bin[b]);
        n += enter[b];
        if (n == 0 || right_count[b + 1] == 0) continue;
        const float cost = area_of(acc) * shape.tests(n) + area_of(right[b + 1]) * shape.tests(right_count[b + 1]);
        if (cost < best.cost) best = {a, border(lo, width, b + 1), cost};
      }
    }
    return best;
  }

  // Moves the references [from, from + n) to start at `to` (>= from), boxes with their triangles.
  void shift(std::uint32_t from, std::uint32_t n, std::uint32_t to) {
    if (to == from) return;
    std::copy_backward(box.get() + from, box.get() + from + n, box.get() + to + n);
    std::copy_backward(tri.get() + from, tri.get() + from + n, tri.get() + to + n);
  }

  // Performs `split` on [first, first + count) within `cap` positions: the left side's references
  // from first, the right side's from first + its share of the positions; returns the two counts, or
  // {0, 0} (nothing changed, the bounds untouched) where one side would be empty or the positions are
  // too few.
  std::array<std::uint32_t, 2> spatial_partition(std::uint32_t first, std::uint32_t count, std::uint32_t cap,
                                                 const SpatialSplit& split, std::uint32_t& right_first,
                                                 NodeBounds& left_bounds, NodeBounds& right_bounds) {
    std::vector<RefBox> side_box[2];
    std::vector<std::uint32_t> side_tri[2];
    for (std::uint32_t p = first; p < first + count; ++p) {
      const RefBox& r = box[p];
      if (r.hi[split.axis] <= split.plane || r.lo[split.axis] >= split.plane) {
        const int side = r.hi[split.axis] <= split.plane ? 0 : 1;
        side_box[side].push_back(r);
        side_tri[side].push_back(tri[p]);
        continue;
      }
      const auto halves = split_triangle(triangles[tri[p]], to_bounds(r), split.axis, split.plane);
      for (int side = 0; side < 2; ++side) {
        if (halves[side].empty()) continue;
        side_box[side].push_back(to_ref_box(halves[side]));
        side_tri[side].push_back(tri[p]);
      }
    }
    const std::uint32_t nl = static_cast<std::uint32_t>(side_box[0].size());
    const std::uint32_t nr = static_cast<std::uint32_t>(side_box[1].size());
    if (nl == 0 || nr == 0 || nl + nr > cap) return {0u, 0u};
    right_first = first + share(nl, nr, cap);
    for (std::uint32_t i = 0; i < nl; ++i) {
      box[first + i] = side_box[0][i];
      tri[first + i] = side_tri[0][i];
      left_bounds.add(side_box[0][i]);
    }
    for (std::uint32_t i = 0; i < nr; ++i) {
      box[right_first + i] = side_box[1][i];
      tri[right_first + i] = side_tri[1][i];
      right_bounds.add(side_box[1][i]);
    }
    return {nl, nr};
  }

  // The positions of `cap` that the left child of nl and nr references gets: its own and the share of
  // the spare ones in proportion to its references.
  static std::uint32_t share(std::uint32_t nl, std::uint32_t nr, std::uint32_t cap) {
    const std::uint64_t spare = cap - nl - nr;
    return nl + static_cast<std::uint32_t>(spare * nl / (std::uint64_t(nl) + nr));
  }

  void build(std::uint32_t slot, std::uint32_t first, std::uint32_t count, std::uint32_t cap, int depth,
             const NodeBounds& bounds) {
    Node& node = nodes[slot];
    node.lo = {bounds.box.lo[0], bounds.box.lo[1], bounds.box.lo[2]};
    node.hi = {bounds.box.hi[0], bounds.box.hi[1], bounds.box.hi[2]};
    const Box centroids = to_box(bounds.centroids);
    node.first = first;
    node.count = count;
    node.references = count;
    if (count == 1) return;
    std::uint32_t mid = first + count / 2;
    NodeBounds left_bounds, right_bounds;
    const Split split = depth < kMedianDepth ? best_split(first, count, centroids) : Split{};
    std::uint32_t left_count = 0, right_count = 0, right_first = 0;
    bool done = false;
    if (split.axis >= 0) {
      const float area = node.box().area();
      // a spatial split is looked for where the object split's children overlap (Stich et al.'s
      // alpha) and the subtree has positions to spare
      SpatialSplit spatial;
      if (cap > count) {
        RefBox overlap{vmax(split.left.lo, split.right.lo), vmin(split.left.hi, split.right.hi)};
        if (area_of(overlap) > kSpatialOverlap * root_area) spatial = best_spatial(first, count, node.box());
      }
      const float best = std::min(split.cost, spatial.cost);
      if (count <= shape.max_leaf && area * shape.tests(count) <= kNodeCost * area + best) return;
      if (spatial.cost < split.cost) {
        const auto n = spatial_partition(first, count, cap, spatial, right_first, left_bounds, right_bounds);
        left_count = n[0];
        right_count = n[1];
        done = left_count != 0;
      }
      if (!done) {
        const int axis = split.axis;
        const float lo = centroids.lo[axis];
        const float scale = kBins / (centroids.hi[axis] - lo);
        const auto in_left = [&](const RefBox& r) {
          return std::min(kBins - 1, static_cast<int>((centroid_of(r)[axis] - lo) * scale)) <= split.bin;
        };
        mid = partition(first, first + count, in_left, left_bounds, right_bounds);
      }
    } else if (count <= shape.max_leaf) {
      return;  // every centroid in one point, or below the median depth: a leaf when small enough
    } else {
      if (depth >= kMedianDepth) median_split(first, count, mid, centroids);
      left_bounds = bounds_of(first, mid - first);
      right_bounds = bounds_of(mid, first + count - mid);
    }
    if (!done) {
      left_count = mid - first;
      right_count = first + count - mid;
      right_first = first + share(left_count, right_count, cap);
      shift(mid, right_count, right_first);
    }
    const std::uint32_t left_cap = right_first - first, right_cap = cap - left_cap;
    node.count = 0;  // `compact` sets every node's first and references
    node.left = slot + 1;
    node.right = slot + 2 * left_cap;
    const auto left = [&] { build(slot + 1, first, left_count, left_cap, depth + 1, left_bounds); };
    const auto right = [&] { build(node.right, right_first, right_count, right_cap, depth + 1, right_bounds); };
    if (count >= kParallelTriangles) {
      tbb::parallel_invoke(left, right);
    } else {
      left();
      right();
    }
  }

  // From depth kMedianDepth on, the object median along the widest centroid axis: halves the count,
  // so the depth stays bounded. nth_element over the positions with the references' order
  // (centroid, then triangle, then position) moves them as it would move the indices themselves;
  // boxes and triangles are then put in that order.
  void median_split(std::uint32_t first, std::uint32_t count, std::uint32_t mid, const Box& centroids) {
    int axis = 0;
    for (int a = 1; a < 3; ++a)
      if (centroids.hi[a] - centroids.lo[a] > centroids.hi[axis] - centroids.lo[axis]) axis = a;
    std::vector<std::uint32_t> order(count);
    std::iota(order.begin(), order.end(), first);
    std::nth_element(order.begin(), order.begin() + (mid - first), order.end(),
                     [&](std::uint32_t x, std::uint32_t y) {
                       const float cx = centroid_of(box[x])[axis], cy = centroid_of(box[y])[axis];
                       return cx < cy || (cx == cy && (tri[x] < tri[y] || (tri[x] == tri[y] && x < y)));
                     });
    std::vector<RefBox> moved_box(count);
    std::vector<std::uint32_t> moved_tri(count);
    for (std::uint32_t i = 0; i < count; ++i) {
      moved_box[i] = box[order[i]];
      moved_tri[i] = tri[order[i]];
    }
    std::copy(moved_box.begin(), moved_box.end(), box.get() + first);
    std::copy(moved_tri.begin(), moved_tri.end(), tri.get() + first);
  }

  // The tree with its references in leaf order and no gaps: every node's first and references name
  // its subtree's entries in one run (depth first, left before right).
  Tree compact() {
    Tree tree;
    std::vector<std::uint32_t> order;  // positions in leaf order
    order.reserve(capacity);
    const auto visit = [&](auto& self, std::uint32_t slot) -> void {
      Node& n = nodes[slot];
      const std::uint32_t start = static_cast<std::uint32_t>(order.size());
      if (n.count > 0) {
        for (std::uint32_t i = 0; i < n.count; ++i) order.push_back(n.first + i);
      } else {
        self(self, n.left);
        self(self, n.right);
      }
      n.first = start;
      n.references = static_cast<std::uint32_t>(order.size()) - start;
    };
    visit(visit, 0u);
    tree.size = order.size();
    tree.triangle = std::make_unique_for_overwrite<std::uint32_t[]>(tree.size);
    for (std::size_t i = 0; i < tree.size; ++i) tree.triangle[i] = tri[order[i]];
    tree.slots = 2 * capacity - 1;
    tree.nodes = std::move(nodes);
    return tree;
  }
};

}  // namespace

float Tree::pad() const {
  const Box root = nodes[0].box();
  float largest = 0.0f;
  for (int a = 0; a < 3; ++a) largest = std::max({largest, std::fabs(root.lo[a]), std::fabs(root.hi[a])});
  return std::ldexp(std::max(largest, 1e-20f), -20);
}

Tree build(const ReferenceChunks& references, std::span<const Triangle> triangles, LeafShape shape,
           bool spatial_splits) {
  Builder builder(references, triangles, shape, spatial_splits);
  const auto count = static_cast<std::uint32_t>(references.size);
  const NodeBounds root = builder.bounds_of(0u, count);
  builder.root_area = area_of(root.box);
  builder.build(0u, 0u, count, static_cast<std::uint32_t>(builder.capacity), 0, root);
  return builder.compact();
}

}  // namespace cohort::binary_bvh

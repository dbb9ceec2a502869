// build_bvh4: a binary BVH by binned SAH, built in parallel into slots fixed by the triangle counts
// (so the tree does not depend on the thread count), then collapsed into 4-wide nodes depth first.
#include "runtime/accel/bvh4.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <numeric>

#include "kernels/common/bvh4_traverse.h"
#include "runtime/accel/clip.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

constexpr int kBins = 32;
constexpr std::uint32_t kMaxLeaf = 4;            // triangles; BVH4_LEAF_MAX allows up to 16
constexpr int kMedianDepth = 32;                 // below this, object-median splits bound the depth
constexpr std::uint32_t kParallelTriangles = 4096;
constexpr float kNodeCost = 0.5f;                // a 4-wide box test against one triangle test
constexpr double kSplitAreaFactor = 1.0;         // split references whose box area is over the mean
constexpr int kMaxSplitDepth = 6;                // at most 64 references per triangle
static_assert(kMedianDepth + 27 <= BVH4_MAX_DEPTH, "the traversal stack must hold the deepest tree");

struct Box {
  std::array<float, 3> lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
  void extend(const Box& b) {
    for (int a = 0; a < 3; ++a) { lo[a] = std::min(lo[a], b.lo[a]); hi[a] = std::max(hi[a], b.hi[a]); }
  }
  void extend(const std::array<float, 3>& p) {
    for (int a = 0; a < 3; ++a) { lo[a] = std::min(lo[a], p[a]); hi[a] = std::max(hi[a], p[a]); }
  }
  float area() const {
    float d[3];
    for (int a = 0; a < 3; ++a) d[a] = std::max(0.0f, hi[a] - lo[a]);
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
  }
};

// A binary node; count > 0 marks a leaf of triangles [first, first + count) of the reference list.
struct Node2 {
  Box box;
  std::uint32_t first = 0, count = 0;
  std::uint32_t left = 0, right = 0;
};

Box triangle_box(const Triangle& t) {
  Box b;
  for (const co_float4* p : {&t.v0, &t.v1, &t.v2}) b.extend(std::array<float, 3>{p->x, p->y, p->z});
  return b;
}

// A part of a triangle the tree sorts on its own: the triangle's index and a box around its part.
struct Reference {
  Box box;
  std::uint32_t triangle;
};

// Early split clipping (Ernst & Greiner, "Early Split Clipping for Bounding Volume Hierarchies",
// 2007): a triangle whose box is larger than the average triangle's (long thin or diagonal
// triangles, the walls and pillars of an interior) enters the tree as several references, each with
// the box of its part in one half of the box before (kd::split_triangle_bounds, conservative),
// halved along the longest side until no larger than the average or six times. On the Sponza
// interior this made renders 1.16x faster on 2 CPU cores for 27 % more references; a threshold of
// 16 times the average gained 1.07x, and on the other bench scenes every threshold was within the
// noise (docs/results.md). A ray then opens the leaves near where it meets the triangle
// rather than every leaf the triangle's whole box overlaps. Several references to one triangle
// change no hit: the closest hit is the least (t, index) however often a triangle is tested.
// In fixed chunks joined in order: the same references for any thread count.
std::vector<Reference> make_references(std::span<const Triangle> triangles) {
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
      const auto halves = kd::split_triangle_bounds({t.v0.x, t.v0.y, t.v0.z}, {t.v1.x, t.v1.y, t.v1.z},
                                                    {t.v2.x, t.v2.y, t.v2.z}, cell, axis, mid);
      for (const Bounds& h : halves) {
        if (h.empty()) continue;
        self(self, t, index, Box{{h.lo.x, h.lo.y, h.lo.z}, {h.hi.x, h.hi.y, h.hi.z}}, depth + 1);
      }
    };
    for (std::size_t i = c * kChunk; i < std::min(n, (c + 1) * kChunk); ++i)
      split(split, triangles[i], static_cast<std::uint32_t>(i), triangle_box(triangles[i]), 0);
  });
  std::vector<Reference> refs;
  for (auto& p : parts) refs.insert(refs.end(), p.begin(), p.end());
  return refs;
}

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

// A reference's centroid, lane a on axis a: what the binning, the partition and the median split
// all sort by, so one expression gives each of them the same bits.
inline Vec4 centroid_of(const RefBox& b) { return 0.5f * (b.lo + b.hi); }

struct Builder {
  std::vector<RefBox> ref_box;                 // per reference
  std::vector<std::uint32_t> triangle;         // per reference
  std::vector<std::uint32_t> refs;             // reference indices, partitioned into the leaves
  // A subtree of n references owns the 2n - 1 slots from its root's: its left child's subtree
  // starts one after the root, its right child's after the left's 2 n_left - 1. Unused slots stay.
  std::vector<Node2> nodes;

  explicit Builder(const std::vector<Reference>& references)
      : ref_box(references.size()), triangle(references.size()),
        refs(references.size()), nodes(2 * references.size() - 1) {
    for (std::size_t i = 0; i < references.size(); ++i) {
      const Box& b = references[i].box;
      ref_box[i] = {Vec4{b.lo[0], b.lo[1], b.lo[2], 0.0f}, Vec4{b.hi[0], b.hi[1], b.hi[2], 0.0f}};
      triangle[i] = references[i].triangle;
    }
    std::iota(refs.begin(), refs.end(), 0u);
  }

  struct Split {
    int axis = -1;
    int bin = 0;
    float cost = INFINITY;
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
    // a bin's box is set by its first reference (what extending an empty box gives), so only
    // the counts start cleared: the sweeps below read non-empty bins only
    std::array<std::array<RefBox, kBins>, 3> bin_box;
    std::array<std::array<std::uint32_t, kBins>, 3> bin_count{};
    for (std::uint32_t i = first; i < first + count; ++i) {
      const RefBox& box = ref_box[refs[i]];
      const Vec4 c = centroid_of(box);
      const Int4 bins = __builtin_convertvector((c - lo) * scale, Int4);
      for (int a = 0; a < 3; ++a) {
        if (!used[a]) continue;
        const int b = std::min(kBins - 1, bins[a]);
        if (bin_count[a][b]++ == 0) {
          bin_box[a][b] = box;
        } else {
          bin_box[a][b].lo = vmin(bin_box[a][b].lo, box.lo);
          bin_box[a][b].hi = vmax(bin_box[a][b].hi, box.hi);
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
      for (int b = 0; b < kBins; ++b)
        if (bin_count[a][b]) full[m++] = b;
      std::array<float, kBins> right_area{};
      std::array<std::uint32_t, kBins> right_count{};
      Box acc;
      std::uint32_t n = 0;
      for (int j = m - 1; j > 0; --j) {
        acc.extend(to_box(bin_box[a][full[j]]));
        n += bin_count[a][full[j]];
        right_area[j] = acc.area();
        right_count[j] = n;
      }
      acc = Box{};
      n = 0;
      for (int j = 0; j < m - 1; ++j) {
        acc.extend(to_box(bin_box[a][full[j]]));
        n += bin_count[a][full[j]];
        const float cost = acc.area() * n + right_area[j + 1] * right_count[j + 1];
        if (cost < best.cost) best = {a, full[j], cost};
      }
    }
    return best;
  }

  float centroid(std::uint32_t r, int a) const { return centroid_of(ref_box[r])[a]; }

  static Box to_box(const RefBox& r) { return Box{{r.lo[0], r.lo[1], r.lo[2]}, {r.hi[0], r.hi[1], r.hi[2]}}; }

  void build(std::uint32_t slot, std::uint32_t first, std::uint32_t count, int depth) {
    Node2& node = nodes[slot];
    const Vec4 inf{INFINITY, INFINITY, INFINITY, INFINITY};
    RefBox box{inf, -inf}, centroid_box{inf, -inf};
    for (std::uint32_t i = first; i < first + count; ++i) {
      const RefBox& r = ref_box[refs[i]];
      box.lo = vmin(box.lo, r.lo);
      box.hi = vmax(box.hi, r.hi);
      const Vec4 c = centroid_of(r);
      centroid_box.lo = vmin(centroid_box.lo, c);
      centroid_box.hi = vmax(centroid_box.hi, c);
    }
    node.box = to_box(box);
    const Box centroids = to_box(centroid_box);
    node.first = first;
    node.count = count;
    if (count == 1) return;
    std::uint32_t mid = first + count / 2;
    const Split split = depth < kMedianDepth ? best_split(first, count, centroids) : Split{};
    if (split.axis >= 0) {
      const float leaf_cost = node.box.area() * count;
      if (count <= kMaxLeaf && leaf_cost <= kNodeCost * node.box.area() + split.cost) return;
      const float scale = kBins / (centroids.hi[split.axis] - centroids.lo[split.axis]);
      const auto in_left = [&](std::uint32_t r) {
        return std::min(kBins - 1, static_cast<int>((centroid(r, split.axis) - centroids.lo[split.axis]) * scale)) <=
               split.bin;
      };
      mid = static_cast<std::uint32_t>(std::partition(refs.begin() + first, refs.begin() + first + count, in_left) -
                                       refs.begin());
    } else if (count <= kMaxLeaf) {
      return;  // every centroid in one point, or below the median depth: a leaf when small enough
    } else if (depth >= kMedianDepth) {
      // the object median along the widest centroid axis: halves the count, so the depth stays bounded
      int axis = 0;
      for (int a = 1; a < 3; ++a)
        if (centroids.hi[a] - centroids.lo[a] > centroids.hi[axis] - centroids.lo[axis]) axis = a;
      std::nth_element(refs.begin() + first, refs.begin() + mid, refs.begin() + first + count,
                       [&](std::uint32_t x, std::uint32_t y) {
                         const float cx = centroid(x, axis), cy = centroid(y, axis);
                         return cx < cy || (cx == cy && x < y);
                       });
    }
    node.count = 0;
    const std::uint32_t left_count = mid - first, right_count = first + count - mid;
    node.left = slot + 1;
    node.right = slot + 2 * left_count;
    const auto left = [&] { build(slot + 1, first, left_count, depth + 1); };
    const auto right = [&] { build(slot + 2 * left_count, mid, right_count, depth + 1); };
    if (count >= kParallelTriangles) {
      tbb::parallel_invoke(left, right);
    } else {
      left();
      right();
    }
  }
};

// Boxes grow by `pad` on every side: the watertight test reports a hit on a shared edge or vertex
// for a ray that, rounded otherwise, passes a few ulps outside that triangle's box, and the box
// must still let it in (bvh4_traverse.h).
void set_lane(Bvh4Node& node, int lane, const Box& b, std::uint32_t child, float pad) {
  float* lanes[6] = {&node.lo_x.x, &node.hi_x.x, &node.lo_y.x, &node.hi_y.x, &node.lo_z.x, &node.hi_z.x};
  for (int a = 0; a < 3; ++a) {
    lanes[2 * a][lane] = b.lo[a] - pad;
    lanes[2 * a + 1][lane] = b.hi[a] + pad;
  }
  (&node.child.x)[lane] = child;
}

struct Collapser {
  const Builder& b;
  Bvh4& out;
  float pad;  // 2^-20 of the largest coordinate: far above the rounding of any vertex
  double sah = 0;  // sum over nodes and leaves of area x cost, divided by the root's area at the end

  // Appends the 4-wide node for binary inner node `slot` and its subtree; returns its index.
  std::uint32_t collapse(std::uint32_t slot, int depth) {
    const auto me = static_cast<std::uint32_t>(out.nodes.size());
    out.nodes.emplace_back();
    std::array<std::uint32_t, 4> kids{};
    int n = 0;
    if (b.nodes[slot].count) {
      kids[n++] = slot;  // a root that is a leaf: one lane
    } else {
      kids[n++] = b.nodes[slot].left;
      kids[n++] = b.nodes[slot].right;
    }
    // open the inner child of largest area until four lanes are full
    while (n < 4) {
      int widest = -1;
      for (int i = 0; i < n; ++i) {
        const Node2& k = b.nodes[kids[i]];
        if (!k.count && (widest < 0 || k.box.area() > b.nodes[kids[widest]].box.area())) widest = i;
      }
      if (widest < 0) break;
      const Node2& k = b.nodes[kids[widest]];
      kids[widest] = k.left;
      kids[n++] = k.right;
    }
    Bvh4Node node{};
    const Box empty{{INFINITY, INFINITY, INFINITY}, {INFINITY, INFINITY, INFINITY}};
    for (int lane = 0; lane < 4; ++lane) set_lane(node, lane, empty, BVH4_EMPTY, 0.0f);
    sah += kNodeCost * b.nodes[slot].box.area();
    out.stats.depth = std::max(out.stats.depth, depth);
    for (int lane = 0; lane < n; ++lane) {
      const Node2& k = b.nodes[kids[lane]];
      std::uint32_t child;
      if (k.count) {
        child = bvh4_leaf_ref(k.first, k.count);
        ++out.stats.leaf_count;
        sah += k.box.area() * k.count;
      } else {
        child = collapse(kids[lane], depth + 1);
      }
      set_lane(node, lane, k.box, child, pad);
    }
    out.nodes[me] = node;
    return me;
  }
};

}  // namespace

Bvh4 build_bvh4(std::span<const Triangle> triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.empty()) throw InputError("a BVH needs at least one triangle");
  if (triangles.size() > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene has {} triangles; the 4-wide BVH (--tree bvh4) takes at most {}: use "
                                 "--tree deep or compact",
                                 triangles.size(), BVH4_LEAF_FIRST_MAX));
  const std::vector<Reference> references = make_references(triangles);
  if (references.size() > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene's {} triangles make {} BVH references; the 4-wide BVH (--tree bvh4) "
                                 "takes at most {}: use --tree deep or compact",
                                 triangles.size(), references.size(), BVH4_LEAF_FIRST_MAX));
  Builder builder(references);
  builder.build(0u, 0u, static_cast<std::uint32_t>(references.size()), 0);
  Bvh4 bvh;
  bvh.nodes.reserve(triangles.size() / 2 + 1);
  const Box& root = builder.nodes[0].box;
  float largest = 0.0f;
  for (int a = 0; a < 3; ++a) largest = std::max({largest, std::fabs(root.lo[a]), std::fabs(root.hi[a])});
  Collapser collapser{builder, bvh, std::ldexp(std::max(largest, 1e-20f), -20)};
  collapser.collapse(0, 1);
  bvh.leaf_vertices.resize(builder.refs.size());
  for (std::size_t i = 0; i < builder.refs.size(); ++i) {
    const std::uint32_t tri = builder.triangle[builder.refs[i]];
    bvh.leaf_vertices[i] = triangles[tri];
    bvh.leaf_vertices[i].v0.w = co_as_float(tri);
  }
  bvh.stats.node_count = bvh.nodes.size();
  bvh.stats.references = references.size();
  bvh.stats.average_leaf_triangles = double(references.size()) / double(bvh.stats.leaf_count);
  const float root_area = builder.nodes[0].box.area();
  bvh.stats.sah_cost = root_area > 0 ? collapser.sah / root_area : 0.0;
  bvh.stats.bytes = bvh.nodes.size() * sizeof(Bvh4Node) + bvh.leaf_vertices.size() * sizeof(Triangle);
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace cohort

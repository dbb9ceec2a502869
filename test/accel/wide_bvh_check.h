// The wide BVHs side by side for their tests: a traits struct per tree (build it, view it, trace a
// ray) for the typed suite of wide_bvh_common_test.cpp, each layout's structure check (defined in
// its own test file), what those checks share, and the hit check that sets one tree's closest and
// any hits against the KD-tree's, every other wide BVH's and brute force's, bit for bit.
#pragma once

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "accel/ray_check.h"
#include "accel/tree_check.h"
#include "runtime/accel/host_traversal.h"

namespace cohort::test {

// Each layout's walk over its nodes (bvh4_test.cpp, bvh8_test.cpp, bvh8f_test.cpp): the first few
// violations, empty when the tree is sound; `kept` holds the triangles it was built from.
std::vector<std::string> structure_errors(const Bvh4& bvh, const KdTree& kept);
std::vector<std::string> structure_errors(const Bvh8& bvh, const KdTree& kept);
std::vector<std::string> structure_errors(const Bvh8f& bvh, const KdTree& kept);

// What the three walks check alike: each node reached once; each child's box not inverted and
// inside its parent's; leaves of at most the layout's entries, each entry in range, reached once, a
// copy of a kept triangle with that triangle's index in v0.w (what the device reads) and overlapping
// its leaf's box; every kept triangle in at least one leaf (early split clipping and spatial splits
// put parts of one triangle in several); the leaf count, the references and the depth the stats say, the
// depth within the traversal's stack. The walk adds its layout's own errors to `errors`.
class StructureTally {
 public:
  // `leaf_vertices`: the leaves' entries as the 4-wide BVH stores them (each a copy of its kept
  // triangle with the triangle's index in v0.w); a layout that stores them otherwise converts them.
  StructureTally(std::size_t node_count, std::vector<Triangle> leaf_vertices, const KdTree& kept);

  // Counts a visit of node `index` at `depth` (the root's children are at depth 1); false, with an
  // error, when the node is out of range or was reached before.
  bool reach(std::uint32_t index, int depth);
  // Checks the box [lo, hi] of node `index`'s child `lane`: not inverted, and inside its parent's
  // box [plo, phi] where it has a parent (plo not null).
  void box(std::uint32_t index, int lane, const float lo[3], const float hi[3], const float* plo, const float* phi);
  // Checks a leaf's entries [first, first + count), at most max_count, against the leaf's box.
  void leaf(std::uint32_t first, std::uint32_t count, std::uint32_t max_count, const float lo[3], const float hi[3]);
  // Entry `entry` is padding that no leaf names (an unused lane of a block): it must be a copy of
  // entry `copy_of`, and it is not counted among the references.
  void padding(std::uint32_t entry, std::uint32_t copy_of);
  // The walk's errors and those of the totals, the first ten.
  std::vector<std::string> finish(const Bvh4Stats& stats, int max_depth);

  std::vector<std::string> errors;

 private:
  const std::vector<Triangle> leaf_vertices_;
  std::size_t padding_ = 0;
  const KdTree& kept_;
  std::vector<int> seen_node_, seen_entry_, seen_triangle_;
  std::size_t leaves_ = 0;
  int deepest_ = 0;
};

// A wide BVH's tree and view types, its builder and its traversal, for the typed suite.
template <typename TreeType, typename ViewType, TreeType (*Build)(std::span<const Triangle>),
          HitOut (*Trace)(const ViewType*, co_vec3, co_vec3, float, float, int, std::uint32_t*)>
struct WideBvhTraits {
  using Tree = TreeType;
  using View = ViewType;
  static Tree build(std::span<const Triangle> triangles) { return Build(triangles); }
  static HitOut trace(const View& view, co_vec3 org, co_vec3 dir, float tmax, int any_hit, std::uint32_t* steps) {
    return Trace(&view, org, dir, 0.f, tmax, any_hit, steps);
  }
};

// kDescription names the tree in the log; kMaxDepth is the depth its traversal's stack holds.
struct Bvh4Traits : WideBvhTraits<Bvh4, Bvh4View, build_bvh4, bvh4_trace_steps> {
  static constexpr const char* kDescription = "4-wide BVH";
  static constexpr int kMaxDepth = BVH4_MAX_DEPTH;
};
struct Bvh8Traits : WideBvhTraits<Bvh8, Bvh8View, build_bvh8, bvh8_trace_steps> {
  static constexpr const char* kDescription = "compressed 8-wide BVH";
  static constexpr int kMaxDepth = BVH8_STACK;
};
struct Bvh8fTraits : WideBvhTraits<Bvh8f, Bvh8fView, build_bvh8f, bvh8f_trace_steps> {
  static constexpr const char* kDescription = "8-wide BVH with float planes";
  static constexpr int kMaxDepth = BVH4_MAX_DEPTH;
};

// A wide BVH's leaves as bytes: the 4-wide and compressed BVHs' entries, the 8-wide one with float
// planes' blocks of four triangles.
template <class Tree>
std::span<const std::byte> leaf_bytes(const Tree& tree) {
  if constexpr (requires { tree.leaf_blocks; })
    return std::as_bytes(std::span(tree.leaf_blocks));
  else
    return std::as_bytes(std::span(tree.leaf_vertices));
}

// A tree and its host view (which points into the tree, so neither is copied).
template <typename Traits>
struct BuiltBvh {
  explicit BuiltBvh(std::span<const Triangle> triangles) : tree(Traits::build(triangles)), view(host_view(tree)) {}
  BuiltBvh(const BuiltBvh&) = delete;
  BuiltBvh& operator=(const BuiltBvh&) = delete;
  HitOut trace(co_vec3 org, co_vec3 dir, float tmax, int any_hit, std::uint32_t* steps = nullptr) const {
    return Traits::trace(view, org, dir, tmax, any_hit, steps);
  }

  const typename Traits::Tree tree;
  const typename Traits::View view;
};

// A wide BVH's closest hit on (0, inf), whichever tree it is.
struct AnyWideBvh {
  const char* description;
  std::function<HitOut(co_vec3 org, co_vec3 dir)> closest_hit;
};

template <typename Traits>
AnyWideBvh any_wide_bvh(std::span<const Triangle> triangles) {
  const auto built = std::make_shared<const BuiltBvh<Traits>>(triangles);
  return {Traits::kDescription, [built](co_vec3 org, co_vec3 dir) { return built->trace(org, dir, kInf, 0); }};
}

// Every wide BVH over `triangles` but the one of Traits.
template <typename Traits>
std::vector<AnyWideBvh> other_wide_bvhs(std::span<const Triangle> triangles) {
  std::vector<AnyWideBvh> others;
  if constexpr (!std::is_same_v<Traits, Bvh4Traits>) others.push_back(any_wide_bvh<Bvh4Traits>(triangles));
  if constexpr (!std::is_same_v<Traits, Bvh8Traits>) others.push_back(any_wide_bvh<Bvh8Traits>(triangles));
  if constexpr (!std::is_same_v<Traits, Bvh8fTraits>) others.push_back(any_wide_bvh<Bvh8fTraits>(triangles));
  return others;
}

// The rays of the hit check over `kd`: 20k feature rays (at shared vertices and edge midpoints),
// 10k random ones and 10k from split planes.
std::vector<TestRay> hit_check_rays(const KdTree& kd);

// Builds the tree of Traits over `positions`' kept triangles and checks its structure, then over
// hit_check_rays: its closest hit against the deep KD-tree's and every other wide BVH's, bit for
// bit, and against brute force's on every 8th ray; its any hit before half and before 1.5 times
// the closest distance against the KD-tree's.
template <typename Traits>
void expect_same_hits(const std::vector<glm::vec3>& positions, const char* name) {
  const KdTree kd = build_kdtree(positions);
  const KdTree kept = kept_triangles(positions);
  ASSERT_EQ(kd.triangles.size(), kept.triangles.size());
  ASSERT_EQ(0, std::memcmp(kd.triangles.data(), kept.triangles.data(), kd.triangles.size() * sizeof(Triangle)));
  const BuiltBvh<Traits> bvh(kept.triangles);
  for (const std::string& e : structure_errors(bvh.tree, kept)) ADD_FAILURE() << name << ": " << e;
  const std::vector<AnyWideBvh> others = other_wide_bvhs<Traits>(kept.triangles);
  const KdTreeView kv = view_of(kd);
  const std::vector<TestRay> rays = hit_check_rays(kd);
  std::size_t hits = 0, differ = 0, brute_differ = 0, occlusion_differ = 0;
  std::vector<std::size_t> others_differ(others.size(), 0);
  std::uint64_t kd_steps = 0, bvh_steps = 0;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const TestRay& ray = rays[i];
    const co_vec3 org = v3(ray.org.x, ray.org.y, ray.org.z), dir = v3(ray.dir.x, ray.dir.y, ray.dir.z);
    std::uint32_t ks = 0, bs = 0;
    const HitOut k = kd_trace_steps(&kv, org, dir, 0.f, kInf, 0, &ks);
    const HitOut b = bvh.trace(org, dir, kInf, 0, &bs);
    kd_steps += ks;
    bvh_steps += bs;
    hits += k.triangle != HIT_NONE;
    differ += std::memcmp(&k, &b, sizeof(HitOut)) != 0;
    for (std::size_t o = 0; o < others.size(); ++o) {
      const HitOut other = others[o].closest_hit(org, dir);
      others_differ[o] += std::memcmp(&other, &b, sizeof(HitOut)) != 0;
    }
    if (i % 8 == 0) {
      const HitOut e = brute_force(kept, ray, 0.f, kInf);
      brute_differ += std::memcmp(&e, &b, sizeof(HitOut)) != 0;
    }
    for (const float limit : {0.5f, 1.5f}) {
      const float tmax = k.triangle != HIT_NONE ? limit * k.t : kInf;
      occlusion_differ += (kd_trace(&kv, org, dir, 0.f, tmax, 1).triangle != HIT_NONE) !=
                          (bvh.trace(org, dir, tmax, 1).triangle != HIT_NONE);
    }
  }
  std::string against_others;
  for (std::size_t o = 0; o < others.size(); ++o)
    against_others += fmt::format(", {} from the {}", others_differ[o], others[o].description);
  fmt::print("[{}] {} rays, {} hits; {} of {} nodes, depth {}: closest hits differing {} from the KD-tree{}, {} from "
             "brute force; any-hit answers differing {}; {:.1f} KD-tree visits against {:.1f} steps per ray\n",
             name, rays.size(), hits, Traits::kDescription, bvh.tree.stats.node_count, bvh.tree.stats.depth, differ,
             against_others, brute_differ, occlusion_differ, double(kd_steps) / rays.size(),
             double(bvh_steps) / rays.size());
  EXPECT_GT(hits, rays.size() / 4);
  EXPECT_EQ(differ, 0u);
  for (std::size_t o = 0; o < others.size(); ++o) EXPECT_EQ(others_differ[o], 0u) << "against the " << others[o].description;
  EXPECT_EQ(brute_differ, 0u);
  EXPECT_EQ(occlusion_differ, 0u);
}

}  // namespace cohort::test

// bvh4_walk and bvh4_path_bits (kernels/common/accel/bvh4_path.h), the BVH's partial traversal: at every
// level the record names the child whose box the ray enters first among those it enters, checked
// against slab tests done here in double precision; zeros once the walk ends; equal directions from
// one point, equal bits. The traversal resumed where the walk stops finds the full traversal's hit,
// bit for bit, visiting every node the full traversal visits but those the walk did, once; the walk
// over the breadth-first top alone (a prefix of the nodes, as in local memory) decides the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "accel/ray_check.h"
#include "accel/test_meshes.h"
#include "kernels/common/accel/bvh4_path.h"
#include "runtime/accel/host_traversal.h"

namespace cohort::test {
namespace {

// Entry distance of the ray into lane k's box over (0, inf), or infinity when it misses.
double box_entry(const Bvh4Node& n, int k, const glm::dvec3& o, const glm::dvec3& d) {
  const float* lo[3] = {&n.lo_x.x, &n.lo_y.x, &n.lo_z.x};
  const float* hi[3] = {&n.hi_x.x, &n.hi_y.x, &n.hi_z.x};
  double t0 = 0, t1 = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const double l = lo[a][k], h = hi[a][k];
    if (std::isinf(l) && std::isinf(h) && l > 0) return std::numeric_limits<double>::infinity();  // unused lane
    if (d[a] == 0) {
      if (o[a] < l || o[a] > h) return std::numeric_limits<double>::infinity();
      continue;
    }
    double ta = (l - o[a]) / d[a], tb = (h - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 ? t0 : std::numeric_limits<double>::infinity();
}

TEST(Bvh4Path, EachLevelNamesTheChildEnteredFirst) {
  const KdTree kept = build_kdtree(load_shipped("voxel-terrain.gltf"), {});
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const Bvh4View view = host_view(bvh);
  constexpr std::uint32_t levels = 6;
  int checked = 0, ambiguous = 0;  // levels checked; near-ties left unchecked
  for (const TestRay& r : make_rays(kept.bounds, 2000, 11)) {
    const std::uint32_t bits = bvh4_path_bits(&view, v3(r.org.x, r.org.y, r.org.z), v3(r.dir.x, r.dir.y, r.dir.z),
                                              levels);
    std::uint32_t ref = 0;
    bool at_leaf = false;
    for (std::uint32_t level = 0; level < levels; ++level) {
      const std::uint32_t lane = (bits >> (2 * (levels - 1 - level))) & 3u;
      if (at_leaf || bvh4_is_leaf(ref)) {
        EXPECT_EQ(lane, 0u) << "level " << level << " after the walk reached a leaf";
        at_leaf = true;
        continue;
      }
      const Bvh4Node& n = bvh.nodes[ref];
      double best = std::numeric_limits<double>::infinity(), second = best;
      int first = -1;
      for (int k = 0; k < 4; ++k) {
        const double t = box_entry(n, k, glm::dvec3(r.org), glm::dvec3(r.dir));
        if (t < best) { second = best; best = t; first = k; } else if (t < second) second = t;
      }
      // no child entered (the float test, with its widened exit, may still graze one), or a near-tie
      // between boxes (shared faces) that may round either way in float: this ray is followed no further
      if (first < 0 || second - best <= 1e-4 * std::max(1.0, best)) {
        ambiguous += first >= 0;
        break;
      }
      EXPECT_EQ(lane, std::uint32_t(first)) << "level " << level;
      ++checked;
      const std::uint32_t children[4] = {n.child.x, n.child.y, n.child.z, n.child.w};
      ref = children[lane];
    }
  }
  EXPECT_GT(checked, 2000);  // most rays are followed several levels down
  EXPECT_LT(ambiguous, checked / 4);
}

TEST(Bvh4Path, RaysFromOnePointInOneDirectionShareTheirBits) {
  const KdTree kept = build_kdtree(load_shipped("voxel-terrain.gltf"), {});
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const Bvh4View view = host_view(bvh);
  const co_vec3 o = v3(kept.bounds.lo.x - 1.f, kept.bounds.hi.y + 1.f, kept.bounds.lo.z - 1.f);
  const co_vec3 d = v3(0.6f, -0.5f, 0.62f);
  const std::uint32_t a = bvh4_path_bits(&view, o, d, 8), b = bvh4_path_bits(&view, o, d, 8);
  EXPECT_EQ(a, b);
  EXPECT_EQ(bvh4_path_bits(&view, o, d, 4), a >> 8);  // fewer levels: the same top bits
}

// Where a walk of `levels` over the first `top_nodes` nodes stops.
struct WalkEnd {
  std::uint32_t bits = 0, ref = 0;
  float ref_t = 0;
  int sp = 0;
  std::uint32_t stack_ref[BVH4_STACK];
  float stack_t[BVH4_STACK];
  bool same_state(const WalkEnd& o) const {
    return ref == o.ref && ref_t == o.ref_t && sp == o.sp &&
           std::equal(stack_ref, stack_ref + sp, o.stack_ref) && std::equal(stack_t, stack_t + sp, o.stack_t);
  }
};

WalkEnd walk(const std::vector<Bvh4Node>& top, std::uint32_t top_nodes, std::uint32_t levels, const Bvh4View& bvh,
             const Bvh4Ray& r, float tmin, float tmax) {
  WalkEnd w;
  w.bits = bvh4_walk(top.data(), top_nodes, levels, &bvh, &r, tmin, tmax, &w.ref, &w.ref_t, w.stack_ref, w.stack_t,
                     &w.sp);
  return w;
}

void expect_walk_and_resume_are_the_traversal(const std::vector<glm::vec3>& mesh, std::uint32_t seed) {
  const KdTree kept = build_kdtree(mesh, {});
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const Bvh4View view = host_view(bvh);
  const auto& starts = bvh.top_level_starts;
  ASSERT_GE(starts.size(), 2u);
  ASSERT_LE(starts.size(), BVH4_TOP_LEVELS + 1);
  int walked = 0, rays = 0;  // walks (a ray per level count) that went at least one step
  const float short_range = 0.3f * glm::length(kept.bounds.hi - kept.bounds.lo);
  for (const TestRay& tr : make_rays(kept.bounds, 1500, seed)) {
    const co_vec3 o = v3(tr.org.x, tr.org.y, tr.org.z), d = v3(tr.dir.x, tr.dir.y, tr.dir.z);
    // every other ray a shadow ray's finite interval
    const float tmin = 0.f, tmax = rays % 2 ? short_range : kInf;
    std::uint32_t full_steps = 0;
    const HitOut full = bvh4_trace_steps(&view, o, d, tmin, tmax, 0, &full_steps);
    const Bvh4Ray r = bvh4_ray(o, d);
    for (std::uint32_t levels = 0; levels < starts.size(); ++levels) {
      // the top alone, as local memory holds it: the same walk as over the whole array
      const std::vector<Bvh4Node> top(bvh.nodes.begin(), bvh.nodes.begin() + starts[levels]);
      WalkEnd w = walk(top, starts[levels], levels, view, r, tmin, tmax);
      const WalkEnd whole = walk(bvh.nodes, starts[levels], levels, view, r, tmin, tmax);
      ASSERT_TRUE(w.same_state(whole) && w.bits == whole.bits) << "levels " << levels;
      // the nodes the walk visited: one per level it went on
      std::uint32_t steps_walked = 0;
      for (std::uint32_t l = 1; l <= levels; ++l)
        steps_walked += !walk(bvh.nodes, starts[l], l, view, r, tmin, tmax)
                             .same_state(walk(bvh.nodes, starts[l - 1], l - 1, view, r, tmin, tmax));
      HitOut resumed;
      resumed.t = tmax; resumed.u = 0; resumed.v = 0; resumed.triangle = HIT_NONE;
      std::uint32_t resume_steps = 0;
      if (w.ref != TRAVERSAL_DONE)
        bvh4_continue(&view, &r, tmin, 0, &resumed, w.ref, w.ref_t, w.stack_ref, w.stack_t, w.sp, &resume_steps);
      ASSERT_EQ(resumed.triangle, full.triangle) << "levels " << levels;
      ASSERT_EQ(co_as_uint(resumed.t), co_as_uint(full.t)) << "levels " << levels;
      ASSERT_EQ(co_as_uint(resumed.u), co_as_uint(full.u));
      ASSERT_EQ(co_as_uint(resumed.v), co_as_uint(full.v));
      ASSERT_EQ(resume_steps + steps_walked, full_steps) << "levels " << levels << ": a node visited twice or never";
      walked += steps_walked > 0;
    }
    ++rays;
  }
  EXPECT_GT(walked, rays / 2) << "the walks went nowhere";
}

TEST(Bvh4Path, WalkThenResumeIsTheFullTraversal) {
  expect_walk_and_resume_are_the_traversal(load_shipped("voxel-terrain.gltf"), 3);
  expect_walk_and_resume_are_the_traversal(random_soup(3000, 5), 7);
  expect_walk_and_resume_are_the_traversal(coplanar_grid(40, 40), 9);
  // a tiny scene: a root with leaves below, one level to walk
  expect_walk_and_resume_are_the_traversal(triangle_copies(3), 11);
}

TEST(Bvh4Path, TopLevelsAreABreadthFirstPrefix) {
  const KdTree kept = build_kdtree(random_soup(20000, 3), {});
  const Bvh4 bvh = build_bvh4(kept.triangles);
  const auto& starts = bvh.top_level_starts;
  ASSERT_EQ(starts.size(), BVH4_TOP_LEVELS + 1) << "20K triangles fill the top levels";
  EXPECT_EQ(starts[0], 0u);
  EXPECT_EQ(starts[1], 1u);
  // every inner child of a node above the last top depth lies at the next depth's range, and no
  // inner node below the top points back into it
  for (std::uint32_t d = 0; d + 1 < BVH4_TOP_LEVELS; ++d)
    for (std::uint32_t i = starts[d]; i < starts[d + 1]; ++i)
      for (const std::uint32_t c : {bvh.nodes[i].child.x, bvh.nodes[i].child.y, bvh.nodes[i].child.z, bvh.nodes[i].child.w})
        if (!bvh4_is_leaf(c)) {
          EXPECT_GE(c, starts[d + 1]);
          EXPECT_LT(c, d + 2 < starts.size() ? starts[d + 2] : bvh.nodes.size());
        }
  for (std::size_t i = starts.back(); i < bvh.nodes.size(); ++i)
    for (const std::uint32_t c : {bvh.nodes[i].child.x, bvh.nodes[i].child.y, bvh.nodes[i].child.z, bvh.nodes[i].child.w})
      if (!bvh4_is_leaf(c)) {
        EXPECT_GT(c, i) << "each node before its children";
      }
}

}  // namespace
}  // namespace cohort::test

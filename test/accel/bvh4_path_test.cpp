// bvh4_path_bits (kernels/common/bvh4_path.h), the BVH's partial traversal record: at every level,
// the child whose box the ray enters first among those it enters, checked against slab tests done
// here in double precision; zeros once the walk ends; equal directions from one point, equal bits.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "accel/ray_check.h"
#include "accel/test_meshes.h"
#include "kernels/common/bvh4_path.h"
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

}  // namespace
}  // namespace cohort::test

// A KD-tree sized to a memory budget: the default build gives the fastest tree; when its nodes,
// leaf lists and triangles do not fit, the compact termination (KdBuildOptions::compact: about
// 0.74x the bytes, 0.94x the speed on the H200), and if that does not fit either, the compact tree
// with the depth limit lowered to the deepest that fits. The
// build is deterministic and the limit only cuts the recursion, so the tree of a lower limit is the
// same tree cut off (fewer nodes, fewer references): the bytes grow with the limit, and a binary
// search over it needs a few builds, each cheaper than the first.
#include <fmt/format.h>

#include "runtime/accel/kdtree/subtree.h"
#include "runtime/util/error.h"

namespace cohort {

KdTree build_kdtree_within(std::span<const glm::vec3> positions, const KdBuildOptions& options,
                           std::size_t max_bytes) {
  KdTree tree = build_kdtree(positions, options);
  if (tree.stats.bytes <= max_bytes) return tree;
  double seconds = tree.stats.build_seconds;
  KdBuildOptions compact = options;
  compact.compact = true;
  if (!options.compact) {
    tree = build_kdtree(positions, compact);
    seconds += tree.stats.build_seconds;
    if (tree.stats.bytes <= max_bytes) {
      tree.stats.build_seconds = seconds;
      return tree;
    }
  }
  int fits = -1;  // deepest limit known to fit
  KdTree best;
  int lo = 0, hi = kd::effective_max_depth(options, tree.triangles.size()) - 1;
  while (lo <= hi) {
    const int depth = lo + (hi - lo) / 2;
    KdBuildOptions shallower = compact;
    shallower.max_depth = depth;
    KdTree candidate = build_kdtree(positions, shallower);
    seconds += candidate.stats.build_seconds;
    if (candidate.stats.bytes <= max_bytes) {
      fits = depth;
      best = std::move(candidate);
      lo = depth + 1;
    } else {
      hi = depth - 1;
    }
  }
  if (fits < 0) {
    throw InputError(fmt::format(
        "the KD-tree needs at least {:.2f} MiB (one leaf over {} triangles); the budget is {:.2f} MiB",
        static_cast<double>(8 + tree.triangles.size() * (sizeof(Triangle) + 4)) / 1048576.0,
        tree.triangles.size(), static_cast<double>(max_bytes) / 1048576.0));
  }
  best.stats.build_seconds = seconds;
  return best;
}

}  // namespace cohort

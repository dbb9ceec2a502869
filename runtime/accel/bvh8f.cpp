// build_bvh8f: the binary BVH of runtime/accel/binary_bvh.h collapsed into 8-wide nodes with float
// planes, depth first (runtime/accel/wide_collapse.h, the 4-wide BVH's collapse at width 8).
#include "runtime/accel/bvh8f.h"

#include <fmt/format.h>

#include <chrono>

#include "kernels/common/accel/bvh8f_traverse.h"
#include "runtime/accel/binary_bvh.h"
#include "runtime/accel/wide_collapse.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

constexpr std::uint32_t kMaxLeaf = 4;  // triangles, as the 4-wide BVH's leaves
static_assert(binary_bvh::kMaxDepth <= BVH4_MAX_DEPTH, "the traversal stack must hold the deepest tree");

}  // namespace

Bvh8f build_bvh8f(std::span<const Triangle> triangles) {
  const auto start = std::chrono::steady_clock::now();
  if (triangles.empty()) throw InputError("a BVH needs at least one triangle");
  if (triangles.size() > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene has {} triangles; the 8-wide BVH (--tree bvh8f) takes at most {}: use "
                                 "--tree deep or compact",
                                 triangles.size(), BVH4_LEAF_FIRST_MAX));
  const binary_bvh::ReferenceChunks references = binary_bvh::make_references(triangles);
  if (references.size > BVH4_LEAF_FIRST_MAX)
    throw InputError(fmt::format("the scene's {} triangles make {} BVH references; the 8-wide BVH (--tree bvh8f) "
                                 "takes at most {}: use --tree deep or compact",
                                 triangles.size(), references.size, BVH4_LEAF_FIRST_MAX));
  const binary_bvh::Tree binary = binary_bvh::build(references, kMaxLeaf);
  Bvh8f bvh;
  wide_collapse::Collapser<Bvh8fNode, 8> collapser{binary, binary.pad()};
  const auto sums = collapser.collapse(bvh.nodes);
  bvh.leaf_vertices.resize(binary.size);
  binary_bvh::parallel_chunks(binary.size, [&](std::size_t i) {
    const std::uint32_t tri = binary.triangle_of(i);
    bvh.leaf_vertices[i] = triangles[tri];
    bvh.leaf_vertices[i].v0.w = co_as_float(tri);
  });
  bvh.stats.node_count = bvh.nodes.size();
  bvh.stats.references = references.size;
  bvh.stats.leaf_count = sums.leaves;
  bvh.stats.depth = sums.depth;
  bvh.stats.average_leaf_triangles = double(references.size) / double(bvh.stats.leaf_count);
  const float root_area = binary.nodes[0].box().area();
  bvh.stats.sah_cost = root_area > 0 ? sums.sah / root_area : 0.0;
  bvh.stats.bytes = bvh.nodes.size() * sizeof(Bvh8fNode) + bvh.leaf_vertices.size() * sizeof(Triangle);
  bvh.stats.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return bvh;
}

}  // namespace cohort

// build_kdtree: drop the triangles no ray can hit reliably, build, flatten, measure.
#include "runtime/accel/kdtree.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "runtime/accel/kdtree_internal.h"

namespace cohort {
namespace {

bool is_finite(const glm::vec3& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
}

// Zero area in double precision: the edges are exact differences of floats there, so a triangle
// with collinear float vertices along an axis-aligned line (or repeated vertices) is caught
// exactly.
bool has_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
  return n.x != 0.0 || n.y != 0.0 || n.z != 0.0;
}

co_float4 to_float4(const glm::vec3& p) { return {p.x, p.y, p.z, 0.f}; }

// Keeps the good triangles in input order; returns how many were dropped.
std::size_t keep_good_triangles(std::span<const glm::vec3> positions, KdTree& tree) {
  const std::size_t input = positions.size() / 3;
  for (std::size_t i = 0; i < input; ++i) {
    const glm::vec3& a = positions[3 * i];
    const glm::vec3& b = positions[3 * i + 1];
    const glm::vec3& c = positions[3 * i + 2];
    if (!is_finite(a) || !is_finite(b) || !is_finite(c) || !has_area(a, b, c)) continue;
    tree.triangles.push_back({to_float4(a), to_float4(b), to_float4(c)});
    tree.source_index.push_back(static_cast<std::uint32_t>(i));
    tree.bounds.extend(a);
    tree.bounds.extend(b);
    tree.bounds.extend(c);
  }
  return input - tree.triangles.size();
}

}  // namespace

KdTree build_kdtree(std::span<const glm::vec3> positions, const KdBuildOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  // Triangles are named by 30-bit node-local indices in the builder and 32-bit source indices.
  if (positions.size() / 3 > KD_MAX_INDEX) {
    throw std::length_error(fmt::format("KD-tree input has {} triangles; at most {} are supported",
                                        positions.size() / 3, KD_MAX_INDEX));
  }
  KdTree tree;
  tree.stats.dropped_triangles = keep_good_triangles(positions, tree);
  kd::flatten(kd::build_subtree(tree.triangles, tree.bounds, options), tree);
  kd::compute_stats(tree, options);
  tree.stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

}  // namespace cohort

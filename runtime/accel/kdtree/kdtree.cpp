// build_kdtree: drop the triangles no ray can hit reliably, build, flatten, measure.
#include "runtime/accel/kdtree/kdtree.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "runtime/accel/kdtree/subtree.h"

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
bool is_good(std::span<const glm::vec3> positions, std::size_t i) {
  const glm::vec3& a = positions[3 * i];
  const glm::vec3& b = positions[3 * i + 1];
  const glm::vec3& c = positions[3 * i + 2];
  return is_finite(a) && is_finite(b) && is_finite(c) && has_area(a, b, c);
}

constexpr std::size_t kTriangleChunk = 65536;  // input triangles per task

// In parallel over fixed chunks: which triangles are good and each chunk's count and bounds, then
// the kept triangles written at their chunk's prefix offset. The chunk bounds are joined in chunk
// order, so the result is the serial one (the first of equal extremes kept) for any thread count.
std::size_t keep_good_triangles(std::span<const glm::vec3> positions, KdTree& tree) {
  const std::size_t input = positions.size() / 3;
  const std::size_t chunks = (input + kTriangleChunk - 1) / kTriangleChunk;
  std::vector<std::uint8_t> good(input);
  std::vector<std::size_t> kept(chunks + 1, 0);
  std::vector<Bounds> bounds(chunks);
  // Sized for every input triangle (fewer are kept only from bad input), uninitialised: the second
  // pass writes them on every core, then they are shrunk without reallocating.
  tree.triangles.resize(input);
  tree.source_index.resize(input);
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    for (std::size_t i = k * kTriangleChunk; i < std::min(input, (k + 1) * kTriangleChunk); ++i) {
      good[i] = is_good(positions, i);
      if (!good[i]) continue;
      ++kept[k + 1];
      for (int v = 0; v < 3; ++v) bounds[k].extend(positions[3 * i + v]);
    }
  });
  for (std::size_t k = 0; k < chunks; ++k) {
    kept[k + 1] += kept[k];
    tree.bounds.extend(bounds[k]);
  }
  tbb::parallel_for(std::size_t{0}, chunks, [&](std::size_t k) {
    std::size_t out = kept[k];
    for (std::size_t i = k * kTriangleChunk; i < std::min(input, (k + 1) * kTriangleChunk); ++i) {
      if (!good[i]) continue;
      tree.triangles[out] = {to_float4(positions[3 * i]), to_float4(positions[3 * i + 1]),
                             to_float4(positions[3 * i + 2])};
      tree.source_index[out++] = static_cast<std::uint32_t>(i);
    }
  });
  tree.triangles.resize(kept[chunks]);
  tree.source_index.resize(kept[chunks]);
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
  const kd::Subtree subtree = kd::build_subtree(tree.triangles, tree.bounds, options);
  kd::flatten(subtree, tree);
  kd::compute_stats(subtree, tree, options);
  tree.stats.compact = options.compact;
  tree.stats.build_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return tree;
}

}  // namespace cohort

// Straggler rays (docs/design.md, "Straggler rays"): a ray the traversal walks through cells it
// never enters. The bound: a front-to-back traversal visits only nodes whose cell the ray segment
// touches, so the number of such nodes (counted on the host in double precision, closed boxes
// widened by rounding tolerance) bounds what any correct traversal may visit.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "accel/ray_check.h"

namespace cohort::test {

// Nodes whose cell the segment [tmin, tmax] of the ray touches, counted by a recursive walk.
std::uint32_t nodes_touched(const KdTree& tree, const TestRay& ray, float tmin, float tmax);

// Rays built to find stragglers: axis-parallel and in-plane directions with components exactly 0
// and -0, from random points, points exactly on split planes, on the scene box's faces, on
// triangle vertices and edges; and rays leaving triangles (origin on the surface, cosine-sampled
// directions with u2 = 0 and other exact values, as the path tracer draws them).
std::vector<TestRay> straggler_rays(const KdTree& tree, std::size_t count, std::uint32_t seed);

struct StragglerCheck {
  std::size_t rays = 0;
  std::uint32_t max_visited = 0;
  std::uint32_t p9999_visited = 0;        // 99.99th percentile of nodes visited
  std::size_t over_bound = 0;             // rays that visited more nodes than their segment touches
  std::vector<std::string> worst;         // the worst rays in hex floats, to replay on the host
};

// Visits per ray (`visited[i]` from any traversal of ray i on (0, inf), closest hit) against
// nodes_touched. A traversal that ends at its closest hit visits fewer; never more.
StragglerCheck check_stragglers(const KdTree& tree, std::span<const TestRay> rays,
                                std::span<const std::uint32_t> visited);

// kd_trace_steps on the host (closest hit on (0, inf)) for every ray; the hits go to `hits` when given.
std::vector<std::uint32_t> host_visits(const KdTree& tree, std::span<const TestRay> rays,
                                       std::vector<HitOut>* hits = nullptr);

// "org (x, y, z) dir (x, y, z)" in C99 hex floats (%a): exact, so the ray replays bit for bit.
std::string hex_ray(const TestRay& ray);

}  // namespace cohort::test

#include "accel/straggler_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include <tbb/parallel_for.h>

#include "kernels/common/core/sampling.h"

namespace cohort::test {
namespace {

struct Cell {
  glm::dvec3 lo, hi;
};

// Closed slab test in double precision. A zero direction component (either sign) keeps the ray in
// the slab exactly when the origin lies in it, boundaries included.
bool segment_touches(const Cell& c, const glm::dvec3& o, const glm::dvec3& d, double tmin, double tmax) {
  double t0 = tmin, t1 = tmax;
  for (int a = 0; a < 3; ++a) {
    // the traversal widens its intervals by a few ulps of t; a relative 1e-5 covers that
    const double tol = 1e-5 * (std::abs(c.hi[a] - c.lo[a]) + std::abs(c.lo[a]) + std::abs(c.hi[a]));
    const double lo = c.lo[a] - tol, hi = c.hi[a] + tol;
    if (d[a] == 0.0) {
      if (o[a] < lo || o[a] > hi) return false;
      continue;
    }
    double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return t0 <= t1 * (1 + 1e-5) + 1e-30;
}

std::uint32_t count_touched(const KdTree& tree, std::uint32_t index, const Cell& cell, const glm::dvec3& o,
                            const glm::dvec3& d, double tmin, double tmax) {
  if (!segment_touches(cell, o, d, tmin, tmax)) return 0;
  const KdNode node = tree.nodes[index];
  if (kd_is_leaf(node)) return 1;
  const std::uint32_t axis = kd_axis(node);
  const double split = co_as_float(node.word1);
  Cell below = cell, above = cell;
  below.hi[axis] = split;
  above.lo[axis] = split;
  return 1 + count_touched(tree, kd_left_child(node), below, o, d, tmin, tmax) +
         count_touched(tree, kd_left_child(node) + 1, above, o, d, tmin, tmax);
}

// Exactly the float the renderer gets for a direction component that should be 0: +0 or -0.
glm::vec3 with_signed_zeros(glm::vec3 v, std::uint32_t pattern) {
  for (int a = 0; a < 3; ++a)
    if (v[a] == 0.f) v[a] = (pattern >> a) & 1u ? -0.f : 0.f;
  return v;
}

}  // namespace

std::uint32_t nodes_touched(const KdTree& tree, const TestRay& ray, float tmin, float tmax) {
  const Cell root{glm::dvec3(tree.bounds.lo), glm::dvec3(tree.bounds.hi)};
  return count_touched(tree, 0, root, glm::dvec3(ray.org), glm::dvec3(ray.dir), tmin, tmax);
}

std::vector<TestRay> straggler_rays(const KdTree& tree, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  const glm::vec3 lo = tree.bounds.lo, hi = tree.bounds.hi;
  auto inside = [&] { return lo + (hi - lo) * glm::vec3(unit(rng), unit(rng), unit(rng)); };
  std::vector<float> splits[3];
  for (const KdNode& n : tree.nodes)
    if (!kd_is_leaf(n)) splits[kd_axis(n)].push_back(co_as_float(n.word1));
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  auto vertex = [&](std::uint32_t tri, int k) {
    const Triangle& t = tree.triangles[tri];
    const co_float4 v = k == 0 ? t.v0 : k == 1 ? t.v1 : t.v2;
    return glm::vec3(v.x, v.y, v.z);
  };
  // origins of six kinds: random, on a split plane, on a box face, a vertex, an edge point, a surface
  auto origin = [&](int kind, glm::vec3* normal) {
    glm::vec3 o = inside();
    const int axis = int(pick(3));
    if (kind == 1 && !splits[axis].empty()) o[axis] = splits[axis][pick(splits[axis].size())];
    if (kind == 2) o[axis] = unit(rng) < 0.5f ? lo[axis] : hi[axis];
    if (kind >= 3 && !tree.triangles.empty()) {
      const std::uint32_t tri = std::uint32_t(pick(tree.triangles.size()));
      const glm::vec3 a = vertex(tri, 0), b = vertex(tri, 1), c = vertex(tri, 2);
      float u = unit(rng), v = unit(rng);
      if (u + v > 1.f) u = 1.f - u, v = 1.f - v;
      if (kind == 3) o = vertex(tri, int(pick(3)));
      if (kind == 4) o = a + (b - a) * u;
      if (kind == 5) o = a + (b - a) * u + (c - a) * v;
      const glm::vec3 n = glm::cross(b - a, c - a);
      if (normal && glm::dot(n, n) > 0) *normal = glm::normalize(n);
    }
    return o;
  };
  // exact values of u2 that put sin or cos of 2 pi u2 at (or within rounding of) 0
  const float exact_u2[] = {0.f, 0.25f, 0.5f, 0.75f};
  std::vector<TestRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    const int kind = int(rays.size() % 6);
    glm::vec3 n(0.f);
    const glm::vec3 o = origin(kind, &n);
    glm::vec3 d;
    const std::uint32_t shape = std::uint32_t(rays.size() / 6 % 3);
    if (kind == 5 && n != glm::vec3(0.f)) {
      // leaving the surface as the path tracer does (sample_cosine_hemisphere), either side
      const co_vec3 s = sample_cosine_hemisphere(v3(n.x, n.y, n.z), unit(rng), exact_u2[pick(4)]);
      d = glm::vec3(s.x, s.y, s.z) * (unit(rng) < 0.5f ? 1.f : -1.f);
    } else if (shape == 0) {
      d = glm::vec3(0.f);  // along an axis
      d[pick(3)] = unit(rng) < 0.5f ? 1.f : -1.f;
    } else if (shape == 1) {
      d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f);  // in a coordinate plane
      d[pick(3)] = 0.f;
    } else {
      d = glm::normalize(glm::vec3(unit(rng), unit(rng), unit(rng)) - 0.5f);  // general
    }
    if (!(glm::dot(d, d) > 0.f)) continue;
    rays.push_back({o, with_signed_zeros(d, std::uint32_t(pick(8)))});
  }
  return rays;
}

std::vector<std::uint32_t> host_visits(const KdTree& tree, std::span<const TestRay> rays,
                                       std::vector<HitOut>* hits) {
  const KdTreeView view = view_of(tree);
  std::vector<std::uint32_t> visited(rays.size());
  if (hits) hits->resize(rays.size());
  tbb::parallel_for(std::size_t(0), rays.size(), [&](std::size_t i) {
    const TestRay& r = rays[i];
    const HitOut hit = kd_trace_steps(&view, v3(r.org.x, r.org.y, r.org.z), v3(r.dir.x, r.dir.y, r.dir.z), 0.f,
                                      INFINITY, 0, &visited[i]);
    if (hits) (*hits)[i] = hit;
  });
  return visited;
}

std::string hex_ray(const TestRay& r) {
  return fmt::format("org ({:a}, {:a}, {:a}) dir ({:a}, {:a}, {:a})", r.org.x, r.org.y, r.org.z, r.dir.x, r.dir.y,
                     r.dir.z);
}

StragglerCheck check_stragglers(const KdTree& tree, std::span<const TestRay> rays,
                                std::span<const std::uint32_t> visited) {
  StragglerCheck out;
  out.rays = rays.size();
  std::vector<std::uint32_t> bound(rays.size());
  tbb::parallel_for(std::size_t(0), rays.size(),
                    [&](std::size_t i) { bound[i] = nodes_touched(tree, rays[i], 0.f, INFINITY); });
  std::vector<std::size_t> order(rays.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return visited[a] > visited[b]; });
  if (!order.empty()) {
    out.max_visited = visited[order.front()];
    out.p9999_visited = visited[order[rays.size() / 10000]];
  }
  for (std::size_t i = 0; i < rays.size(); ++i) out.over_bound += visited[i] > bound[i];
  for (std::size_t k = 0; k < std::min<std::size_t>(5, order.size()); ++k) {
    const std::size_t i = order[k];
    out.worst.push_back(fmt::format("{} nodes (bound {}): {}", visited[i], bound[i], hex_ray(rays[i])));
  }
  return out;
}

}  // namespace cohort::test

#include "accel/ray_check.h"

#include "runtime/accel/host_traversal.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <tuple>

namespace cohort::test {
namespace {

constexpr std::size_t kMaxExamples = 8;
constexpr std::size_t kRecheckEvery = 50;

co_vec3 to_co(const glm::vec3& p) { return v3(p.x, p.y, p.z); }

glm::vec3 random_direction(std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(-1.f, 1.f);
  for (;;) {
    const glm::vec3 d(unit(rng), unit(rng), unit(rng));
    const float len2 = glm::dot(d, d);
    if (len2 > 1e-4f && len2 <= 1.f) return d / std::sqrt(len2);
  }
}

glm::vec3 random_point(const Bounds& box, std::mt19937& rng) {
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  return box.lo + glm::vec3(unit(rng), unit(rng), unit(rng)) * box.extent();
}

enum class Outcome : std::uint8_t { kAgree, kTie, kNearTie, kMismatch };

struct RayResult {
  Outcome closest = Outcome::kAgree;
  bool occlusion_ok = true;
  bool culling_ok = true;
  bool hit = false;
  std::string detail;
};

float single_triangle_t(const KdTree& tree, const TestRay& ray, std::uint32_t tri) {
  const WatertightRay wr = watertight_ray(to_co(ray.org), to_co(ray.dir));
  const Triangle& t = tree.triangles[tri];
  float th = kInf, u = 0, v = 0;
  if (!intersect_triangle(&wr, v3_from4(t.v0), v3_from4(t.v1), v3_from4(t.v2), 0.f, kInf, &th, &u,
                          &v)) {
    return kInf;
  }
  return th;
}

bool close(float a, float b) { return std::abs(a - b) <= 1e-5f * std::abs(b); }

Outcome compare_closest(const KdTree& tree, const TestRay& ray, const HitOut& expected,
                        const HitOut& got, TieRule rule) {
  if ((expected.triangle == HIT_NONE) != (got.triangle == HIT_NONE)) return Outcome::kMismatch;
  if (expected.triangle == HIT_NONE) return Outcome::kAgree;
  if (rule == TieRule::kIdentical)
    return got.triangle == expected.triangle && got.t == expected.t ? Outcome::kAgree : Outcome::kMismatch;
  if (!close(got.t, expected.t)) return Outcome::kMismatch;
  if (got.triangle == expected.triangle) return Outcome::kAgree;
  // A different triangle is fine at a genuine tie: the same t, bit for bit.
  const float t = single_triangle_t(tree, ray, got.triangle);
  if (t == expected.t) return Outcome::kTie;
  return rule == TieRule::kNear && close(t, expected.t) ? Outcome::kNearTie : Outcome::kMismatch;
}

HitOut trace(const KdTreeView& view, const TestRay& ray, float tmax, bool any_hit,
             Traversal traversal) {
  if (traversal == Traversal::kTolerant) return trace_tolerant(view, ray, 0.f, tmax, any_hit);
  return kd_trace(&view, to_co(ray.org), to_co(ray.dir), 0.f, tmax, any_hit ? 1 : 0);
}

bool occluded(const KdTreeView& view, const TestRay& ray, float tmax, Traversal traversal) {
  return trace(view, ray, tmax, true, traversal).triangle != HIT_NONE;
}

RayResult check_ray(const KdTree& tree, const KdTreeView& view, const SphereCulledBruteForce& brute,
                    const TestRay& ray, std::size_t index, const CheckOptions& options) {
  RayResult r;
  const RecheckedHit rechecked = brute.closest_rechecked(ray, index);
  const HitOut expected = rechecked.hit;
  r.culling_ok = rechecked.culling_ok;
  const HitOut got = trace(view, ray, kInf, false, options.traversal);
  r.hit = expected.triangle != HIT_NONE;
  r.closest = compare_closest(tree, ray, expected, got, options.ties);
  // Any hit in (0, tmax) exists exactly when the closest hit lies below tmax.
  if (r.hit) {
    r.occlusion_ok = !occluded(view, ray, 0.5f * expected.t, options.traversal) &&
                     occluded(view, ray, 1.5f * expected.t, options.traversal);
  } else {
    r.occlusion_ok = !occluded(view, ray, kInf, options.traversal);
  }
  if (r.closest == Outcome::kMismatch || !r.occlusion_ok || !r.culling_ok) {
    r.detail = fmt::format(
        "org ({}, {}, {}) dir ({}, {}, {}): brute tri {} t {}; tree tri {} t {}{}{}", ray.org.x,
        ray.org.y, ray.org.z, ray.dir.x, ray.dir.y, ray.dir.z, expected.triangle, expected.t,
        got.triangle, got.t, r.occlusion_ok ? "" : " (any-hit disagrees)",
        r.culling_ok ? "" : " (sphere culling disagrees with plain brute force)");
  }
  return r;
}

}  // namespace

std::vector<TestRay> make_rays(const Bounds& box, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  const float radius = 0.75f * box.diagonal() + 1e-3f;
  std::vector<TestRay> rays(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (i % 2 == 0) {
      rays[i] = {random_point(box, rng), random_direction(rng)};
    } else {
      const glm::vec3 org = box.center() + radius * random_direction(rng);
      rays[i] = {org, glm::normalize(random_point(box, rng) - org)};
    }
  }
  return rays;
}

std::vector<TestRay> make_feature_rays(const KdTree& tree, std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Bounds around = tree.bounds;
  const glm::vec3 pad(0.5f * tree.bounds.diagonal());
  around.lo -= pad;
  around.hi += pad;
  std::uniform_int_distribution<std::size_t> pick(0, tree.triangles.size() - 1);
  std::uniform_int_distribution<int> feature(0, 5);
  std::vector<TestRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    const Triangle& t = tree.triangles[pick(rng)];
    const glm::vec3 v[3] = {
        {t.v0.x, t.v0.y, t.v0.z}, {t.v1.x, t.v1.y, t.v1.z}, {t.v2.x, t.v2.y, t.v2.z}};
    const int f = feature(rng);
    const glm::vec3 target = f < 3 ? v[f] : 0.5f * (v[f - 3] + v[(f - 2) % 3]);
    const glm::vec3 org = random_point(around, rng);
    if (glm::length(target - org) > 1e-3f * tree.bounds.diagonal()) {
      rays.push_back({org, glm::normalize(target - org)});
    }
  }
  return rays;
}

std::vector<TestRay> make_split_plane_rays(const KdTree& tree, std::size_t count, std::uint32_t seed) {
  struct Plane {
    std::uint32_t axis;
    float split;
    std::vector<std::uint32_t> flat;  // triangles lying in it
    auto operator<=>(const Plane& o) const { return std::tie(axis, split) <=> std::tie(o.axis, o.split); }
    bool operator==(const Plane& o) const { return axis == o.axis && split == o.split; }
  };
  std::vector<Plane> planes;
  for (const KdNode& n : tree.nodes)
    if (!kd_is_leaf(n)) planes.push_back({kd_axis(n), co_as_float(n.word1), {}});
  std::sort(planes.begin(), planes.end());
  planes.erase(std::unique(planes.begin(), planes.end()), planes.end());
  if (planes.empty()) return {};
  for (std::uint32_t i = 0; i < tree.triangles.size(); ++i) {
    const Triangle& t = tree.triangles[i];
    for (std::uint32_t axis = 0; axis < 3; ++axis) {
      const float c = (&t.v0.x)[axis];
      if ((&t.v1.x)[axis] != c || (&t.v2.x)[axis] != c) continue;
      const auto it = std::lower_bound(planes.begin(), planes.end(), Plane{axis, c, {}});
      if (it != planes.end() && it->axis == axis && it->split == c) it->flat.push_back(i);
    }
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.f, 1.f);
  std::uniform_int_distribution<std::size_t> pick_plane(0, planes.size() - 1);
  std::normal_distribution<float> gauss;
  std::vector<TestRay> rays;
  rays.reserve(count);
  while (rays.size() < count) {
    const Plane& plane = planes[pick_plane(rng)];
    glm::vec3 org;
    if (!plane.flat.empty() && unit(rng) < 0.75f) {
      const Triangle& t = tree.triangles[plane.flat[std::size_t(unit(rng) * plane.flat.size()) % plane.flat.size()]];
      const glm::vec3 v[3] = {{t.v0.x, t.v0.y, t.v0.z}, {t.v1.x, t.v1.y, t.v1.z}, {t.v2.x, t.v2.y, t.v2.z}};
      const float where = unit(rng), s = unit(rng);
      const int corner = int(unit(rng) * 3.f) % 3;
      if (where < 0.3f) org = v[corner];  // a vertex: a concave corner in voxel geometry
      else if (where < 0.7f) org = glm::mix(v[corner], v[(corner + 1) % 3], s);  // an edge
      else {
        const float a = unit(rng), b = unit(rng) * (1.f - a);
        org = v[0] + a * (v[1] - v[0]) + b * (v[2] - v[0]);
      }
    } else {
      org = random_point(tree.bounds, rng);
    }
    org[plane.axis] = plane.split;  // exactly in the plane, whatever the interpolation rounded
    glm::vec3 dir(gauss(rng), gauss(rng), gauss(rng));
    const float way = unit(rng);
    dir[plane.axis] = way < 0.1f ? 0.f : (way < 0.55f ? -std::abs(dir[plane.axis]) : std::abs(dir[plane.axis]));
    if (glm::length(dir) < 1e-3f) continue;
    rays.push_back({org, glm::normalize(dir)});
  }
  return rays;
}

HitOut trace_tolerant(const KdTreeView& view, const TestRay& ray, float tmin, float tmax,
                      bool any_hit) {
  struct Entry {
    std::uint32_t node;
    float t0, t1;
  };
  HitOut hit{tmax, 0.f, 0.f, HIT_NONE};
  const co_vec3 org = to_co(ray.org), dir = to_co(ray.dir);
  const co_vec3 inv_dir = v3(1.f / dir.x, 1.f / dir.y, 1.f / dir.z);
  const co_vec3 pad = v3_scale(v3_add(v3_abs(view.lo), v3_abs(view.hi)), 1e-5f);
  float t0 = tmin, t1 = tmax;
  if (!intersect_box(org, inv_dir, v3_sub(view.lo, pad), v3_add(view.hi, pad), &t0, &t1))
    return hit;
  const WatertightRay wr = watertight_ray(org, dir);
  std::vector<Entry> stack{{0u, t0, t1}};
  while (!stack.empty()) {
    const Entry e = stack.back();
    stack.pop_back();
    const float eps = 1e-5f * std::max(std::abs(e.t0), std::abs(e.t1));
    if (hit.t < e.t0 - eps) continue;
    const KdNode node = view.nodes[e.node];
    if (kd_is_leaf(node)) {
      if (kd_intersect_leaf(&view, node, &wr, tmin, &hit, any_hit)) return hit;
      continue;
    }
    const std::uint32_t axis = kd_axis(node);
    const float split = co_as_float(node.word1), o = v3_get(org, axis);
    const float t_plane = (split - o) * v3_get(inv_dir, axis);
    // eps also covers the rounding of the origin's distance to the plane, for tiny intervals
    const float plane_eps =
        eps + 1e-6f * (std::abs(o) + std::abs(split)) * std::abs(v3_get(inv_dir, axis));
    const bool below_first = o < split || (o == split && v3_get(dir, axis) <= 0.f);
    const std::uint32_t near_child = kd_left_child(node) + (below_first ? 0u : 1u);
    const std::uint32_t far_child = kd_left_child(node) + (below_first ? 1u : 0u);
    // The part of [t0, t1] on each side of the plane, widened by eps. When the origin lies on the
    // plane up to rounding (|t_plane| <= plane_eps) or in it (NaN), either side may hold all of it.
    Entry near_part{near_child, e.t0, e.t1}, far_part{far_child, e.t0, e.t1};
    if (!(std::abs(t_plane) <= plane_eps) && !std::isnan(t_plane)) {
      if (t_plane > 0.f) {
        near_part.t1 = std::min(e.t1, t_plane + plane_eps);
        far_part.t0 = std::max(e.t0, t_plane - plane_eps);
      } else {
        far_part.t0 = kInf;  // the plane is behind the origin: the ray never reaches the far side
      }
    }
    if (far_part.t0 <= far_part.t1) stack.push_back(far_part);
    if (near_part.t0 <= near_part.t1) stack.push_back(near_part);
  }
  return hit;
}

KdTreeView view_of(const KdTree& tree) { return host_view(tree); }

HitOut brute_force(const KdTree& tree, const TestRay& ray, float tmin, float tmax) {
  HitOut hit{tmax, 0.f, 0.f, HIT_NONE};
  const WatertightRay wr = watertight_ray(to_co(ray.org), to_co(ray.dir));
  for (std::uint32_t i = 0; i < tree.triangles.size(); ++i) {
    const Triangle& t = tree.triangles[i];
    float th, u, v;
    if (intersect_triangle(&wr, v3_from4(t.v0), v3_from4(t.v1), v3_from4(t.v2), tmin, hit.t, &th,
                           &u, &v)) {
      hit = {th, u, v, i};
    }
  }
  return hit;
}

SphereCulledBruteForce::SphereCulledBruteForce(const KdTree& tree) : tree_(tree) {
  spheres_.reserve(tree.triangles.size());
  for (const Triangle& t : tree.triangles) {
    const glm::dvec3 a(t.v0.x, t.v0.y, t.v0.z), b(t.v1.x, t.v1.y, t.v1.z),
        c(t.v2.x, t.v2.y, t.v2.z);
    const glm::dvec3 center = (a + b + c) / 3.0;
    const double radius =
        std::sqrt(std::max({glm::dot(a - center, a - center), glm::dot(b - center, b - center),
                            glm::dot(c - center, c - center)}));
    const glm::dvec3 m = glm::abs(center);
    spheres_.push_back({center, 1.01 * radius, std::max({m.x, m.y, m.z})});
  }
}

HitOut SphereCulledBruteForce::trace(const TestRay& ray, float tmin, float tmax) const {
  HitOut hit{tmax, 0.f, 0.f, HIT_NONE};
  const WatertightRay wr = watertight_ray(to_co(ray.org), to_co(ray.dir));
  const glm::dvec3 org(ray.org), dir(ray.dir);
  const double dd = glm::dot(dir, dir);
  const glm::dvec3 o = glm::abs(org);
  const double org_scale = std::max({o.x, o.y, o.z});
  for (std::uint32_t i = 0; i < spheres_.size(); ++i) {
    const Sphere& s = spheres_[i];
    // Distance from the centre to the half-line t >= 0, in double so nothing cancels; the margin
    // covers the float rounding of intersect_triangle (about 1e-7 of the coordinates) many times.
    const glm::dvec3 v = s.center - org;
    const double tc = glm::dot(v, dir);
    const double vv = glm::dot(v, v);
    const double dist2 = tc > 0.0 ? vv - tc * tc / dd : vv;
    const double reach = s.radius + 1e-5 * (s.scale + org_scale);
    if (dist2 > reach * reach) continue;
    const Triangle& t = tree_.triangles[i];
    float th, u, v2;
    if (intersect_triangle(&wr, v3_from4(t.v0), v3_from4(t.v1), v3_from4(t.v2), tmin, hit.t, &th,
                           &u, &v2)) {
      hit = {th, u, v2, i};
    }
  }
  return hit;
}

RecheckedHit SphereCulledBruteForce::closest_rechecked(const TestRay& ray, std::size_t index) const {
  RecheckedHit r{trace(ray, 0.f, kInf)};
  if (index % kRecheckEvery == 0) {
    const HitOut plain = brute_force(tree_, ray, 0.f, kInf);
    r.culling_ok = plain.triangle == r.hit.triangle && plain.t == r.hit.t;
  }
  return r;
}

RayCheck check_against_brute_force(const KdTree& tree, std::span<const TestRay> rays,
                                   CheckOptions options) {
  const KdTreeView view = view_of(tree);
  const SphereCulledBruteForce brute(tree);
  std::vector<RayResult> results(rays.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rays.size(), 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i) {
                        results[i] =
                            check_ray(tree, view, brute, rays[i], i, options);
                      }
                    });
  RayCheck check;
  check.rays = rays.size();
  for (const RayResult& r : results) {
    check.hits += r.hit;
    check.ties += r.closest == Outcome::kTie;
    check.near_ties += r.closest == Outcome::kNearTie;
    check.mismatches += r.closest == Outcome::kMismatch;
    check.occlusion_mismatches += !r.occlusion_ok;
    check.culling_mismatches += !r.culling_ok;
    if (!r.detail.empty() && check.examples.size() < kMaxExamples)
      check.examples.push_back(r.detail);
  }
  return check;
}

}  // namespace cohort::test

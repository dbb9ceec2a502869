// Host traversal (kd_trace, the device code compiled as C++) against a brute-force loop over every
// triangle with the same watertight intersect_triangle.
#pragma once

#include <cstddef>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "kernels/common/accel/kdtree_traverse.h"
#include "runtime/accel/kdtree/kdtree.h"

namespace cohort::test {

inline constexpr float kInf = std::numeric_limits<float>::infinity();

struct TestRay {
  glm::vec3 org;
  glm::vec3 dir;
};

// Half the rays start inside `box` with uniform directions; the other half start on a sphere around
// it and aim at a uniform point inside (for a flat box: a point on the plane).
std::vector<TestRay> make_rays(const Bounds& box, std::size_t count, std::uint32_t seed);

// Rays from random points around the scene aimed exactly at a vertex or an edge midpoint of a
// random triangle: the hits lie on shared edges and vertices, often on split planes.
std::vector<TestRay> make_feature_rays(const KdTree& tree, std::size_t count, std::uint32_t seed);

// Rays whose origin lies exactly in a split plane of the tree (the axis coordinate is the split's
// float): most on a triangle lying flat in that plane (at a vertex, on an edge or inside it), the rest
// anywhere in the plane within the bounds; the direction leaves the plane to the lower side, to the
// upper side, or (one ray in ten) runs in it. A ray that starts on a face it just left, next to a
// flat face that shares the plane (a voxel's concave corner), is the case a traversal that visits
// only the side the ray heads into gets wrong.
std::vector<TestRay> make_split_plane_rays(const KdTree& tree, std::size_t count, std::uint32_t seed);

KdTreeView view_of(const KdTree& tree);

// Every triangle through intersect_triangle, the closest hit on (tmin, tmax): the least t, and of
// equal t the lowest triangle index.
HitOut brute_force(const KdTree& tree, const TestRay& ray, float tmin, float tmax);

// The closest hit on (0, infinity) and, on the rays that were re-checked, whether brute_force agreed.
struct RecheckedHit {
  HitOut hit;
  bool culling_ok = true;
};

// The same answer, faster: a triangle whose generous bounding sphere the ray (a half-line from the
// origin) misses is skipped before intersect_triangle. The margins make it conservative, and
// closest_rechecked re-checks it against brute_force on every 50th ray.
class SphereCulledBruteForce {
 public:
  explicit SphereCulledBruteForce(const KdTree& tree);
  HitOut trace(const TestRay& ray, float tmin, float tmax) const;
  // trace(ray, 0, infinity); where `index` (the ray's place in its batch) is a multiple of 50, also
  // brute_force's closest hit, which must be the same t and triangle.
  RecheckedHit closest_rechecked(const TestRay& ray, std::size_t index) const;

 private:
  struct Sphere {
    glm::dvec3 center;
    double radius;  // already widened by 1%
    double scale;   // largest |coordinate| of the center, for the absolute margin
  };
  const KdTree& tree_;
  std::vector<Sphere> spheres_;
};

struct RayCheck {
  std::size_t rays = 0;
  std::size_t hits = 0;
  std::size_t ties = 0;        // another triangle at exactly the same t
  std::size_t near_ties = 0;   // another triangle within 1e-5 relative (TieRule::kNear only)
  std::size_t mismatches = 0;  // closest hit disagrees
  std::size_t occlusion_mismatches = 0;  // any-hit disagrees
  std::size_t culling_mismatches = 0;  // the sphere-culled brute force disagrees with the plain one
  std::vector<std::string> examples;   // the first few disagreements, for the log
};

// How a different triangle than brute force's may still agree.
enum class TieRule {
  kIdentical,  // never: the traversal's promise (kdtree_traverse.h, KD_TERMINATION_SLACK) is the
               // least (t, triangle index), which is what the brute force finds
  kExact,  // only when its t equals the closest t bit for bit
  kNear,   // when its t is within 1e-5 relative: for rays through shared edges and vertices, where
           // the triangles around the point give t values a few ulps apart and the traversal may
           // stop in the cell it reached first
};

enum class Traversal {
  kDevice,    // kd_trace of kernels/common/accel/kdtree_traverse.h, what the renderer runs
  kTolerant,  // trace_tolerant below
};

struct CheckOptions {
  TieRule ties = TieRule::kIdentical;
  Traversal traversal = Traversal::kDevice;
};

// Closest hit on (0, inf), and any hit on (0, t_closest / 2) and (0, 1.5 t_closest), per ray.
RayCheck check_against_brute_force(const KdTree& tree, std::span<const TestRay> rays,
                                   CheckOptions options = {});

// kd_trace with every cell decision widened by a relative 1e-5: a cell is visited whenever the ray
// may be inside it up to rounding, and cells are never cut off by an earlier hit. It answers "does
// the tree hold every triangle where the ray can meet it" independently of the device traversal's
// rounding at cell boundaries (kd_trace decides near/far from t_plane against an interval computed
// with other arithmetic than the watertight hit, so a hit exactly on a split plane can fall into
// the cell it did not visit).
HitOut trace_tolerant(const KdTreeView& view, const TestRay& ray, float tmin, float tmax,
                      bool any_hit);

}  // namespace cohort::test

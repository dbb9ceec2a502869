// The partitions of the KD build (kdtree_partition.cpp) against a reference that classifies one
// reference at a time: same children, same order, same clipped boxes, and a straddling reference
// whose triangle misses a child cell left out of that child.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "runtime/accel/clip.h"
#include "runtime/accel/kdtree/partition.h"

namespace cohort::test {
namespace {

using kd::Ref;

struct Case {
  std::vector<Triangle> triangles;
  std::vector<Ref> refs;
  Bounds cell;
};

co_float4 point(std::mt19937& rng, float lo, float hi) {
  std::uniform_real_distribution<float> u(lo, hi);
  return {u(rng), u(rng), u(rng), 0.f};
}

// Triangles across the cell [0, 1]^3 (some reaching out of it), each referenced with its bounds
// clipped to the cell. Every seventh reference gets a box stretched to the cell's far x face: its
// triangle may then miss a child cell its box reaches (partition takes boxes as given), so the
// drop of an empty clipped side is exercised. Every eleventh is flat in x at a grid position, so
// planes through flat references come up.
Case make_case(std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Case c;
  c.cell.lo = glm::vec3(0.f);
  c.cell.hi = glm::vec3(1.f);
  for (std::size_t i = 0; c.refs.size() < count; ++i) {
    const co_float4 centre = point(rng, -0.1f, 1.1f);
    const float size = std::uniform_real_distribution<float>(0.01f, 0.6f)(rng);
    Triangle t{};
    co_float4* v[3] = {&t.v0, &t.v1, &t.v2};
    for (co_float4* p : v) {
      const co_float4 d = point(rng, -size, size);
      *p = {centre.x + d.x, centre.y + d.y, centre.z + d.z, 0.f};
    }
    if (i % 11 == 0) {
      const float x = static_cast<float>(rng() % 8) / 8.f;
      for (co_float4* p : v) p->x = x;
    }
    const Bounds box = kd::clip_triangle_bounds(kd::vertex(t.v0), kd::vertex(t.v1),
                                                kd::vertex(t.v2), c.cell);
    if (box.empty()) continue;
    Ref r{box, static_cast<std::uint32_t>(c.triangles.size())};
    if (i % 7 == 0 && box.lo.x != box.hi.x) r.box.hi.x = 1.f;
    c.triangles.push_back(t);
    c.refs.push_back(r);
  }
  return c;
}

// One reference at a time, as kdtree_partition.cpp's header describes the split.
std::array<std::vector<Ref>, 2> reference_split(const Case& c, const kd::SplitPlane& plane) {
  std::array<std::vector<Ref>, 2> out;
  const int a = plane.axis;
  for (const Ref& r : c.refs) {
    const float lo = r.box.lo[a], hi = r.box.hi[a];
    if (lo != hi && lo < plane.pos && hi > plane.pos) {
      const Triangle& t = c.triangles[r.tri];
      const std::array<Bounds, 2> boxes = kd::split_triangle_bounds(
          kd::vertex(t.v0), kd::vertex(t.v1), kd::vertex(t.v2), c.cell, r.box, a, plane.pos);
      for (int side = 0; side < 2; ++side) {
        if (!boxes[side].empty()) out[side].push_back({boxes[side], r.tri});
      }
      continue;
    }
    const bool left = lo == hi ? lo < plane.pos || (lo == plane.pos && plane.planar_left)
                               : lo < plane.pos;
    out[left ? 0 : 1].push_back(r);
  }
  return out;
}

bool same_refs(const Ref* a, const std::vector<Ref>& b, std::size_t count) {
  if (count != b.size()) return false;
  for (std::size_t i = 0; i < count; ++i) {
    if (a[i].tri != b[i].tri || std::memcmp(&a[i].box, &b[i].box, sizeof(Bounds)) != 0) return false;
  }
  return true;
}

std::vector<kd::SplitPlane> planes() {
  std::vector<kd::SplitPlane> out;
  for (int axis = 0; axis < 3; ++axis) {
    for (float pos : {0.25f, 0.5f, 0.6180339f}) {
      for (bool planar_left : {true, false}) {
        kd::SplitPlane p;
        p.axis = axis;
        p.pos = pos;
        p.planar_left = planar_left;
        out.push_back(p);
      }
    }
  }
  return out;
}

TEST(KdPartition, SerialSplitMatchesTheReference) {
  const Case c = make_case(3000, 5);
  std::size_t dropped = 0;
  for (const kd::SplitPlane& plane : planes()) {
    const auto expected = reference_split(c, plane);
    // The node's references sit above another node's, as in the build's stack.
    kd::RefStack stack;
    Ref* below = stack.push(17);
    for (int i = 0; i < 17; ++i) below[i] = c.refs[static_cast<std::size_t>(i)];
    std::copy(c.refs.begin(), c.refs.end(), stack.push(c.refs.size()));
    kd::UninitialisedArray<kd::Straddler> straddling;
    std::size_t clipped = 0;
    const auto counts = kd::partition(stack, 17, 17 + c.refs.size(), c.cell, plane, c.triangles,
                                      straddling, clipped);
    ASSERT_TRUE(same_refs(stack.data() + 17, expected[0], counts[0]))
        << "left child, axis " << plane.axis << " at " << plane.pos;
    ASSERT_TRUE(same_refs(stack.data() + 17 + c.refs.size(), expected[1], counts[1]))
        << "right child, axis " << plane.axis << " at " << plane.pos;
    EXPECT_EQ(stack.size(), 17 + c.refs.size() + counts[1]);
    for (int i = 0; i < 17; ++i) EXPECT_EQ(stack[static_cast<std::size_t>(i)].tri, c.refs[static_cast<std::size_t>(i)].tri);
    EXPECT_GT(clipped, 0u);
    dropped += 2 * clipped + c.refs.size() - clipped - counts[0] - counts[1];
  }
  EXPECT_GT(dropped, 0u) << "no straddling reference missed a child cell: the drop went untested";
}

TEST(KdPartition, ParallelSplitMatchesTheReference) {
  // Above one chunk of the parallel split (32768 references), so chunks are joined.
  const Case c = make_case(70'000, 9);
  for (const kd::SplitPlane& plane : {planes()[0], planes()[7], planes()[14]}) {
    const auto expected = reference_split(c, plane);
    const std::array<kd::RefStack, 2> children = kd::partition_apart(c.refs, c.cell, plane, c.triangles);
    for (int side = 0; side < 2; ++side) {
      ASSERT_TRUE(same_refs(children[side].data(), expected[side], children[side].size()))
          << "child " << side << ", axis " << plane.axis << " at " << plane.pos;
    }
  }
}

}  // namespace
}  // namespace cohort::test

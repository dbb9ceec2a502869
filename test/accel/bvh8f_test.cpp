// The 8-wide BVH with float planes' layout (runtime/accel/bvh8f.h): its structure check, its leaves'
// blocks of four triangles, and the four-triangle test lane for lane against the one-triangle test.
// The checks it shares with the other wide BVHs (every ray's hit bit for bit against the KD-tree's
// and the other trees', the same tree for any thread count, degenerate inputs) run on it in
// wide_bvh_common_test.cpp.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>

#include "accel/test_meshes.h"
#include "accel/tree_check.h"
#include "accel/wide_bvh_check.h"
#include "runtime/accel/binary_bvh.h"

namespace cohort::test {

// The blocks' lanes as entries (entry 4 b + i is lane i of block b), each a copy of its triangle
// with the triangle's index in v0.w, as the 4-wide BVH stores its leaf entries.
std::vector<Triangle> leaf_entries(const Bvh8f& bvh) {
  std::vector<Triangle> entries(bvh.leaf_blocks.size() * 4);
  for (std::size_t b = 0; b < bvh.leaf_blocks.size(); ++b) {
    const Triangle4& q = bvh.leaf_blocks[b];
    for (int i = 0; i < 4; ++i) {
      const auto lane = [i](const co_float4& row) { return (&row.x)[i]; };
      const auto vertex = [&](int v, float w) {
        return co_make_float4(lane(q.v[v][0]), lane(q.v[v][1]), lane(q.v[v][2]), w);
      };
      entries[4 * b + i] = {vertex(0, co_as_float(q.index[i])), vertex(1, 0.0f), vertex(2, 0.0f)};
    }
  }
  return entries;
}

// Walks the tree from the root (with StructureTally's checks): each node in depth-first order (each
// node before its children, a lane's subtree after the lanes before it); leaves of at most four
// triangles, in the lanes of their blocks, the unused lanes copies of the last; unused lanes BVH4_EMPTY at +infinity (all six planes), after the used ones; reserved words zero; no node
// without children.
std::vector<std::string> structure_errors(const Bvh8f& bvh, const KdTree& kept) {
  StructureTally tally(bvh.nodes.size(), leaf_entries(bvh), kept);
  std::vector<std::string>& errors = tally.errors;
  std::uint32_t next_in_order = 0;
  std::function<void(std::uint32_t, int, const float*, const float*)> walk = [&](std::uint32_t index, int depth,
                                                                                  const float* plo, const float* phi) {
    if (!tally.reach(index, depth)) return;
    if (index != next_in_order++) errors.push_back(fmt::format("node {} where a depth-first walk has {}", index, next_in_order - 1));
    const Bvh8fNode& n = bvh.nodes[index];
    if (std::any_of(std::begin(n.reserved), std::end(n.reserved), [](std::uint32_t r) { return r != 0; }))
      errors.push_back(fmt::format("node {}: reserved words not zero", index));
    int used = 0;
    for (int lane = 0; lane < 8; ++lane) {
      const std::uint32_t ref = n.child[lane];
      const float lo[3] = {n.planes[0][lane], n.planes[2][lane], n.planes[4][lane]};
      const float hi[3] = {n.planes[1][lane], n.planes[3][lane], n.planes[5][lane]};
      if (ref == BVH4_EMPTY) {
        // the packet walk stops at a node's first empty lane (bvh8f_trace_packet)
        if (lane + 1 < 8 && n.child[lane + 1] != BVH4_EMPTY)
          errors.push_back(fmt::format("node {} lane {}: an empty lane before a used one", index, lane));
        for (int a = 0; a < 3; ++a)
          if (lo[a] != INFINITY || hi[a] != INFINITY)
            errors.push_back(fmt::format("node {} lane {}: empty lane with a box", index, lane));
        continue;
      }
      ++used;
      tally.box(index, lane, lo, hi, plo, phi);
      if (bvh4_is_leaf(ref)) {
        // a leaf's entries run through its blocks' lanes; the rest of its last block repeats its last
        const std::uint32_t first = 4 * bvh4_leaf_first(ref), count = bvh4_leaf_count(ref);
        tally.leaf(first, count, 4, lo, hi);
        for (std::uint32_t e = first + count; e < first + 4 * bvh8f_leaf_blocks(count); ++e)
          tally.padding(e, first + count - 1);
      } else
        walk(ref, depth + 1, lo, hi);
    }
    if (used == 0) errors.push_back(fmt::format("node {} has no children", index));
  };
  walk(0, 1, nullptr, nullptr);
  return tally.finish(bvh.stats, BVH4_MAX_DEPTH);
}

namespace {

// Leaves that cost one test per block of four (binary_bvh::LeafShape) hold about four triangles:
// far fewer leaves and nodes than the 4-wide BVH's, which tests one triangle after another.
TEST(Bvh8f, LeavesOfFourTrianglesInFewerNodes) {
  const KdTree kept = kept_triangles(random_soup(20'000, 5));
  const Bvh8f wide = build_bvh8f(kept.triangles);
  const Bvh4 narrow = build_bvh4(kept.triangles);
  // the same references before the build; spatial splits add at most a quarter, where each tree's
  // SAH prefers them
  const std::size_t before = binary_bvh::make_references(kept.triangles).size;
  for (const std::size_t references : {wide.stats.references, narrow.stats.references}) {
    EXPECT_GE(references, before);
    EXPECT_LE(references, before + before / 4);
  }
  EXPECT_GT(wide.stats.average_leaf_triangles, 3.0);  // 3.8 on this soup, against 1.5
  EXPECT_LT(wide.stats.leaf_count, narrow.stats.leaf_count / 2);
  EXPECT_LT(wide.stats.node_count, narrow.stats.node_count / 3);
  EXPECT_LT(wide.stats.depth, narrow.stats.depth);
  EXPECT_EQ(wide.leaf_blocks.size(), wide.stats.leaf_count);  // leaves of at most four: one block each
}

// intersect_triangle4 against intersect_triangle lane by lane, bit for bit: the hit mask, and t, u
// and v of every lane hit, over rays at random triangles, through their vertices and edges (where
// the watertight test decides on zeros), grazing ones, degenerate triangles (det 0) and limits.
TEST(Bvh8f, FourTriangleTestIsTheOneTriangleTestLaneForLane) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u01(-1.0f, 1.0f);
  const auto point = [&] { return v3(u01(rng), u01(rng), u01(rng)); };
  std::size_t lanes_hit = 0, checked = 0;
  for (int trial = 0; trial < 20'000; ++trial) {
    co_vec3 p[4][3];
    for (auto& tri : p)
      for (co_vec3& v : tri) v = point();
    if (trial % 7 == 0) p[1][2] = v3_add(p[1][0], v3_scale(v3_sub(p[1][1], p[1][0]), 0.5f));  // det 0: collinear
    if (trial % 11 == 0) p[2][1] = p[2][0];                                                    // a repeated vertex
    Triangle4 q{};
    for (int i = 0; i < 4; ++i) {
      for (int v = 0; v < 3; ++v) {
        (&q.v[v][0].x)[i] = p[i][v].x;
        (&q.v[v][1].x)[i] = p[i][v].y;
        (&q.v[v][2].x)[i] = p[i][v].z;
      }
    }
    co_vec3 org = v3_scale(point(), 3.0f);
    const int target = trial % 4;
    if (trial % 17 == 0) {  // signed zeros: a vertex at x = -0 seen from an origin at x = +0
      org.x = 0.0f;
      p[target][0].x = -0.0f;
      (&q.v[0][0].x)[target] = -0.0f;
    }
    co_vec3 at = p[target][0];  // a vertex, an edge's midpoint, or a point inside
    if (trial % 3 == 1) at = v3_scale(v3_add(p[target][0], p[target][1]), 0.5f);
    if (trial % 3 == 2) at = v3_scale(v3_add(v3_add(p[target][0], p[target][1]), p[target][2]), 1.0f / 3.0f);
    const co_vec3 dir = trial % 13 == 0 ? v3(0.0f, 0.0f, 1.0f) : v3_sub(at, org);
    const float tmin = trial % 5 == 0 ? 0.5f : 0.0f, tmax = trial % 6 == 0 ? 0.9f : INFINITY;
    const WatertightRay wr = watertight_ray(org, dir);
    float t4[4], u4[4], v4[4];
    const std::uint32_t mask = intersect_triangle4(&wr, &q, tmin, tmax, t4, u4, v4);
    for (int i = 0; i < 4; ++i) {
      float t = 0, u = 0, v = 0;
      const int hit = intersect_triangle(&wr, p[i][0], p[i][1], p[i][2], tmin, tmax, &t, &u, &v);
      ASSERT_EQ(hit, int((mask >> i) & 1u)) << "trial " << trial << " lane " << i;
      ++checked;
      if (!hit) continue;
      ++lanes_hit;
      EXPECT_EQ(std::bit_cast<std::uint32_t>(t), std::bit_cast<std::uint32_t>(t4[i])) << trial;
      EXPECT_EQ(std::bit_cast<std::uint32_t>(u), std::bit_cast<std::uint32_t>(u4[i])) << trial;
      EXPECT_EQ(std::bit_cast<std::uint32_t>(v), std::bit_cast<std::uint32_t>(v4[i])) << trial;
    }
  }
  EXPECT_GT(lanes_hit, checked / 5);  // the rays aimed at a lane hit it most of the time
}

// bvh8f_trace_packet against bvh8f_trace_steps ray by ray, bit for bit: camera-like packets (one
// origin, directions within a small cone, eight or fewer rays), packets of rays from scattered
// origins in one octant with wide directions, and rays aimed at vertices and edges, where the
// closest-hit tie rule decides between triangles; on a random soup, a grid of coplanar cells and the
// voxel terrain (axis-aligned faces shared by many boxes). A ray's node count is at least one (the
// root) where it has one at all.
TEST(Bvh8f, PacketGivesEachRayItsOwnWalksHit) {
  const std::vector<std::vector<glm::vec3>> meshes = {random_soup(5'000, 3), coplanar_grid(30, 30),
                                                      load_shipped("voxel-terrain.gltf")};
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> u01(0.0f, 1.0f);
  std::size_t rays = 0, hits = 0, ties_possible = 0;
  for (const auto& mesh : meshes) {
    const KdTree kept = kept_triangles(mesh);
    const Bvh8f bvh = build_bvh8f(kept.triangles);
    const Bvh8fView view = host_view(bvh);
    glm::vec3 lo(INFINITY), hi(-INFINITY);
    for (const glm::vec3& v : mesh) lo = glm::min(lo, v), hi = glm::max(hi, v);
    const glm::vec3 size = hi - lo;
    const auto inside = [&] { return lo + size * glm::vec3(u01(rng), u01(rng), u01(rng)); };
    const auto around = [&] { return lo + size * glm::vec3(3.0f * u01(rng) - 1.0f, 3.0f * u01(rng) - 1.0f, 2.0f); };
    for (int trial = 0; trial < 600; ++trial) {
      const int kind = trial % 3;
      const glm::vec3 eye = kind == 1 ? inside() : around();
      const glm::vec3 aim = inside() - eye;
      co_vec3 orgs[BVH8F_PACKET], dirs[BVH8F_PACKET];
      for (int l = 0; l < BVH8F_PACKET; ++l) {
        glm::vec3 org = eye, dir = aim;
        if (kind == 0) dir += 0.01f * glm::length(aim) * glm::vec3(u01(rng) - 0.5f, u01(rng) - 0.5f, u01(rng) - 0.5f);
        if (kind == 1) {  // scattered origins, directions anywhere in the aim's octant
          org = inside();
          dir = glm::sign(aim) * glm::vec3(u01(rng), u01(rng), u01(rng));
        }
        if (kind == 2) {  // at a vertex or an edge's midpoint of a random triangle
          const std::size_t t = std::uniform_int_distribution<std::size_t>(0, mesh.size() / 3 - 1)(rng);
          const glm::vec3 a = mesh[3 * t], b = mesh[3 * t + 1];
          dir = (l % 2 ? a : 0.5f * (a + b)) - org;
          ++ties_possible;
        }
        orgs[l] = v3(org.x, org.y, org.z);
        dirs[l] = v3(dir.x, dir.y, dir.z);
      }
      Bvh8fPacket packet;
      bvh8f_packet_begin(&packet, dirs[0]);
      const int lanes = trial % 4 == 3 ? 1 + trial % BVH8F_PACKET : BVH8F_PACKET;
      std::vector<int> lane_of_ray;
      for (int l = 0; l < lanes; ++l)
        if (bvh8f_packet_fits(&packet, dirs[l])) lane_of_ray.push_back(l);  // only a ray of the packet's octant joins
      // the packet filled as the naive kernel fills it: lanes past its rays repeat the first
      float ox[BVH8F_PACKET], oy[BVH8F_PACKET], oz[BVH8F_PACKET], dx[BVH8F_PACKET], dy[BVH8F_PACKET], dz[BVH8F_PACKET];
      for (std::size_t lane = 0; lane < BVH8F_PACKET; ++lane) {
        const int l = lane_of_ray[lane < lane_of_ray.size() ? lane : 0];
        ox[lane] = orgs[l].x, oy[lane] = orgs[l].y, oz[lane] = orgs[l].z;
        dx[lane] = dirs[l].x, dy[lane] = dirs[l].y, dz[lane] = dirs[l].z;
      }
      bvh8f_packet_add_all(&view, &packet, std::uint32_t(lane_of_ray.size()), ox, oy, oz, dx, dy, dz);
      bvh8f_trace_packet(&view, &packet);
      for (std::size_t lane = 0; lane < lane_of_ray.size(); ++lane) {
        const int l = lane_of_ray[lane];
        std::uint32_t steps = 0;
        const HitOut alone = bvh8f_trace_steps(&view, orgs[l], dirs[l], 0.0f, INFINITY, 0, &steps);
        const HitOut& packed = packet.hit[lane];
        const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
        ASSERT_EQ(alone.triangle, packed.triangle) << "trial " << trial << " lane " << lane;
        EXPECT_EQ(bits(alone.t), bits(packed.t)) << "trial " << trial << " lane " << lane;
        EXPECT_EQ(bits(alone.u), bits(packed.u)) << "trial " << trial << " lane " << lane;
        EXPECT_EQ(bits(alone.v), bits(packed.v)) << "trial " << trial << " lane " << lane;
        EXPECT_GE(packet.count[lane], 1u);
        ++rays;
        if (alone.triangle != HIT_NONE) ++hits;
      }
    }
  }
  EXPECT_GT(rays, 8'000u);
  EXPECT_GT(hits, rays / 3);  // most packets are aimed at the mesh
  EXPECT_GT(ties_possible, 1'000u);
}

// bvh8f_packet_add_all (the camera rays' set-ups side by side) gives each lane of a packet the bits
// that watertight_ray, bvh_slab_ray and bvh_slab_offsets give its ray alone, and leaves the lanes
// past its rays as bvh8f_packet_begin left them, for 1 to 8 rays: direction components of 0, below
// the inverse's 1e-18 floor and of either sign, origins far out (beyond what the slabs can offset)
// and not finite, so that every select of watertight_ray, bvh4_inverse and bvh_slab_ray is taken.
TEST(Bvh8f, PacketAddAllGivesEachLaneItsRaysOwnSetUp) {
  const Bvh8fView view{};
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const auto bits = [](float f) { return std::bit_cast<std::uint32_t>(f); };
  const auto same = [&](co_vec3 a, co_vec3 b) { return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z); };
  int special = 0;
  for (int trial = 0; trial < 4'000; ++trial) {
    const glm::vec3 signs(u(rng) < 0 ? -1.0f : 1.0f, u(rng) < 0 ? -1.0f : 1.0f, u(rng) < 0 ? -1.0f : 1.0f);
    const std::uint32_t n = 1u + std::uint32_t(trial % BVH8F_PACKET);
    float ox[BVH8F_PACKET], oy[BVH8F_PACKET], oz[BVH8F_PACKET], dx[BVH8F_PACKET], dy[BVH8F_PACKET], dz[BVH8F_PACKET];
    for (std::uint32_t l = 0; l < BVH8F_PACKET; ++l) {
      glm::vec3 o(10.0f * u(rng), 10.0f * u(rng), 10.0f * u(rng));
      glm::vec3 d = signs * glm::abs(glm::vec3(u(rng), u(rng), u(rng)));
      const int axis = int(rng() % 3);
      switch (rng() % 8) {  // the cases the selects are for, one lane in two
        case 0: d[axis] = 0.0f; ++special; break;
        case 1: d[axis] = signs[axis] * 1e-20f; ++special; break;
        case 2: o[axis] = 3e21f; ++special; break;  // beyond what a fused slab can offset
        case 3: o[axis] = l % 2 ? NAN : -INFINITY; ++special; break;
        default: break;
      }
      ox[l] = o.x, oy[l] = o.y, oz[l] = o.z, dx[l] = d.x, dy[l] = d.y, dz[l] = d.z;
    }
    Bvh8fPacket begun, all;
    bvh8f_packet_begin(&begun, v3(dx[0], dy[0], dz[0]));
    all = begun;
    bvh8f_packet_add_all(&view, &all, n, ox, oy, oz, dx, dy, dz);
    ASSERT_EQ(all.lanes, (1u << n) - 1u) << "trial " << trial;
    for (std::uint32_t l = 0; l < BVH8F_PACKET; ++l) {
      // each ray's own set-up; a lane without a ray as the empty packet had it
      co_vec3 o = v3(ox[l], oy[l], oz[l]), d = v3(dx[l], dy[l], dz[l]), origin, inverse, near_o, far_o;
      bvh_slab_ray(o, d, &origin, &inverse);
      bvh_slab_offsets(origin, inverse, &near_o, &far_o);
      if (l >= n) {
        near_o = v3(begun.near_o[0][l], begun.near_o[1][l], begun.near_o[2][l]);
        far_o = v3(begun.far_o[0][l], begun.far_o[1][l], begun.far_o[2][l]);
        inverse = v3(begun.inv[0][l], begun.inv[1][l], begun.inv[2][l]);
      }
      ASSERT_TRUE(same(near_o, v3(all.near_o[0][l], all.near_o[1][l], all.near_o[2][l])) &&
                  same(far_o, v3(all.far_o[0][l], all.far_o[1][l], all.far_o[2][l])) &&
                  same(inverse, v3(all.inv[0][l], all.inv[1][l], all.inv[2][l])))
          << "trial " << trial << " lane " << l;
      if (l >= n) continue;
      const WatertightRay a = watertight_ray(o, d), &b = all.wr[l];
      ASSERT_TRUE(same(o, b.org) && same(a.row_x, b.row_x) && same(a.row_y, b.row_y) && same(a.row_z, b.row_z) &&
                  bits(a.sz) == bits(b.sz))
          << "trial " << trial << " lane " << l;
    }
  }
  EXPECT_GT(special, 8'000);
}

}  // namespace
}  // namespace cohort::test

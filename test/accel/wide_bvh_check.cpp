#include "accel/wide_bvh_check.h"

#include <algorithm>
#include <cstring>
#include <utility>

namespace cohort::test {

namespace {

bool overlaps(const Triangle& t, const float lo[3], const float hi[3]) {
  for (int a = 0; a < 3; ++a) {
    const float v[3] = {(&t.v0.x)[a], (&t.v1.x)[a], (&t.v2.x)[a]};
    if (std::max({v[0], v[1], v[2]}) < lo[a] || std::min({v[0], v[1], v[2]}) > hi[a]) return false;
  }
  return true;
}

}  // namespace

StructureTally::StructureTally(std::size_t node_count, std::vector<Triangle> leaf_vertices, const KdTree& kept)
    : leaf_vertices_(std::move(leaf_vertices)),
      kept_(kept),
      seen_node_(node_count, 0),
      seen_entry_(leaf_vertices_.size(), 0),
      seen_triangle_(kept.triangles.size(), 0) {}

bool StructureTally::reach(std::uint32_t index, int depth) {
  if (index >= seen_node_.size() || seen_node_[index]++) {
    errors.push_back(fmt::format("node {} reached twice or out of range", index));
    return false;
  }
  deepest_ = std::max(deepest_, depth);
  return true;
}

void StructureTally::box(std::uint32_t index, int lane, const float lo[3], const float hi[3], const float* plo,
                         const float* phi) {
  for (int a = 0; a < 3; ++a)
    if (!(lo[a] <= hi[a]) || (plo && (lo[a] < plo[a] || hi[a] > phi[a]))) {
      errors.push_back(fmt::format("node {} lane {}: box inverted or outside its parent's", index, lane));
      return;
    }
}

void StructureTally::leaf(std::uint32_t first, std::uint32_t count, std::uint32_t max_count, const float lo[3],
                          const float hi[3]) {
  ++leaves_;
  if (count > max_count) errors.push_back(fmt::format("leaf at entry {}: {} entries, more than {}", first, count, max_count));
  for (std::uint32_t i = first; i < first + count; ++i) {
    if (i >= leaf_vertices_.size()) {
      errors.push_back(fmt::format("leaf entry {} out of range", i));
      continue;
    }
    ++seen_entry_[i];
    const std::uint32_t tri = co_as_uint(leaf_vertices_[i].v0.w);
    if (tri >= kept_.triangles.size()) {
      errors.push_back(fmt::format("leaf entry {}: triangle {} out of range", i, tri));
      continue;
    }
    ++seen_triangle_[tri];
    if (!overlaps(kept_.triangles[tri], lo, hi)) errors.push_back(fmt::format("triangle {} outside its leaf box", tri));
    Triangle expected = kept_.triangles[tri];
    expected.v0.w = co_as_float(tri);
    if (std::memcmp(&leaf_vertices_[i], &expected, sizeof(Triangle)) != 0)
      errors.push_back(fmt::format("leaf entry {}: its copy is not triangle {}", i, tri));
  }
}

void StructureTally::padding(std::uint32_t entry, std::uint32_t copy_of) {
  if (entry >= leaf_vertices_.size() || copy_of >= leaf_vertices_.size()) {
    errors.push_back(fmt::format("padding entry {} or its original {} out of range", entry, copy_of));
    return;
  }
  ++seen_entry_[entry];
  ++padding_;
  if (std::memcmp(&leaf_vertices_[entry], &leaf_vertices_[copy_of], sizeof(Triangle)) != 0)
    errors.push_back(fmt::format("padding entry {} is not a copy of entry {}", entry, copy_of));
}

std::vector<std::string> StructureTally::finish(const Bvh4Stats& stats, int max_depth) {
  for (std::size_t i = 0; i < seen_node_.size(); ++i)
    if (!seen_node_[i]) errors.push_back(fmt::format("node {} unreachable", i));
  for (std::size_t i = 0; i < seen_entry_.size(); ++i)
    if (seen_entry_[i] != 1) errors.push_back(fmt::format("leaf entry {} reached {} times", i, seen_entry_[i]));
  if (leaf_vertices_.size() - padding_ != stats.references) errors.push_back("leaf entries are not the references");
  for (std::size_t i = 0; i < seen_triangle_.size(); ++i)
    if (seen_triangle_[i] < 1)
      errors.push_back(fmt::format("triangle {} in {} leaves", i, seen_triangle_[i]));
  if (leaves_ != stats.leaf_count) errors.push_back(fmt::format("{} leaves but stats say {}", leaves_, stats.leaf_count));
  if (deepest_ != stats.depth) errors.push_back(fmt::format("depth {} but stats say {}", deepest_, stats.depth));
  if (deepest_ > max_depth) errors.push_back(fmt::format("depth {} over the stack's {}", deepest_, max_depth));
  if (errors.size() > 10) errors.resize(10);
  return errors;
}

std::vector<TestRay> hit_check_rays(const KdTree& kd) {
  std::vector<TestRay> rays = make_feature_rays(kd, 20'000, 41);
  const std::vector<TestRay> random = make_rays(kd.bounds, 10'000, 42);
  rays.insert(rays.end(), random.begin(), random.end());
  const std::vector<TestRay> in_planes = make_split_plane_rays(kd, 10'000, 43);
  rays.insert(rays.end(), in_planes.begin(), in_planes.end());
  return rays;
}

}  // namespace cohort::test

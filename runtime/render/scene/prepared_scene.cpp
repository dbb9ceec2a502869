#include "runtime/render/scene/prepared_scene.h"

#include <algorithm>
#include <chrono>
#include <climits>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "runtime/render/scene/scene_memory.h"
#include "runtime/util/error.h"

namespace cohort {

const std::vector<std::string>& tree_choices() {
  static const std::vector<std::string> names{"auto", "deep", "compact", "bvh4", "bvh8", "bvh8f"};
  return names;
}

TreeChoice tree_options(const std::string& choice, std::span<const DeviceInfo> devices, bool needs_kd, bool sorts) {
  TreeChoice options;
  const bool no_gpu = std::none_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.is_gpu; });
  const bool cpus =
      !devices.empty() && std::all_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.is_cpu; });
  if (choice == "compact") {
    options.kd.compact = true;
  } else if (choice == "auto") {
    options.kd.compact = no_gpu;
    // CPUs trace the 8-wide BVH with float planes (eight boxes per AVX step) unless hash or pth,
    // which walk the 4-wide BVH's top, run on it; GPUs trace the 4-wide one
    options.bvh8f = !needs_kd && cpus && !sorts;
    options.bvh4 = !needs_kd && !options.bvh8f;
  } else if (choice == "bvh4" || choice == "bvh8" || choice == "bvh8f") {
    if (needs_kd)
      throw InputError(fmt::format("--tree {}: --tree-budget and --speculative need the KD-tree; give --tree auto, "
                                   "deep or compact with them",
                                   choice));
    options.bvh4 = choice == "bvh4";
    options.bvh8 = choice == "bvh8";
    options.bvh8f = choice == "bvh8f";
  } else if (choice != "deep") {
    throw InputError(
        fmt::format("--tree {}: unknown tree (choose from {})", choice, fmt::join(tree_choices(), ", ")));
  }
  return options;
}

std::string describe_tree(const PreparedScene& p) {
  if (const Bvh4Stats* bvh = p.bvh_stats())
    return describe_bvh(p.bvh8 ? "compressed 8-wide BVH" : p.bvh8f ? "8-wide BVH (float planes)" : "4-wide BVH", *bvh, p.tree.triangles.size(),
                        p.tree.stats.build_seconds);
  return describe_kdtree(p.tree.stats);
}

std::string describe_bvh(const char* name, const Bvh4Stats& b, std::size_t triangles, double kept_seconds) {
  return fmt::format("{}: depth {}, {} nodes, {} leaves, {} references to {} triangles, {:.2f} per leaf, "
                     "SAH cost {:.2f}, built in {:.3f}s (triangles kept in {:.3f}s)",
                     name, b.depth, b.node_count, b.leaf_count, b.references, triangles, b.average_leaf_triangles,
                     b.sah_cost, b.build_seconds, kept_seconds);
}

std::string describe_kdtree(const KdTreeStats& ts) {
  return fmt::format("kd-tree ({}): depth {}, {} nodes, {} leaves ({} empty), {:.2f} triangles per leaf, SAH cost "
                     "{:.2f}, built in {:.3f}s",
                     tree_kind(ts), ts.depth, ts.node_count, ts.leaf_count, ts.empty_leaf_count,
                     ts.average_leaf_triangles, ts.sah_cost, ts.build_seconds);
}

PreparedScene prepare_scene(const std::filesystem::path& path, const TreeChoice& choice) {
  const auto t0 = std::chrono::steady_clock::now();
  Scene scene = load_scene(path);
  const double load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  PreparedScene p = prepare_loaded_scene(path, std::move(scene), choice);
  p.load_seconds = load_seconds;
  return p;
}

PreparedScene prepare_loaded_scene(const std::filesystem::path& path, Scene scene, const TreeChoice& choice) {
  PreparedScene p;
  p.scene = std::move(scene);
  KdBuildOptions one_leaf = choice.kd;
  one_leaf.leaf_triangles = INT_MAX;  // with the BVH the KD-tree only keeps the triangles
  p.tree = build_kdtree(p.scene.positions, choice.bvh() ? one_leaf : choice.kd);
  // The loaders reject a file without triangles; this catches one whose triangles all go, so that
  // no command renders an image of nothing.
  if (p.tree.triangles.empty())
    throw InputError(fmt::format("{}: nothing to render: all {} triangles are degenerate (zero area) or have "
                                 "non-finite corners",
                                 path.string(), p.scene.triangle_count()));
  try {  // a tree that cannot take the scene says so with the file's name
    if (choice.bvh4) p.bvh4 = build_bvh4(p.tree.triangles);
    if (choice.bvh8) p.bvh8 = build_bvh8(p.tree.triangles);
    if (choice.bvh8f) p.bvh8f = build_bvh8f(p.tree.triangles);
  } catch (const InputError& e) {
    throw InputError(fmt::format("{}: {}", path.string(), e.what()));
  }
  p.tables = make_scene_tables(p.scene, p.tree);
  p.camera = p.scene.camera ? *p.scene.camera : framing_camera(p.scene.bounds());
  return p;
}

void fit_scene_to(PreparedScene& p, std::size_t device_bytes, const KdBuildOptions& options) {
  const SceneMemory memory = scene_memory(p.tree, p.tables, p.bvh());
  if (memory.total() <= device_bytes) return;
  if (p.bvh())
    throw InputError(fmt::format("the scene needs {:.2f} MiB of device memory with the {}-wide BVH; the limit is "
                                 "{:.2f} MiB (a KD-tree can trade depth for bytes: --tree deep or compact)",
                                 memory.total() / 1048576.0, p.bvh8 || p.bvh8f ? 8 : 4, device_bytes / 1048576.0));
  // The smallest tree is one leaf: a node and one list entry and the vertices per triangle.
  const std::size_t smallest = sizeof(KdNode) + p.tree.triangles.size() * (sizeof(std::uint32_t) + sizeof(Triangle));
  if (memory.shading + smallest > device_bytes) {
    throw InputError(fmt::format("the scene needs at least {:.2f} MiB of device memory ({:.2f} MiB of shading data and "
                                 "{:.2f} MiB for the smallest KD-tree); the limit is {:.2f} MiB",
                                 (memory.shading + smallest) / 1048576.0, memory.shading / 1048576.0,
                                 smallest / 1048576.0, device_bytes / 1048576.0));
  }
  // The kept triangles, and so the shading tables, do not depend on the depth limit.
  p.tree = build_kdtree_within(p.scene.positions, options, device_bytes - memory.shading);
}

}  // namespace cohort

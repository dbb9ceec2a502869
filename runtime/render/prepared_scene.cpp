#include "runtime/render/prepared_scene.h"

#include <algorithm>
#include <chrono>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "runtime/render/scene_memory.h"
#include "runtime/util/error.h"

namespace cohort {

const std::vector<std::string>& tree_choices() {
  static const std::vector<std::string> names{"auto", "deep", "compact"};
  return names;
}

KdBuildOptions tree_options(const std::string& choice, std::span<const DeviceInfo> devices) {
  KdBuildOptions options;
  if (choice == "compact") {
    options.compact = true;
  } else if (choice == "auto") {
    options.compact = std::none_of(devices.begin(), devices.end(), [](const DeviceInfo& d) { return d.is_gpu; });
  } else if (choice != "deep") {
    throw InputError(
        fmt::format("--tree {}: unknown KD-tree (choose from {})", choice, fmt::join(tree_choices(), ", ")));
  }
  return options;
}

PreparedScene prepare_scene(const std::filesystem::path& path, const KdBuildOptions& options) {
  PreparedScene p;
  const auto t0 = std::chrono::steady_clock::now();
  p.scene = load_scene(path);
  p.load_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  p.tree = build_kdtree(p.scene.positions, options);
  // The loaders reject a file without triangles; this catches one whose triangles all go, so that
  // no command renders an image of nothing.
  if (p.tree.triangles.empty())
    throw InputError(fmt::format("{}: nothing to render: all {} triangles are degenerate (zero area) or have "
                                 "non-finite corners",
                                 path.string(), p.scene.triangle_count()));
  p.tables = make_scene_tables(p.scene, p.tree);
  p.camera = p.scene.camera ? *p.scene.camera : framing_camera(p.scene.bounds());
  return p;
}

void fit_scene_to(PreparedScene& p, std::size_t device_bytes, const KdBuildOptions& options) {
  const SceneMemory memory = scene_memory(p.tree, p.tables);
  if (memory.total() <= device_bytes) return;
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

#include "runtime/render/prepared_scene.h"

#include <chrono>

#include <fmt/format.h>

#include "runtime/util/error.h"

namespace cohort {

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

}  // namespace cohort

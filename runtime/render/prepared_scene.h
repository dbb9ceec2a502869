// A scene loaded from disk with its KD-tree and device tables: what `render`, `info` and the
// benchmarks start from.
#pragma once

#include <filesystem>

#include "runtime/accel/kdtree.h"
#include "runtime/render/device_scene.h"
#include "runtime/scene/scene.h"

namespace cohort {

struct PreparedScene {
  Scene scene;
  KdTree tree;
  SceneTables tables;
  SceneCamera camera;  // the file's camera, else the framing camera of bench-protocol.md
  double load_seconds = 0;
};

PreparedScene prepare_scene(const std::filesystem::path& path, const KdBuildOptions& options = {});

}  // namespace cohort

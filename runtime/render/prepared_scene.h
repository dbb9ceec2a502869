// A scene loaded from disk with its KD-tree and device tables: what `render`, `info` and the
// benchmarks start from.
#pragma once

#include <cstddef>
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

// Rebuilds the tree with the depth limit lowered as far as needed for the scene's device memory
// (tree and shading data, scene_memory.h) to fit `device_bytes`; nothing when it fits already.
// Throws InputError naming the size needed and the limit when not even a one-leaf tree fits.
void fit_scene_to(PreparedScene& scene, std::size_t device_bytes, const KdBuildOptions& options = {});

}  // namespace cohort

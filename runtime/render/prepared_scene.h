// A scene loaded from disk with its KD-tree and device tables: what `render`, `info` and the
// benchmarks start from.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "runtime/accel/kdtree.h"
#include "runtime/backend/device_info.h"
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

// The KD-tree a render builds (`--tree`): "deep" (the default build: the fastest to trace on the
// H200), "compact" (KdBuildOptions::compact: 0.55-0.67x the nodes and 0.74-0.83x the bytes, traced
// as fast on CPUs and 2-5 % slower on the H200, built in about the same time; docs/results.md) or
// "auto": compact when no device is a GPU. Every tree gives every ray the same hit
// (kernels/common/kdtree_traverse.h), so the choice changes speed and memory, never the image.
// Throws InputError for another name.
KdBuildOptions tree_options(const std::string& choice, std::span<const DeviceInfo> devices = {});
inline KdBuildOptions tree_options(const std::string& choice, const DeviceInfo& device) {
  return tree_options(choice, {&device, 1});
}
// The names tree_options takes, for the CLI's --tree.
const std::vector<std::string>& tree_choices();

PreparedScene prepare_scene(const std::filesystem::path& path, const KdBuildOptions& options = {});

// Rebuilds the tree with the depth limit lowered as far as needed for the scene's device memory
// (tree and shading data, scene_memory.h) to fit `device_bytes`; nothing when it fits already.
// Throws InputError naming the size needed and the limit when not even a one-leaf tree fits.
void fit_scene_to(PreparedScene& scene, std::size_t device_bytes, const KdBuildOptions& options = {});

}  // namespace cohort

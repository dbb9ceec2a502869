// A scene loaded from disk with its KD-tree and device tables: what `render`, `info` and the
// benchmarks start from.
#pragma once

#include <cstddef>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include <optional>

#include "runtime/accel/bvh4.h"
#include "runtime/accel/bvh8.h"
#include "runtime/accel/bvh8f.h"
#include "runtime/accel/wide_bvh.h"
#include "runtime/accel/kdtree/kdtree.h"
#include "runtime/backend/device_info.h"
#include "runtime/render/scene/device_scene.h"
#include "runtime/scene/scene.h"

namespace cohort {

struct PreparedScene {
  Scene scene;
  KdTree tree;                // with a BVH: one leaf, for the kept triangles and their indices
  std::optional<Bvh4> bvh4;   // what the kernels trace with --tree bvh4 (tree_options)
  std::optional<Bvh8> bvh8;   // what the kernels trace with --tree bvh8
  std::optional<Bvh8f> bvh8f; // what the kernels trace with --tree bvh8f
  SceneTables tables;
  SceneCamera camera;  // the file's camera, else the framing camera of docs/bench-protocol.md
  double load_seconds = 0;

  // the BVH the kernels trace, if any
  WideBvh bvh() const {
    if (bvh4) return &*bvh4;
    if (bvh8) return &*bvh8;
    if (bvh8f) return &*bvh8f;
    return {};
  }
  // the BVH's figures, if there is one
  const Bvh4Stats* bvh_stats() const {
    return bvh4 ? &bvh4->stats : bvh8 ? &bvh8->stats : bvh8f ? &bvh8f->stats : nullptr;
  }
  // "deep", "compact", "bvh4", "bvh8" or "bvh8f": what --stats, info and the bench JSON name as the tree
  const char* tree_kind() const {
    return bvh4 ? "bvh4" : bvh8 ? "bvh8" : bvh8f ? "bvh8f" : cohort::tree_kind(tree.stats);
  }
  double build_seconds() const {
    const Bvh4Stats* b = bvh_stats();
    return tree.stats.build_seconds + (b ? b->build_seconds : 0.0);
  }
};

// One line on what the scene is traced with, as `info` and `render -v` print it: "kd-tree (deep):
// depth 21, ..., built in 0.12s" or "4-wide BVH: depth 9, ...".
std::string describe_tree(const PreparedScene& scene);
// The same line for a BVH's figures: "4-wide BVH: depth 9, ..." (`name` first).
std::string describe_bvh(const char* name, const Bvh4Stats& stats, std::size_t triangles, double kept_seconds);
std::string describe_kdtree(const KdTreeStats& stats);

// What a scene is traced with: a KD-tree built with `kd`, or with `bvh4` a 4-wide BVH, with `bvh8`
// the compressed 8-wide BVH, with `bvh8f` the 8-wide BVH with float planes, over the kept triangles (the KD-tree then one leaf; `kd` is still the
// KD-tree the choice would build without the BVH, what a memory limit falls back to).
struct TreeChoice {
  KdBuildOptions kd;
  bool bvh4 = false;
  bool bvh8 = false;
  bool bvh8f = false;
  bool bvh() const { return bvh4 || bvh8 || bvh8f; }
};

// The structure a render traces with (`--tree`): "bvh4" (a 4-wide BVH: 1.6-2.3x the KD-tree's
// samples per CPU second on PoCL, 1.1-2.1x its rays/s on the H200 for naive and sc; 0.9x on the
// conference; docs/results.md), "bvh8f" (the 8-wide BVH with float planes and leaves of four triangles
// tested in one float4 step, for CPUs; docs/design.md), "deep" (the KD-tree built for GPUs), "compact"
// (KdBuildOptions::compact: 0.55-0.67x the nodes and 0.74-0.83x the bytes) or "auto": a KD-tree when
// one is asked for (`needs_kd`: --tree-budget, --speculative: compact when no device is a GPU, deep
// when one is), else bvh8f when every device is a CPU and the method is not hash or pth (`sorts`:
// they walk the top of the KD-tree or the 4-wide BVH; the auto method then probes the others), else
// bvh4 (GPUs, and without devices: `info`). "bvh8" (the compressed 8-wide BVH of Ylitie, Karras &
// Laine, for GPUs' incoherent rays; docs/design.md) is never chosen by auto; hash and pth do not run
// on either 8-wide BVH (SortedTraversal refuses them). Every structure gives every ray the same hit
// (kernels/common/accel/bvh4_traverse.h), so the choice changes speed and memory, never the image.
// Throws InputError for another name, and for bvh4, bvh8 or bvh8f with `needs_kd`.
TreeChoice tree_options(const std::string& choice, std::span<const DeviceInfo> devices = {}, bool needs_kd = false,
                        bool sorts = false);
inline TreeChoice tree_options(const std::string& choice, const DeviceInfo& device, bool needs_kd = false,
                               bool sorts = false) {
  return tree_options(choice, {&device, 1}, needs_kd, sorts);
}
// The names tree_options takes, for the CLI's --tree.
const std::vector<std::string>& tree_choices();

PreparedScene prepare_scene(const std::filesystem::path& path, const TreeChoice& choice);
// The same from a scene loaded already (`path` names it in errors); load_seconds stays 0.
PreparedScene prepare_loaded_scene(const std::filesystem::path& path, Scene scene, const TreeChoice& choice);
inline PreparedScene prepare_scene(const std::filesystem::path& path, const KdBuildOptions& options = {}) {
  return prepare_scene(path, TreeChoice{options, false});
}

// Rebuilds the tree with the depth limit lowered as far as needed for the scene's device memory
// (tree and shading data, scene_memory.h) to fit `device_bytes`; nothing when it fits already.
// Throws InputError naming the size needed and the limit when not even a one-leaf tree fits, and
// for a scene traced through a BVH that does not fit (it has no depth to trade).
void fit_scene_to(PreparedScene& scene, std::size_t device_bytes, const KdBuildOptions& options = {});

}  // namespace cohort

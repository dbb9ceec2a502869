// The JSON that `cohort bench` writes: every figure, the device, the build and the settings.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "runtime/bench/scene_bench.h"
#include "runtime/backend/device.h"

namespace cohort {

nlohmann::json rate_json(const RateFigure& f, double scale = 1e-6);  // {median, best, runs} in millions
// The scenes and their views; accel_key names the acceleration structure ("kdtree", "bvh").
nlohmann::json bvh4_json(const Bvh4Stats& b);  // nodes, leaves, depth, ... as --stats and the bench JSON write them
// The sort's settings: code, pth_levels, sort_from_bounce, sort_payload (the bench's settings, and
// within coherence_json).
nlohmann::json sort_json(const SortSettings& s);
// How hash or pth sorted, as --stats and the bench JSON write it: sort_json of the sort as resolved,
// key_bits, subtree_nodes, speculative.
nlohmann::json coherence_json(const CoherenceFigures& c);
nlohmann::json scenes_json(const std::vector<SceneFigures>& scenes, const std::string& accel_key = "kdtree");
nlohmann::json bench_json(const BenchDevice& device, const BenchOptions& options,
                          const std::vector<SceneFigures>& scenes);

}  // namespace cohort

// cohort replay: the straggler rays a render wrote (--stragglers) traced again on the host with the
// kernels' own traversal, so a slow ray can be studied in a debugger, bit for bit as the device saw it.
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <fstream>
#include <optional>

#include "runtime/accel/host_traversal.h"
#include "runtime/cli/commands.h"
#include "runtime/render/scene/prepared_scene.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

float parse_float(const nlohmann::json& value, const std::filesystem::path& file) {
  const std::string text = value.get<std::string>();
  char* end = nullptr;
  const float f = std::strtof(text.c_str(), &end);  // reads C99 hex floats exactly
  if (text.empty() || end != text.c_str() + text.size())
    throw InputError(fmt::format("{}: \"{}\" is not a number", file.string(), text));
  return f;
}

glm::vec3 parse_vec3(const nlohmann::json& value, const std::filesystem::path& file) {
  if (!value.is_array() || value.size() != 3)
    throw InputError(fmt::format("{}: a ray's org and dir are arrays of 3 numbers", file.string()));
  return {parse_float(value[0], file), parse_float(value[1], file), parse_float(value[2], file)};
}

}  // namespace

int run_replay(const ReplayCommand& cmd) {
  std::ifstream in(cmd.stats);
  if (!in) throw InputError(fmt::format("{}: cannot open", cmd.stats.string()));
  nlohmann::json stats;
  try {
    stats = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not JSON ({})", cmd.stats.string(), e.what()));
  }
  if (!stats.contains("stragglers") || !stats["stragglers"].contains("worst"))
    throw InputError(fmt::format("{}: no \"stragglers\" (render with --stragglers N --stats FILE)", cmd.stats.string()));
  // the render's tree, so the node counts compare (files from before --tree: the deep one)
  std::string tree = "deep";
  if (stats.contains("kdtree") && stats["kdtree"].contains("kind")) {
    const nlohmann::json& kind = stats["kdtree"]["kind"];
    if (!kind.is_string() || (kind != "deep" && kind != "compact" && kind != "bvh4" && kind != "bvh8" && kind != "bvh8f"))
      throw InputError(fmt::format("{}: kdtree.kind must be \"deep\", \"compact\", \"bvh4\", \"bvh8\" or \"bvh8f\"",
                                   cmd.stats.string()));
    tree = kind.get<std::string>();
  }
  const PreparedScene p = prepare_scene(cmd.scene, tree_options(tree));
  const KdTreeView kd_view = host_view(p.tree);
  std::optional<Bvh4View> bvh_view;
  std::optional<Bvh8View> bvh8_view;
  std::optional<Bvh8fView> bvh8f_view;
  if (p.bvh4) {
    bvh_view = host_view(*p.bvh4);
    fmt::print("{}: 4-wide BVH, {} nodes, depth {}\n", cmd.scene.string(), p.bvh4->stats.node_count,
               p.bvh4->stats.depth);
  } else if (p.bvh8) {
    bvh8_view = host_view(*p.bvh8);
    fmt::print("{}: compressed 8-wide BVH, {} nodes, depth {}\n", cmd.scene.string(), p.bvh8->stats.node_count,
               p.bvh8->stats.depth);
  } else if (p.bvh8f) {
    bvh8f_view = host_view(*p.bvh8f);
    fmt::print("{}: 8-wide BVH (float planes), {} nodes, depth {}\n", cmd.scene.string(), p.bvh8f->stats.node_count,
               p.bvh8f->stats.depth);
  } else {
    fmt::print("{}: {} KD-tree, {} nodes, depth {}\n", cmd.scene.string(), tree, p.tree.stats.node_count,
               p.tree.stats.depth);
  }
  for (const auto& ray : stats["stragglers"]["worst"]) {
    try {
      const glm::vec3 o = parse_vec3(ray.at("org"), cmd.stats), d = parse_vec3(ray.at("dir"), cmd.stats);
      const float tmin = parse_float(ray.at("tmin"), cmd.stats), tmax = parse_float(ray.at("tmax"), cmd.stats);
      std::uint32_t steps = 0;
      const co_vec3 org = v3(o.x, o.y, o.z), dir = v3(d.x, d.y, d.z);
      const HitOut hit = bvh_view    ? bvh4_trace_steps(&*bvh_view, org, dir, tmin, tmax, 0, &steps)
                         : bvh8_view ? bvh8_trace_steps(&*bvh8_view, org, dir, tmin, tmax, 0, &steps)
                         : bvh8f_view ? bvh8f_trace_steps(&*bvh8f_view, org, dir, tmin, tmax, 0, &steps)
                                     : kd_trace_steps(&kd_view, org, dir, tmin, tmax, 0, &steps);
      fmt::print("device {} nodes, host {} nodes: org ({:a}, {:a}, {:a}) dir ({:a}, {:a}, {:a}) -> {}\n",
                 ray.at("nodes").get<std::uint32_t>(), steps, o.x, o.y, o.z, d.x, d.y, d.z,
                 hit.triangle == HIT_NONE ? std::string("miss") : fmt::format("triangle {} at t {:a}", hit.triangle, hit.t));
    } catch (const nlohmann::json::exception& e) {
      throw InputError(fmt::format("{}: a straggler ray is malformed ({})", cmd.stats.string(), e.what()));
    }
  }
  return 0;
}

}  // namespace cohort

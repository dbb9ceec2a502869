#include "runtime/cli/scene_commands.h"

#include <fmt/format.h>

#include "runtime/render/methods/methods.h"
#include "runtime/render/scene/scene_memory.h"
#include "runtime/render/workloads.h"
#include "runtime/util/error.h"

namespace cohort {
namespace {

// The options a loaded scene fixes: a render may not change them.
void check_shared_options(const RenderCommand& base, const RenderCommand& c) {
  const auto differs = [](const char* option) {
    throw InputError(fmt::format("{} is the scene's, set when it was loaded: load the scene again to change it", option));
  };
  if (c.scene != base.scene) differs("the scene file");
  if (c.device != base.device) differs("--device");
  if (c.backend != base.backend) differs("--backend");
  if (c.tree != base.tree) differs("--tree");
  if (c.tree_budget_mib != base.tree_budget_mib) differs("--tree-budget");
  if (c.memory_limit_mib != base.memory_limit_mib) differs("--memory-limit");
  if (c.no_cache != base.no_cache) differs("--no-cache");
  if (c.checkpoint || c.resume) throw InputError("--checkpoint and --resume are the command line's, not a loaded scene's");
}

}  // namespace

SceneCommands::SceneCommands(RenderCommand base)
    : base_(std::move(base)),
      scene_(parse_render(base_), [this](const PreparedScene& scene) { report_scene_warnings(scene, base_.scene); }) {}

SceneRender SceneCommands::render(const RenderCommand& command, const std::optional<SceneCamera>& camera,
                                  const RenderHooks& hooks, const std::vector<std::filesystem::path>& denoise_venvs) {
  check_shared_options(base_, command);
  const LoadedScene::Prepared prepared = scene_.prepare(parse_render(command), camera);
  const PreparedRender& render = prepared.render;
  const bool built = prepared.built_tree;

  const auto team = solo_render_team();
  RenderOutcome outcome = run_render_passes(render, *team, {}, hooks);
  render_first_hit_aovs(render, outcome);

  SceneRender out;
  out.interrupted = outcome.result.interrupted;
  if (command.denoise) out.denoised = denoise_image(outcome, denoise_venvs);
  out.stats = stats_json(render, outcome, nullptr);
  // what this render set up: the file is read once per scene, a tree built once
  const bool first = renders_++ == 0;
  const double load = first ? scene_.load_seconds() : 0.0;
  const double build = built ? render.scene.build_seconds() : 0.0;
  out.stats["timings"]["load_seconds"] = load;
  out.stats["timings"]["build_seconds"] = build;
  for (auto& rank : out.stats["ranks"]) {
    rank["load_seconds"] = load;
    rank["build_seconds"] = build;
  }
  out.stats["setup"] = {{"render", renders_}, {"loaded_scene", first}, {"built_tree", built},
                        {"compiled", !outcome.result.compile_from_cache || outcome.result.compile_seconds > 0}};
  out.image = std::move(outcome.result.image);
  out.aovs = std::move(outcome.aovs);
  return out;
}

nlohmann::json SceneCommands::info() {
  const PreparedScene& p = scene_.scene(parse_render(base_));
  const Bounds b = p.scene.bounds();
  nlohmann::json materials = nlohmann::json::array();
  for (const auto& m : p.scene.materials)
    materials.push_back({{"name", m.name},
                         {"base_color", {m.base_color.x, m.base_color.y, m.base_color.z}},
                         {"emission", {m.emission.x, m.emission.y, m.emission.z}},
                         {"metallic", m.metallic},
                         {"roughness", m.roughness},
                         {"transmission", m.transmission},
                         {"textured", m.base_color_texture >= 0}});
  std::size_t spots = 0;
  for (const auto& l : p.scene.lights) spots += l.type == SceneLight::Type::spot;
  const SceneMemory memory = scene_memory(p.tree, p.tables, p.bvh());
  const auto vec = [](const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); };
  return {{"scene", base_.scene.string()},
          {"triangles", p.scene.triangle_count()},
          {"kept_triangles", p.tree.triangles.size()},
          {"dropped_triangles", p.tree.stats.dropped_triangles},
          {"materials", materials},
          {"textures", p.scene.textures.size()},
          {"lights", {{"emissive_triangles", p.tables.emitters.entries.size()},
                      {"emitted_power", p.tables.emitters.total_power},
                      {"point", p.scene.lights.size() - spots},
                      {"spot", spots}}},
          {"bounds", {{"lo", vec(b.lo)}, {"hi", vec(b.hi)}, {"diagonal", b.diagonal()}}},
          {"camera", {{"from_file", p.scene.camera.has_value()}, {"eye", vec(p.camera.eye)},
                      {"target", vec(p.camera.target)}, {"up", vec(p.camera.up)}, {"fov", p.camera.vfov_degrees}}},
          {"tree", describe_tree(p)},
          {"device_memory", {{"nodes", memory.nodes}, {"leaf_lists", memory.leaf_lists},
                             {"triangles", memory.triangles}, {"shading", memory.shading}, {"total", memory.total()},
                             {"text", describe(memory, p.tree.triangles.size())}}},
          {"host_geometry_bytes", p.scene.geometry_bytes()},
          {"load_seconds", scene_.load_seconds()},
          {"unread_textures", p.scene.unread_textures},
          {"notes", p.scene.notes},
          {"warnings", p.scene.warnings}};
}

}  // namespace cohort

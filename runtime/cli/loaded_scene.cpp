#include "runtime/cli/loaded_scene.h"

#include <fmt/format.h>

#include <chrono>

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

LoadedScene::LoadedScene(RenderCommand base)
    : base_(std::move(base)), cache_(base_.no_cache ? std::nullopt : std::optional(ProgramCache::default_directory())) {
  const RenderPlan plan = parse_render(base_);
  OpenedDevices opened = open_render_devices(plan, 0);
  devices_ = std::move(opened.devices);
  pool_ = std::move(opened.pool);
  const auto t0 = std::chrono::steady_clock::now();
  loaded_ = load_scene(base_.scene);
  load_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

LoadedScene::Variant& LoadedScene::variant(const RenderPlan& plan, bool& built) {
  const bool needs_kd = plan.command.tree_budget_mib > 0 || plan.settings().speculative;
  const VariantKey key{needs_kd, plan.command.white_sky,
                       plan.environment_map ? plan.command.environment : std::string()};
  built = false;
  if (auto it = variants_.find(key); it != variants_.end()) return it->second;
  auto tree = trees_.find(needs_kd);
  if (tree == trees_.end()) {
    PreparedScene prepared = build_render_trees(plan, devices_, [&](const TreeChoice& choice) {
      return prepare_loaded_scene(base_.scene, loaded_, choice);
    });
    if (trees_.empty()) report_scene_warnings(prepared, base_.scene);
    tree = trees_.emplace(needs_kd, std::move(prepared)).first;
    built = true;
  }
  PreparedScene scene = tree->second;
  RenderPlan scene_plan = plan;  // its settings are each render's own
  apply_scene_options(scene, scene_plan);
  const SceneCamera camera = scene.camera;
  auto render = std::make_unique<PreparedRender>(PreparedRender{
      .plan = std::move(scene_plan), .devices = devices_, .pool = pool_, .scene = std::move(scene), .cache = cache_});
  return variants_.emplace(key, Variant{std::move(render), camera}).first->second;
}

SceneRender LoadedScene::render(const RenderCommand& command, const std::optional<SceneCamera>& camera,
                                const RenderHooks& hooks, const std::vector<std::filesystem::path>& denoise_venvs) {
  check_shared_options(base_, command);
  RenderPlan plan = parse_render(command);
  if (command.white_sky) apply_white_sky_settings(plan.command.settings);
  bool built = false;
  Variant& v = variant(plan, built);
  PreparedRender& render = *v.render;
  render.plan = plan;
  render.scene.camera = plan_camera(camera ? *camera : v.camera, render.scene.scene.bounds(), command);

  const auto team = solo_render_team();
  RenderOutcome outcome = run_render_passes(render, *team, {}, hooks);
  render_first_hit_aovs(render, outcome);

  SceneRender out;
  out.interrupted = outcome.result.interrupted;
  if (command.denoise) out.denoised = denoise_image(outcome, denoise_venvs);
  out.stats = stats_json(render, outcome, nullptr);
  // what this render set up: the file is read once per scene, a tree built once
  const bool first = renders_++ == 0;
  const double load = first ? load_seconds_ : 0.0;
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

nlohmann::json LoadedScene::info() {
  bool built = false;
  const PreparedScene& p = variant(parse_render(base_), built).render->scene;
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
          {"load_seconds", load_seconds_},
          {"warnings", p.scene.warnings}};
}

}  // namespace cohort

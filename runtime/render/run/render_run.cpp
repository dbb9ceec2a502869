#include "runtime/render/run/render_run.h"

#include <fmt/format.h>

#include <ctime>

#include "runtime/render/run/checkpoint.h"
#include "runtime/util/hash.h"

namespace cohort {
namespace {

std::unique_ptr<DeviceWorkers> start_workers(const PreparedRender& render, PassSource& passes) {
  return std::make_unique<DeviceWorkers>(*render.pool, render.cache, render.scene, render.input.settings, passes);
}

}  // namespace

std::uint64_t render_fingerprint(const PreparedRender& render) {
  const auto& s = render.input.settings;
  const auto& p = render.scene;
  const auto& c = p.camera;
  const std::string text = fmt::format(
      "{}|{}x{}|seed {}|depth {} rr {}|nee {} mis {} rr {}|env {}|eye {} {} {}|target {} {} {}|fov {}|tris {}",
      std::filesystem::weakly_canonical(render.input.scene).string(), s.width, s.height, s.seed, s.max_depth,
      s.rr_depth, s.nee, s.mis, s.russian_roulette,
      s.environment ? fmt::format("{} {} {}", s.environment->x, s.environment->y, s.environment->z) : "none",
      c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.vfov_degrees, p.tree.triangles.size());
  // an environment map is named by its file, an adaptive render by its target (older checkpoints,
  // without either, keep their fingerprint)
  std::string extra;
  if (p.tables.environment)
    extra += "|envmap " + std::filesystem::weakly_canonical(p.tables.environment->source).string();
  if (s.target_error > 0) extra += fmt::format("|target-error {}", s.target_error);
  return fnv1a64(text + extra);
}

RenderOutcome run_render_passes(const PreparedRender& render, const RenderTeam& team,
                                const std::filesystem::path& checkpoint, const RenderHooks& hooks) {
  const CheckpointPolicy& policy = render.input.checkpoint;
  const std::uint64_t fingerprint = render_fingerprint(render);
  RenderControl control;
  if (policy.resume) control.resume_from = load_checkpoint(checkpoint, fingerprint);
  if (control.resume_from && hooks.resuming) hooks.resuming(control.resume_from->samples);
  if (policy.any()) {
    control.checkpoint_seconds = policy.seconds;
    control.checkpoint = [&](const FilmState& film) { save_checkpoint(checkpoint, fingerprint, film); };
  }
  control.stop_requested = hooks.stop_requested;
  PassJob job(render.input.settings, hooks.progress, control,
              pass_window(render.devices.size() * team.size(), render.pixels() * sizeof(co_float4)),
              render.devices.size());
  if (team.size() > 1) job.combine_on_host();  // other ranks send partial films
  std::vector<DeviceRun> runs;
  const std::clock_t cpu_start = std::clock();
  {
    const auto workers = start_workers(render, job);
    team.serve(job, render.pixels());
    runs = workers->join();
  }
  const std::clock_t cpu_end = std::clock();
  RenderOutcome outcome;
  RenderResult& result = outcome.result;
  result = merge_device_results(runs);
  // the image, its samples and the render loop's time (--method auto's probe renders passes of the
  // image: it is inside the job's clock)
  outcome.film = job.finish_into(result);
  result.render_cpu_seconds = double(cpu_end - cpu_start) / CLOCKS_PER_SEC;
  result.rays = job.rays();  // every rank's rays

  outcome.ranks.push_back(rank_figures(0, team.host(), render.scene, runs));
  const auto texts = team.gather(nlohmann::json(outcome.ranks[0]).dump());
  for (std::size_t r = 1; r < texts.size(); ++r)
    outcome.ranks.push_back(nlohmann::json::parse(texts[r]).get<RankFigures>());
  result.passes = 0;
  for (const RankFigures& rank : outcome.ranks)
    for (const DeviceFigures& d : rank.devices) result.passes += d.passes;
  outcome.image_mean = job.image_mean();
  return outcome;
}

void follow_render(const PreparedRender& render, const RenderTeam& team) {
  const auto runs = team.follow(
      render.devices.size(), [&](PassSource& passes) { return start_workers(render, passes); }, render.pixels());
  team.gather(nlohmann::json(rank_figures(team.rank(), team.host(), render.scene, runs)).dump());
}

}  // namespace cohort

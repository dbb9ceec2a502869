// `cohort render` in four steps: parse the options into a plan, prepare the scene and devices,
// run the passes, write the outputs. The command (cmd_render.cpp) composes them for each rank of
// its RenderTeam.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/open_device.h"
#include "runtime/backend/program_cache.h"
#include "runtime/cli/commands.h"
#include "runtime/cli/interrupt.h"
#include "runtime/cli/output_paths.h"
#include "runtime/cli/render_team.h"
#include "runtime/render/run/aov.h"
#include "runtime/render/run/multi_device.h"
#include "runtime/render/run/pass_job.h"
#include "runtime/render/scene/prepared_scene.h"

namespace cohort {

// The command's options, checked and parsed; nothing loaded or opened yet.
struct RenderPlan {
  RenderCommand command;  // settings hold the parsed resolution and --env colour
  bool environment_map = false;  // --env names an image file
  std::uint64_t memory_limit = 0;  // bytes the devices may use; 0: all they have
  Backend backend = Backend::opencl;
  AovSelection aovs;  // --aov: written to the EXR
  const RenderSettings& settings() const { return command.settings; }
};

// Throws InputError for options that contradict each other.
RenderPlan parse_render(const RenderCommand& command);

// The scene as this rank renders it and the devices that render it.
struct PreparedRender {
  RenderPlan plan;  // settings as the scene set them (--white-sky)
  std::vector<DeviceInfo> devices;
  std::shared_ptr<DevicePool> pool;  // `devices`, open; several renders of one scene share it
  PreparedScene scene;
  ProgramCache cache;
  std::size_t pixels() const { return std::size_t(plan.settings().width) * plan.settings().height; }
};

// Opens this rank's devices (`local_rank` picks them), then loads and builds the scene; the rank
// that `reports` prints the scene's warnings.
PreparedRender prepare_render(RenderPlan plan, int local_rank, bool reports);

// The devices a plan names (--device, --backend, --memory-limit), open.
struct OpenedDevices {
  std::vector<DeviceInfo> devices;
  std::shared_ptr<DevicePool> pool;
};
OpenedDevices open_render_devices(const RenderPlan& plan, int local_rank);

// The scene's trees as the plan asks for them (--tree, --tree-budget, --memory-limit, the method):
// `build` makes a PreparedScene with a tree choice (prepare_scene from the file, or from a scene
// loaded already).
PreparedScene build_render_trees(const RenderPlan& plan, const std::vector<DeviceInfo>& devices,
                                 const std::function<PreparedScene(const TreeChoice&)>& build);

// What the plan changes on a built scene: --env FILE, --white-sky (which also sets the plan's
// workload settings), --camera-bounds and --fov.
void apply_render_options(PreparedScene& scene, RenderPlan& plan);
// The same without the camera options (a scene several cameras render).
void apply_scene_options(PreparedScene& scene, RenderPlan& plan);
// The camera --camera-bounds and --fov make of the scene's `camera`.
SceneCamera plan_camera(SceneCamera camera, const Bounds& bounds, const RenderCommand& cmd);

// Prints the scene's load warnings (rank 0, once per scene).
void report_scene_warnings(const PreparedScene& scene, const std::filesystem::path& path);

// What rank 0 has once every pass is in.
struct RenderOutcome {
  FilmState film;
  RenderResult result;     // every rank's rays and passes; rank 0's device figures
  nlohmann::json ranks;    // rank_json of every rank, in rank order
  PassJob::ImageMean image_mean;
  std::optional<AovImages> aovs;  // with --aov or --denoise
  double aov_seconds = 0;         // wall time of the AOV render (after the passes, outside render_seconds)
};

// How a caller follows and stops a render.
struct RenderHooks {
  std::function<bool()> stop_requested;  // asked after every pass: stops the render early
  ProgressCallback progress;             // null: a progress line on the terminal
};

// Rank 0: renders the image on its devices and, through `team`, the other ranks; saves and resumes
// checkpoints at `checkpoint` (with --checkpoint or --resume).
RenderOutcome run_render_passes(const PreparedRender& render, const RenderTeam& team,
                                const std::filesystem::path& checkpoint, const RenderHooks& hooks);

// Rank 0, after the passes: the AOVs of the image's samples on this rank's first device, when
// --aov or --denoise asks for them, into outcome.aovs and outcome.aov_seconds.
void render_first_hit_aovs(const PreparedRender& render, RenderOutcome& outcome);

// Any other rank: renders the passes rank 0 assigns and sends it this rank's figures.
void follow_render(const PreparedRender& render, const RenderTeam& team);

// Writes the image, the --stats file and the summary lines; returns the exit code (128 + signal
// when interrupted).
int write_render(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths& out,
                 const InterruptGuard& interrupt);

// The beauty denoised by Open Image Denoise, guided by the AOVs (outcome.aovs); the library is
// looked for in the system, $COHORT_OIDN_LIBRARY, $COHORT_VENV, the venv beside the binary and
// `venvs`. Throws DenoiserUnavailable; names the library it used in `library`.
Image denoise_image(const RenderOutcome& outcome, const std::vector<std::filesystem::path>& venvs = {},
                    std::string* library = nullptr);

// --denoise: writes out.denoised_exr and .png; 0, or 2 with a message when Open Image Denoise
// cannot be loaded or run (the beauty is written by then).
int write_denoised(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths& out);

// The JSON figures of the --stats file; `out` names the image files (none: not written).
nlohmann::json rank_json(int rank, const std::string& host, const PreparedScene& prepared,
                         const std::vector<DeviceRun>& runs);
nlohmann::json stats_json(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths* out);

}  // namespace cohort

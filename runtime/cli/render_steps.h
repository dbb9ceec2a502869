// `cohort render` in four steps: parse the options into a plan, prepare the scene and devices,
// run the passes, write the outputs. The command (cmd_render.cpp) composes them for each rank of
// its RenderTeam.
#pragma once

#include <nlohmann/json.hpp>

#include <cstdint>
#include <optional>
#include <vector>

#include "runtime/backend/device.h"
#include "runtime/backend/open_device.h"
#include "runtime/backend/program_cache.h"
#include "runtime/cli/commands.h"
#include "runtime/cli/interrupt.h"
#include "runtime/cli/output_paths.h"
#include "runtime/cli/render_team.h"
#include "runtime/render/aov.h"
#include "runtime/render/multi_device.h"
#include "runtime/render/pass_job.h"
#include "runtime/render/prepared_scene.h"

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
  DeviceOpener open_devices;
  PreparedScene scene;
  ProgramCache cache;
  std::size_t pixels() const { return std::size_t(plan.settings().width) * plan.settings().height; }
};

// Opens this rank's devices (`local_rank` picks them), then loads and builds the scene; the rank
// that `reports` prints the scene's warnings.
PreparedRender prepare_render(RenderPlan plan, int local_rank, bool reports);

// What rank 0 has once every pass is in.
struct RenderOutcome {
  FilmState film;
  RenderResult result;     // every rank's rays and passes; rank 0's device figures
  nlohmann::json ranks;    // rank_json of every rank, in rank order
  PassJob::ImageMean image_mean;
  std::optional<AovImages> aovs;  // with --aov or --denoise
  double aov_seconds = 0;         // wall time of the AOV render (after the passes, outside render_seconds)
};

// Rank 0: renders the image on its devices and, through `team`, the other ranks; saves and resumes
// checkpoints at out.checkpoint.
RenderOutcome run_render_passes(const PreparedRender& render, const RenderTeam& team, const OutputPaths& out,
                                const InterruptGuard& interrupt);

// Rank 0, after the passes: the AOVs of the image's samples on this rank's first device, when
// --aov or --denoise asks for them.
std::optional<AovImages> render_first_hit_aovs(const PreparedRender& render, const FilmState& film);

// Any other rank: renders the passes rank 0 assigns and sends it this rank's figures.
void follow_render(const PreparedRender& render, const RenderTeam& team);

// Writes the image, the --stats file and the summary lines; returns the exit code (128 + signal
// when interrupted).
int write_render(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths& out,
                 const InterruptGuard& interrupt);

// --denoise: writes out.denoised_exr and .png; 0, or 2 with a message when Open Image Denoise
// cannot be loaded or run (the beauty is written by then).
int write_denoised(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths& out);

// The JSON figures of the --stats file.
nlohmann::json rank_json(int rank, const std::string& host, const PreparedScene& prepared,
                         const std::vector<DeviceRun>& runs);
nlohmann::json stats_json(const PreparedRender& render, const RenderOutcome& outcome, const OutputPaths& out);

}  // namespace cohort

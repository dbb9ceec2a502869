// A render's run over its passes, the same for `cohort render`, the Python module and `cohort bench`:
// rank 0 renders the image on its devices and, through its team, on the other ranks, saving and
// resuming checkpoints; any other rank renders the passes rank 0 assigns; after the passes, the
// first-hit AOVs. Its callers parse before it and write after it; it prints nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <vector>

#include "runtime/render/run/aov.h"
#include "runtime/render/run/pass_job.h"
#include "runtime/render/run/rank_figures.h"
#include "runtime/render/run/render_prepare.h"
#include "runtime/render/run/render_team.h"

namespace cohort {

// What rank 0 has once every pass is in.
struct RenderOutcome {
  FilmState film;
  RenderResult result;              // every rank's rays and passes; rank 0's device figures
  std::vector<RankFigures> ranks;   // every rank's, in rank order
  PassJob::ImageMean image_mean;
  std::optional<AovImages> aovs;    // with --aov or --denoise
  double aov_seconds = 0;           // wall time of the AOV render (after the passes, outside render_seconds)
};

// How a caller follows and stops a render.
struct RenderHooks {
  std::function<bool()> stop_requested;  // asked after every pass: stops the render early
  ProgressCallback progress;             // null: no progress
  // a checkpoint of this render was found: the render continues from its `samples` per pixel
  std::function<void(std::uint32_t samples)> resuming;
};

// What decides the image: a checkpoint may only be resumed by a render that would produce it.
std::uint64_t render_fingerprint(const PreparedRender& render);

// Rank 0: renders the image on its devices and, through `team`, the other ranks; saves and resumes
// the film at `checkpoint` as render.input.checkpoint says.
RenderOutcome run_render_passes(const PreparedRender& render, const RenderTeam& team,
                                const std::filesystem::path& checkpoint, const RenderHooks& hooks);

// Rank 0, after the passes: the AOVs of the image's samples on this rank's first device, when the
// input asks for them (aovs, denoise), into outcome.aovs and outcome.aov_seconds.
void render_first_hit_aovs(const PreparedRender& render, RenderOutcome& outcome);

// Any other rank: renders the passes rank 0 assigns and sends it this rank's figures.
void follow_render(const PreparedRender& render, const RenderTeam& team);

}  // namespace cohort

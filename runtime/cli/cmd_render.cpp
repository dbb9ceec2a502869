// `cohort render`: each rank of the team parses, prepares and renders; rank 0 gathers the image
// and writes the outputs (render_steps.h).
#include <fmt/format.h>

#include "runtime/cli/progress.h"
#include "runtime/cli/render_steps.h"
#ifdef COHORT_HAVE_MPI
#include "runtime/mpi/mpi_team.h"
#endif

namespace cohort {
namespace {

// MPI when an MPI launcher started this process with more than one rank, else a team of one.
std::unique_ptr<RenderTeam> join_render_team() {
#ifdef COHORT_HAVE_MPI
  return join_mpi_team();
#else
  return solo_render_team();
#endif
}

int render_rank(const RenderCommand& command, const RenderTeam& team) {
  RenderInput input = parse_render(command);
  // check where the outputs go before spending time on the render; only rank 0 writes
  const OutputPaths out = output_paths(team.leads() ? command.output : std::string("unused"), command.scene);
  const PreparedRender render = prepare_render(std::move(input), team.local_rank());
  if (team.leads()) report_scene_warnings(render.scene, command.scene);
  const InterruptGuard interrupt;  // on every rank: rank 0 decides when to stop, the others finish their passes
  if (!team.leads()) {
    follow_render(render, team);
    return 0;
  }
  ProgressReporter reporter(stderr);
  RenderOutcome outcome = run_render_passes(
      render, team, out.checkpoint,
      {.stop_requested = [&] { return interrupt.requested(); },
       .progress = [&](const Progress& p) { reporter.update(p); },
       .resuming = [&](std::uint32_t samples) {
         fmt::print("resuming {} at {} spp\n", out.checkpoint.string(), samples);
       }});
  reporter.finish();
  render_first_hit_aovs(render, outcome);
  return write_render(command, render, outcome, out, interrupt);
}

}  // namespace

int run_render(const RenderCommand& command) {
  const auto team = join_render_team();
  return team->run([&] { return render_rank(command, *team); });
}

}  // namespace cohort

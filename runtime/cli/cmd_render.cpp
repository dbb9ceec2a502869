// `cohort render`: each rank of the team parses, prepares and renders; rank 0 gathers the image
// and writes the outputs (render_steps.h).
#include "runtime/cli/render_steps.h"
#include "runtime/render/run/adaptive.h"

namespace cohort {
namespace {

int render_rank(const RenderCommand& command, const RenderTeam& team) {
  RenderPlan plan = parse_render(command);
  // check where the outputs go before spending time on the render; only rank 0 writes
  const OutputPaths out = output_paths(team.leads() ? command.output : std::string("unused"), command.scene);
  const PreparedRender render = prepare_render(std::move(plan), team.local_rank(), team.leads());
  const InterruptGuard interrupt;  // on every rank: rank 0 decides when to stop, the others finish their passes
  if (!team.leads()) {
    follow_render(render, team);
    return 0;
  }
  RenderOutcome outcome =
      run_render_passes(render, team, out.checkpoint, {.stop_requested = [&] { return interrupt.requested(); }});
  // adaptive sampling: the samples every pixel has (a tile that stopped early has fewer than the film's most)
  render_first_hit_aovs(render, outcome);
  return write_render(render, outcome, out, interrupt);
}

}  // namespace

int run_render(const RenderCommand& command) {
  const auto team = join_render_team();
  return team->run([&] { return render_rank(command, *team); });
}

}  // namespace cohort

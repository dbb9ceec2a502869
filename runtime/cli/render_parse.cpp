#include <fmt/format.h>

#include "runtime/backend/open_device.h"
#include "runtime/cli/parse_values.h"
#include "runtime/cli/render_steps.h"
#include "runtime/render/methods/methods.h"
#include "runtime/render/run/adaptive.h"
#include "runtime/render/run/aov.h"
#include "runtime/util/error.h"

namespace cohort {

RenderInput parse_render(const RenderCommand& command) {
  RenderInput input{.scene = command.scene, .settings = command.settings};
  RenderSettings& settings = input.settings;
  std::tie(settings.width, settings.height) = parse_resolution(command.resolution);
  if (is_environment_map_path(command.environment)) input.environment_map = command.environment;
  else if (!command.environment.empty()) settings.environment = parse_rgb("--env", command.environment);
  if (settings.spp == 0 && settings.time_limit <= 0) throw InputError("--spp 0 needs --time SECONDS to say when to stop");
  if (settings.straggler_rays && !find_method(settings.method).wavefront)
    throw InputError(fmt::format("--stragglers reads the rays of a wavefront method's extension launches; --method {} "
                                 "has none (every method traces the same rays: use --method wavefront)",
                                 settings.method));
  if (settings.straggler_rays && command.stats_file.empty())
    throw InputError("--stragglers writes its rays to the --stats file: give --stats FILE.json");
  if (command.memory_limit_mib > 0) input.memory_limit = static_cast<std::uint64_t>(command.memory_limit_mib * 1048576.0);
  input.backend = parse_backend(command.backend);
  input.device = command.device;
  input.program_cache = !command.no_cache;
  input.tree = command.tree;
  input.tree_budget_mib = command.tree_budget_mib;
  input.white_sky = command.white_sky;
  input.fov = command.fov;
  if (!command.aov.empty()) input.aovs = parse_aov_list(command.aov);
  input.denoise = command.denoise;
  input.checkpoint = {.save = command.checkpoint, .resume = command.resume, .seconds = command.checkpoint_seconds};
  if (command.target_error) {
    settings.target_error = parse_target_error(*command.target_error);
    if (settings.spp != 0 && settings.spp <= kAdaptiveFirstRound)
      throw InputError(fmt::format("--target-error needs --spp above {} (every pixel takes the first {} samples before "
                                   "any tile may stop); --spp {} leaves nothing to adapt",
                                   kAdaptiveFirstRound, kAdaptiveFirstRound, settings.spp));
  }
  if (!command.camera_bounds.empty()) input.camera_bounds = parse_six("--camera-bounds", command.camera_bounds);
  return input;
}

}  // namespace cohort

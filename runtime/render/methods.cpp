#include "runtime/render/methods.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "runtime/render/render_params.h"
#include "runtime/util/error.h"

namespace cohort {

const std::vector<Method>& methods() {
  static const std::vector<Method> table = {
      {"naive", "one megakernel, a work item per pixel (the reference)", false, render_naive},
      {"wavefront", "wavefront stages over the whole pool, refilled when it drains", true, render_wavefront},
      {"sc", "wavefront with stream compaction of live paths after every bounce", true, render_sc},
      {"rg", "wavefront with path regeneration into free slots after every bounce", true, render_rg},
      {"sc+rg", "stream compaction and path regeneration", true, render_sc_rg},
      {"hash", "sc+rg, rays sorted by origin and direction hash before traversal (Garanzha & Loop 2010)", true,
       render_hash},
      {"pth", "sc+rg, rays sorted by the coherence code of a partial traversal in local memory (Wang & Deng)",
       true, render_pth},
      {"auto", "every method above renders one pass of the image, timed; the fastest renders the rest", false,
       render_auto},
  };
  return table;
}

std::vector<std::string> method_names() {
  std::vector<std::string> names;
  for (const auto& m : methods()) names.emplace_back(m.name);
  return names;
}

const Method& find_method(const std::string& name) {
  for (const auto& m : methods())
    if (name == m.name) return m;
  throw InputError(fmt::format("--method {}: unknown method (choose from {})", name, fmt::join(method_names(), ", ")));
}

RenderResult render(const Device& cl, const ProgramCache& cache, const DeviceScene& scene, const SceneCamera& camera,
                    const RenderSettings& settings, const ProgressCallback& progress, const RenderControl& control) {
  const Method& method = find_method(settings.method);
  const RenderParams params = make_render_params(scene, camera, settings);
  return method.render(MethodInputs{cl, cache, scene, params, settings, progress, control});
}

}  // namespace cohort

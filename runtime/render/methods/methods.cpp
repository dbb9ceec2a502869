#include "runtime/render/methods/methods.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "runtime/backend/device_support.h"
#include "runtime/render/render_params.h"
#include "runtime/util/error.h"

namespace cohort {

const std::vector<Method>& methods() {
  static const std::vector<Method> table = {
      {"naive", "one megakernel, a work item per pixel (the reference)", false, false, naive_method},
      {"wavefront", "wavefront stages over the whole pool, refilled when it drains", true, false, wavefront_method},
      {"sc", "wavefront with stream compaction of live paths after every bounce", true, false, sc_method},
      {"rg", "wavefront with path regeneration into free slots after every bounce", true, false, rg_method},
      {"sc+rg", "stream compaction and path regeneration", true, false, sc_rg_method},
      {"hash", "sc+rg, rays sorted by origin and direction hash before traversal (Garanzha & Loop 2010)", true,
       true, hash_method},
      {"pth", "sc+rg, rays sorted by the coherence code of a partial traversal in local memory (Wang & Deng)",
       true, true, pth_method},
      {"auto", "the methods above take turns at the first launches, timed; the fastest renders the rest", false,
       false, auto_method},
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

const char* device_default_method(bool is_gpu) { return is_gpu ? "sc+rg" : "naive"; }

RenderResult render(const Device& cl, const ProgramCache& cache, const DeviceScene& scene, const SceneCamera& camera,
                    const RenderSettings& settings, const ProgressCallback& progress, const RenderControl& control) {
  const Method& method = find_method(settings.method);
  if (const DeviceSupport support = device_support(cl.info()); method.sorts && !support.sorts)
    throw InputError(fmt::format("--method {}: not on this device: {}", method.name, support.sort_refusal));
  const RenderParams params = make_render_params(scene, camera, settings);
  const MethodInputs in{cl, cache, scene, params, settings, progress, control};
  const std::unique_ptr<PassLauncher> launcher = method.set_up(in);
  return drive_passes(cl, cache, params, settings, progress, control, *launcher);
}

}  // namespace cohort

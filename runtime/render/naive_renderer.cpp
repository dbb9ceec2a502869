// NAIVE: the megakernel of kernels/naive.cl, one launch per pass.
#include "runtime/render/launch_log.h"
#include "runtime/render/methods.h"
#include "runtime/render/pass_driver.h"

namespace cohort {

RenderResult render_naive(const Device& cl, const ProgramCache& cache, const DeviceScene& scene,
                          const RenderParams& params, const RenderSettings& settings, const ProgressCallback& progress,
                          const RenderControl& control) {
  const DeviceProgram build = cl.build_program(cache, "naive", scene.build_options);
  DeviceKernel kernel = build.kernel("render_naive");
  const std::uint32_t zero = 0;
  DeviceBuffer ray_counter = cl.allocate("ray counter", sizeof(zero), &zero);
  const std::uint32_t pixels = settings.width * settings.height;
  // each pass stays far below 2^32 rays so the 32-bit counter cannot wrap
  const std::uint32_t max_per_pass = std::max<std::uint32_t>(1, (1u << 24) / std::max<std::uint32_t>(pixels, 1));
  bool args_set = false;
  RenderResult result = drive_passes(cl, cache, params, settings, max_per_pass, progress, control,
                                     [&](const PassBuffers& b, const RenderParams&) {
    if (!args_set) {
      kernel.set_arg(0, b.params);
      std::size_t arg = set_scene_args(kernel, 1, scene);
      for (const DeviceBuffer* buf : std::initializer_list<const DeviceBuffer*>{&b.film, &ray_counter, &b.dropped})
        kernel.set_arg(arg++, *buf);
      args_set = true;
    }
    LaunchLog log;
    log.launch(cl, kernel, "render_naive", pixels);
    std::uint32_t rays = 0;
    cl.read(ray_counter, 0, sizeof(rays), &rays);
    cl.write(ray_counter, 0, sizeof(zero), &zero, false);
    return PassOutput{rays, log.collect()};
  });
  result.compile_seconds = build.seconds;
  result.compile_from_cache = build.from_cache;
  return result;
}

}  // namespace cohort

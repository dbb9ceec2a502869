// NAIVE: the megakernel of kernels/naive.cl, one launch per pass.
#include "runtime/cl/kernel_program.h"
#include "runtime/render/launch_log.h"
#include "runtime/render/methods.h"
#include "runtime/render/pass_driver.h"

namespace cohort {

RenderResult render_naive(const ClContext& cl, const ProgramCache& cache, const DeviceScene& scene,
                          const RenderParams& params, const RenderSettings& settings, const ProgressCallback& progress,
                          const RenderControl& control) {
  const ProgramBuild build = build_kernel_program(cl, cache, "naive.cl", scene.build_options);
  cl::Kernel kernel(build.program, "render_naive");
  const std::uint32_t zero = 0;
  cl::Buffer ray_counter = cl.buffer("ray counter", sizeof(zero), &zero);
  const std::uint32_t pixels = settings.width * settings.height;
  // each pass stays far below 2^32 rays so the 32-bit counter cannot wrap
  const std::uint32_t max_per_pass = std::max<std::uint32_t>(1, (1u << 24) / std::max<std::uint32_t>(pixels, 1));
  bool args_set = false;
  RenderResult result = drive_passes(cl, params, settings, max_per_pass, progress, control,
                                     [&](const PassBuffers& b, const RenderParams&) {
    if (!args_set) {
      kernel.setArg(0, b.params);
      cl_uint arg = set_scene_args(kernel, 1, scene);
      for (const cl::Buffer* buf : std::initializer_list<const cl::Buffer*>{&b.film, &ray_counter, &b.dropped}) kernel.setArg(arg++, *buf);
      args_set = true;
    }
    LaunchLog log;
    log.launch(cl, kernel, "render_naive", pixels);
    std::uint32_t rays = 0;
    cl.queue.enqueueReadBuffer(ray_counter, CL_TRUE, 0, sizeof(rays), &rays);
    cl.queue.enqueueWriteBuffer(ray_counter, CL_FALSE, 0, sizeof(zero), &zero);
    return PassOutput{rays, log.collect()};
  });
  result.compile_seconds = build.seconds;
  result.compile_from_cache = build.from_cache;
  return result;
}

}  // namespace cohort

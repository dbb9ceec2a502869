// NAIVE: the megakernel of kernels/naive.cl, one launch per pass.
#include <array>

#include "runtime/render/launch_log.h"
#include "runtime/render/methods.h"
#include "runtime/render/pass_driver.h"

namespace cohort {

RenderResult render_naive(const Device& cl, const ProgramCache& cache, const DeviceScene& scene,
                          const RenderParams& params, const RenderSettings& settings, const ProgressCallback& progress,
                          const RenderControl& control) {
  const DeviceProgram build = cl.build_program(cache, "naive", scene.build_options);
  DeviceKernel kernel = build.kernel("render_naive");
  // NAIVE_COUNTER_* of kernels/common/naive_kernel.h: rays, most nodes one ray visited
  static constexpr std::array<std::uint32_t, 2> kZeros{};
  DeviceBuffer counters = cl.allocate("ray counters", sizeof(kZeros), kZeros.data());
  const std::uint32_t pixels = settings.width * settings.height;
  // each pass stays far below 2^32 rays so the 32-bit counter cannot wrap
  const std::uint32_t max_per_pass = std::max<std::uint32_t>(1, (1u << 24) / std::max<std::uint32_t>(pixels, 1));
  bool args_set = false;
  RenderResult result = drive_passes(cl, cache, params, settings, max_per_pass, progress, control,
                                     [&](const PassBuffers& b, const RenderParams&) {
    if (!args_set) {
      kernel.set_arg(0, b.params);
      std::size_t arg = set_scene_args(kernel, 1, scene);
      for (const DeviceBuffer* buf : std::initializer_list<const DeviceBuffer*>{&b.film, &counters, &b.dropped})
        kernel.set_arg(arg++, *buf);
      args_set = true;
    }
    LaunchLog log;
    log.launch(cl, kernel, "render_naive", pixels);
    std::array<std::uint32_t, 2> read{};
    cl.read(counters, 0, sizeof(read), read.data());
    cl.write(counters, 0, sizeof(kZeros), kZeros.data(), false);
    return PassOutput{read[0], log.collect(), read[1]};
  });
  result.compile_seconds = build.seconds;
  result.compile_from_cache = build.from_cache;
  return result;
}

}  // namespace cohort

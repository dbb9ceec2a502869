// naive: the reference megakernel (kernels/common/naive_kernel.h), one launch per pass; a work item
// traces its pixel's samples through every bounce.
#include <array>

#include "kernels/common/contract.h"
#include "runtime/render/launch_log.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/render/methods/method.h"
#include "runtime/render/pass_driver.h"

namespace cohort {

RenderResult render_naive(const MethodInputs& in) {
  const auto& [cl, cache, scene, params, settings, progress, control] = in;
  const DeviceProgram build = cl.build_program(cache, "naive", scene.build_options);
  DeviceKernel kernel = build.kernel("render_naive");
  static constexpr std::array<std::uint32_t, NAIVE_COUNTER_COUNT> kZeros{};
  DeviceBuffer counters = cl.allocate("ray counters", sizeof(kZeros), kZeros.data());
  const std::uint32_t pixels = settings.width * settings.height;
  // each pass stays far below 2^32 rays so the 32-bit counter cannot wrap
  const std::uint32_t max_per_pass = std::max<std::uint32_t>(1, (1u << 24) / std::max<std::uint32_t>(pixels, 1));
  RenderNaiveArgs args;
  args.scene = scene.kernel_buffers();
  args.counters = counters;
  bool args_set = false;
  RenderResult result = drive_passes(cl, cache, params, settings, max_per_pass, progress, control,
                                     [&](const PassBuffers& b, const RenderParams& p) {
    if (!args_set) {
      args.params = b.params;
      args.film = b.film;
      args.dropped_samples = b.dropped;
      args.pixel_list = b.pixel_list;
      args.bind(kernel);
      args_set = true;
    }
    LaunchLog log;
    log.launch(cl, kernel, "render_naive", pass_pixel_count(&p));
    std::array<std::uint32_t, NAIVE_COUNTER_COUNT> read{};
    cl.read(counters, 0, sizeof(read), read.data());
    cl.write(counters, 0, sizeof(kZeros), kZeros.data(), false);
    PassOutput out{read[NAIVE_COUNTER_RAYS], log.collect(), read[NAIVE_COUNTER_MAX_STEPS]};
    out.host_reads = 1;  // the counters, once the megakernel is done
    return out;
  });
  result.compile_seconds = build.seconds;
  result.compile_from_cache = build.from_cache;
  return result;
}

}  // namespace cohort

// naive: the reference megakernel (kernels/common/wavefront/naive_kernel.h), one launch per pass; a work item
// traces its pixel's samples through every bounce.
#include <algorithm>
#include <array>

#include "kernels/common/core/contract.h"
#include "runtime/render/run/launch_log.h"
#include "runtime/backend/kernel_args.h"
#include "runtime/render/methods/method.h"
#include "runtime/render/run/pass_driver.h"

namespace cohort {
namespace {

class NaiveMethod final : public PassLauncher {
 public:
  explicit NaiveMethod(const MethodInputs& in)
      : cl_(in.device),
        program_(cl_.build_program(in.cache, "naive", in.scene.build_options)),
        kernel_(program_.kernel("render_naive")),
        counters_(cl_.allocate("ray counters", sizeof(kZeros), kZeros.data())),
        // each launch stays far below 2^32 rays so the 32-bit counter cannot wrap
        max_per_launch_(std::max<std::uint32_t>(
            1, (1u << 24) / std::max<std::uint32_t>(in.settings.width * in.settings.height, 1))) {
    args_.scene = in.scene.kernel_buffers();
    args_.counters = counters_;
  }

  std::uint32_t max_samples_per_launch() const override { return max_per_launch_; }

  PassOutput launch(const PassBuffers& b, const RenderParams& p) override {
    // bound at every launch: auto hands a launch its own pixel list
    args_.params = b.params;
    args_.film = b.film;
    args_.dropped_samples = b.dropped;
    args_.pixel_list = b.pixel_list;
    args_.bind(kernel_);
    LaunchLog log;
    log.launch(cl_, kernel_, "render_naive", pass_pixel_count(&p));
    std::array<std::uint32_t, NAIVE_COUNTER_WORDS> read{};
    cl_.read(counters_, 0, sizeof(read), read.data());
    cl_.write(counters_, 0, sizeof(kZeros), kZeros.data(), false);
    std::uint32_t rays = 0, max_steps = 0;  // the slots' sum stays below 2^32 (max_per_launch_)
    for (std::uint32_t slot = 0; slot < NAIVE_COUNTER_WORDS; slot += NAIVE_COUNTER_STRIDE) {
      rays += read[slot + NAIVE_COUNTER_RAYS];
      max_steps = std::max(max_steps, read[slot + NAIVE_COUNTER_MAX_STEPS]);
    }
    PassOutput out{rays, log.collect(), max_steps};
    out.host_reads = 1;  // the counters, once the megakernel is done
    return out;
  }

  void report(RenderResult& result) const override {
    result.compile_seconds += program_.seconds;
    result.compile_from_cache = program_.from_cache;
  }

 private:
  static constexpr std::array<std::uint32_t, NAIVE_COUNTER_WORDS> kZeros{};
  const Device& cl_;
  DeviceProgram program_;
  DeviceKernel kernel_;
  DeviceBuffer counters_;
  std::uint32_t max_per_launch_;
  RenderNaiveArgs args_;
};

}  // namespace

std::unique_ptr<PassLauncher> naive_method(const MethodInputs& in) { return std::make_unique<NaiveMethod>(in); }

}  // namespace cohort

// The rendering and tracing kernels compiled as host C++, with every shading feature (a scene that
// uses fewer features takes the same branches: the features only remove code it cannot reach).
#define COHORT_FEATURE_TEXTURES
#define COHORT_FEATURE_CONDUCTOR
#define COHORT_FEATURE_DIELECTRIC
#define COHORT_FEATURE_PLASTIC
#define COHORT_FEATURE_VOLUME
#include "kernels/common/film/film_kernels.h"
#include "kernels/common/wavefront/naive_kernel.h"
#include "kernels/common/pth/pth_kernels.h"
#include "kernels/common/wavefront/trace_kernels.h"
#include "kernels/common/wavefront/wavefront_kernels.h"

#include "host/host_device.h"

namespace cohort::test {

const HostProgram& host_render_program() {
  static const HostProgram program{
      "",
      {{"render_naive", host_kernel(&render_naive)},
       {"wf_generate", host_kernel(&wf_generate)},
       {"wf_extend", host_kernel(&wf_extend)},
       {"wf_shade", host_kernel(&wf_shade)},
       {"wf_shadow", host_kernel(&wf_shadow)},
       {"wf_finish", host_kernel(&wf_finish)},
       {"wf_accumulate", host_kernel(&wf_accumulate)},
       {"wf_simd_efficiency", host_kernel(&wf_simd_efficiency)},
       {"wf_shadow_max_steps", host_kernel(&wf_shadow_max_steps)},
       {"wf_end_bounce", host_kernel(&wf_end_bounce)},
       {"pth_walk_and_code", host_kernel(&pth_walk_and_code)},
       {"pth_walk_and_code32", host_kernel(&pth_walk_and_code32)},
       {"pth_gather", host_kernel(&pth_gather)},
       {"pth_resume", host_kernel(&pth_resume)},
       {"trace_rays", host_kernel(&trace_rays)},
       {"trace_rays_pth", host_kernel(&trace_rays_pth)},
       {"film_add", host_kernel(&film_add)}}};
  return program;
}

}  // namespace cohort::test

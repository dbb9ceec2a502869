// The host side of kernels/common/core/kernel_params.h: each kernel's parameter list becomes a struct of
// named fields (a DeviceBuffer per buffer, LocalMemory for the local array, the value itself for a
// value) whose bind() sets the kernel's arguments in the order of its signature. Call sites fill
// fields by name and never count argument indices; a buffer left unset is an error at bind time.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "kernels/common/core/kernel_params.h"
#include "kernels/common/core/types.h"
#include "runtime/backend/device.h"

namespace cohort {

namespace kernel_args_detail {

inline void bind_arg(DeviceKernel& kernel, std::size_t& index, const DeviceBuffer& buffer, const char* name) {
  if (!buffer) throw std::logic_error(kernel.name() + ": argument " + name + " is not set");
  kernel.set_arg(index++, buffer);
}
inline void bind_arg(DeviceKernel& kernel, std::size_t& index, const LocalMemory& local, const char*) {
  kernel.set_arg(index++, local);
}
// A feature's table (FEATURE_IN or FEATURE_ABSENT, kernel_params.h): a parameter only of programs
// built with the feature, whose scenes have the buffer; without it there is no parameter to set.
inline void bind_feature_arg(DeviceKernel& kernel, std::size_t& index, const DeviceBuffer& buffer) {
  if (buffer) kernel.set_arg(index++, buffer);
}
template <class T>
void bind_arg(DeviceKernel& kernel, std::size_t& index, const T& value, const char*) {
  kernel.set_arg(index++, value);
}

}  // namespace kernel_args_detail

#define CO_HOST_FIELD(kind, T, name) CO_HOST_FIELD_##kind(T, name)
#define CO_HOST_FIELD_IN(T, name) DeviceBuffer name;
#define CO_HOST_FIELD_FEATURE_IN(T, name) DeviceBuffer name;
#define CO_HOST_FIELD_FEATURE_ABSENT(T, name) DeviceBuffer name;
#define CO_HOST_FIELD_IO(T, name) DeviceBuffer name;
#define CO_HOST_FIELD_UNIFORM(T, name) DeviceBuffer name;
#define CO_HOST_FIELD_LOCAL(T, name) LocalMemory name;
#define CO_HOST_FIELD_VALUE(T, name) T name{};
#define CO_HOST_GROUP_FIELD(Group, member, LIST) Group member;
#define CO_HOST_BIND(kind, T, name) CO_HOST_BIND_##kind(name)
#define CO_HOST_BIND_IN(name) kernel_args_detail::bind_arg(kernel, index, name, #name);
#define CO_HOST_BIND_FEATURE_IN(name) kernel_args_detail::bind_feature_arg(kernel, index, name);
#define CO_HOST_BIND_FEATURE_ABSENT(name) CO_HOST_BIND_FEATURE_IN(name)
#define CO_HOST_BIND_IO(name) CO_HOST_BIND_IN(name)
#define CO_HOST_BIND_UNIFORM(name) CO_HOST_BIND_IN(name)
#define CO_HOST_BIND_LOCAL(name) CO_HOST_BIND_IN(name)
#define CO_HOST_BIND_VALUE(name) CO_HOST_BIND_IN(name)
#define CO_HOST_GROUP_BIND(Group, member, LIST) member.bind(kernel, index);
#define CO_HOST_COUNT(kind, T, name) 1 +
#define CO_HOST_GROUP_COUNT(Group, member, LIST) Group::arg_count +

// A struct `Name` with the fields of LIST, bind(kernel) / bind(kernel, index) (for a group), and
// arg_count, the arguments of LIST; bind(kernel) also sets the kernel's last parameter,
// co_params_end (kernel_params.h), so a kernel has arg_count + 1 parameters.
#define CO_HOST_ARGS(Name, LIST)                                     \
  struct Name {                                                      \
    static constexpr std::size_t arg_count = LIST(CO_HOST_COUNT, CO_HOST_GROUP_COUNT) 0; \
    LIST(CO_HOST_FIELD, CO_HOST_GROUP_FIELD)                         \
    void bind(DeviceKernel& kernel, std::size_t& index) const {      \
      LIST(CO_HOST_BIND, CO_HOST_GROUP_BIND)                         \
    }                                                                \
    void bind(DeviceKernel& kernel) const {                          \
      std::size_t index = 0;                                         \
      bind(kernel, index);                                           \
      kernel.set_arg(index, std::uint32_t{0}); /* co_params_end */   \
    }                                                                \
  };

// Groups, then kernels (a group before the kernels that contain it).
CO_HOST_ARGS(SceneBuffers, SCENE_BUFFERS)
CO_HOST_ARGS(PathBuffers, PATH_BUFFERS)
CO_HOST_ARGS(ShadowBuffers, SHADOW_BUFFERS)
CO_HOST_ARGS(TraceTree, TRACE_TREE_PARAMS)
CO_HOST_ARGS(PthWalk, PTH_WALK_PARAMS)

CO_HOST_ARGS(RenderNaiveArgs, RENDER_NAIVE_PARAMS)
CO_HOST_ARGS(RenderAovArgs, RENDER_AOV_PARAMS)
CO_HOST_ARGS(WfGenerateArgs, WF_GENERATE_PARAMS)
CO_HOST_ARGS(WfExtendArgs, WF_EXTEND_PARAMS)
CO_HOST_ARGS(WfShadeArgs, WF_SHADE_PARAMS)
CO_HOST_ARGS(WfShadowArgs, WF_SHADOW_PARAMS)
CO_HOST_ARGS(WfFinishArgs, WF_FINISH_PARAMS)
CO_HOST_ARGS(WfAccumulateArgs, WF_ACCUMULATE_PARAMS)
CO_HOST_ARGS(WfSimdEfficiencyArgs, WF_SIMD_EFFICIENCY_PARAMS)
CO_HOST_ARGS(WfShadowMaxStepsArgs, WF_SHADOW_MAX_STEPS_PARAMS)
CO_HOST_ARGS(WfEndBounceArgs, WF_END_BOUNCE_PARAMS)
CO_HOST_ARGS(PthWalkAndCodeArgs, PTH_WALK_AND_CODE_PARAMS)
CO_HOST_ARGS(PthWalkAndCode32Args, PTH_WALK_AND_CODE32_PARAMS)
CO_HOST_ARGS(PthGatherArgs, PTH_GATHER_PARAMS)
CO_HOST_ARGS(PthResumeArgs, PTH_RESUME_PARAMS)
CO_HOST_ARGS(TraceRaysArgs, TRACE_RAYS_PARAMS)
CO_HOST_ARGS(TraceRaysStepsArgs, TRACE_RAYS_STEPS_PARAMS)
CO_HOST_ARGS(TraceRaysPthArgs, TRACE_RAYS_PTH_PARAMS)
CO_HOST_ARGS(TraceRaysSpeculativeArgs, TRACE_RAYS_SPECULATIVE_PARAMS)
CO_HOST_ARGS(FilmAddArgs, FILM_ADD_PARAMS)

}  // namespace cohort

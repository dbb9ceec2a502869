// The host side of kernels/common/core/kernel_params.h: every kernel's argument struct sets exactly as
// many arguments as the kernel has parameters (compiled here as host C++), in the order of its
// fields, and refuses a buffer left unset instead of launching with a null argument.
#define COHORT_FEATURE_TEXTURES
#define COHORT_FEATURE_CONDUCTOR
#define COHORT_FEATURE_DIELECTRIC
#define COHORT_FEATURE_PLASTIC
#define COHORT_FEATURE_CLEARCOAT  // the clearcoat table is a parameter only with its option
#define COHORT_FEATURE_SHEEN      // the sheen table likewise
#define COHORT_FEATURE_SPECULAR   // and the specular table
#include "kernels/common/wavefront/aov_kernel.h"
#include "kernels/common/film/film_kernels.h"
#include "kernels/common/wavefront/naive_kernel.h"
#include "kernels/common/pth/pth_kernels.h"
#include "kernels/common/wavefront/trace_kernels.h"
#include "kernels/common/wavefront/wavefront_kernels.h"

#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>

#include "runtime/backend/kernel_args.h"

using namespace cohort;

namespace {

template <class... Params>
constexpr std::size_t arity(void (*)(Params...)) {
  return sizeof...(Params);
}

DeviceBuffer some_buffer() { return DeviceBuffer(std::make_shared<BufferObject>(), 4); }

}  // namespace

TEST(KernelArgs, OneArgumentPerKernelParameter) {
  EXPECT_EQ(RenderNaiveArgs::arg_count + 1, arity(&render_naive));
  EXPECT_EQ(RenderAovArgs::arg_count + 1, arity(&render_aov));
  EXPECT_EQ(WfGenerateArgs::arg_count + 1, arity(&wf_generate));
  EXPECT_EQ(WfExtendArgs::arg_count + 1, arity(&wf_extend));
  EXPECT_EQ(WfShadeArgs::arg_count + 1, arity(&wf_shade));
  EXPECT_EQ(WfShadowArgs::arg_count + 1, arity(&wf_shadow));
  EXPECT_EQ(WfFinishArgs::arg_count + 1, arity(&wf_finish));
  EXPECT_EQ(WfAccumulateArgs::arg_count + 1, arity(&wf_accumulate));
  EXPECT_EQ(WfSimdEfficiencyArgs::arg_count + 1, arity(&wf_simd_efficiency));
  EXPECT_EQ(WfShadowMaxStepsArgs::arg_count + 1, arity(&wf_shadow_max_steps));
  EXPECT_EQ(WfEndBounceArgs::arg_count + 1, arity(&wf_end_bounce));
  EXPECT_EQ(PthWalkAndCodeArgs::arg_count + 1, arity(&pth_walk_and_code));
  EXPECT_EQ(PthWalkAndCode32Args::arg_count + 1, arity(&pth_walk_and_code32));
  EXPECT_EQ(PthGatherArgs::arg_count + 1, arity(&pth_gather));
  EXPECT_EQ(PthResumeArgs::arg_count + 1, arity(&pth_resume));
  EXPECT_EQ(PthResumeArgs::arg_count + 1, arity(&pth_resume_speculative));
  EXPECT_EQ(TraceRaysArgs::arg_count + 1, arity(&trace_rays));
  EXPECT_EQ(TraceRaysStepsArgs::arg_count + 1, arity(&trace_rays_steps));
  EXPECT_EQ(TraceRaysPthArgs::arg_count + 1, arity(&trace_rays_pth));
  EXPECT_EQ(TraceRaysSpeculativeArgs::arg_count + 1, arity(&trace_rays_speculative));
  EXPECT_EQ(FilmAddArgs::arg_count + 1, arity(&film_add));
  // the groups stand for their parameters: 14 scene buffers and the clearcoat, sheen and specular tables
  // (declared here, where the kernels are built with their options), 8 path buffers, 4 shadow buffers
  EXPECT_EQ(SceneBuffers::arg_count, 17u);
  EXPECT_EQ(PathBuffers::arg_count, 8u);
  EXPECT_EQ(ShadowBuffers::arg_count, 4u);
}

TEST(KernelArgs, BindSetsFieldsInSignatureOrder) {
  WfSimdEfficiencyArgs args;
  args.steps = some_buffer();
  args.count = 77;
  args.counters = some_buffer();
  DeviceKernel kernel(nullptr, "wf_simd_efficiency");
  args.bind(kernel);
  ASSERT_EQ(kernel.args().size(), WfSimdEfficiencyArgs::arg_count + 1);  // and co_params_end, last
  const auto* end = std::get_if<ValueArg>(&kernel.args().back());
  ASSERT_TRUE(end && end->bytes.size() == 4);
  const auto* steps = std::get_if<DeviceBuffer>(&kernel.args()[0]);
  const auto* count = std::get_if<ValueArg>(&kernel.args()[1]);
  const auto* counters = std::get_if<DeviceBuffer>(&kernel.args()[2]);
  ASSERT_TRUE(steps && count && counters);
  EXPECT_EQ(steps->object(), args.steps.object());
  EXPECT_EQ(counters->object(), args.counters.object());
  std::uint32_t value = 0;
  ASSERT_EQ(count->bytes.size(), sizeof(value));
  std::memcpy(&value, count->bytes.data(), sizeof(value));
  EXPECT_EQ(value, 77u);
}

// A feature's table (FEATURE_IN) is an argument only where it is set: the programs of a scene
// without clearcoat do not declare it, and the host sets one argument fewer.
TEST(KernelArgs, AFeatureTableIsBoundOnlyWhenSet) {
  SceneBuffers b;
  for (DeviceBuffer* d : {&b.nodes, &b.leaf_triangles, &b.triangles, &b.triangle_material, &b.materials, &b.emitters,
                          &b.triangle_uvs, &b.textures, &b.texels, &b.triangle_colors, &b.triangle_frames, &b.env_texels,
                          &b.env_tables, &b.punctual_lights})
    *d = some_buffer();
  DeviceKernel without(nullptr, "render_naive");
  b.bind(without);
  EXPECT_EQ(without.args().size(), SceneBuffers::arg_count - 3 + 1);  // no table, and co_params_end
  // each table is bound where it is set, in its place after the punctual lights: the coat's, the
  // sheen's, then the specular's
  b.material_sheen = some_buffer();
  DeviceKernel sheen_only(nullptr, "render_naive");
  b.bind(sheen_only);
  ASSERT_EQ(sheen_only.args().size(), SceneBuffers::arg_count - 2 + 1);
  const auto* sheen = std::get_if<DeviceBuffer>(&sheen_only.args()[SceneBuffers::arg_count - 3]);
  ASSERT_TRUE(sheen);
  EXPECT_EQ(sheen->object(), b.material_sheen.object());
  b.material_specular = some_buffer();
  DeviceKernel sheen_specular(nullptr, "render_naive");
  b.bind(sheen_specular);
  ASSERT_EQ(sheen_specular.args().size(), SceneBuffers::arg_count - 1 + 1);
  const auto* specular = std::get_if<DeviceBuffer>(&sheen_specular.args()[SceneBuffers::arg_count - 2]);
  ASSERT_TRUE(specular);
  EXPECT_EQ(specular->object(), b.material_specular.object());
  b.material_coats = some_buffer();
  DeviceKernel with(nullptr, "render_naive");
  b.bind(with);
  ASSERT_EQ(with.args().size(), SceneBuffers::arg_count + 1);
  const auto* coats = std::get_if<DeviceBuffer>(&with.args()[SceneBuffers::arg_count - 3]);
  ASSERT_TRUE(coats);
  EXPECT_EQ(coats->object(), b.material_coats.object());
  sheen = std::get_if<DeviceBuffer>(&with.args()[SceneBuffers::arg_count - 2]);
  ASSERT_TRUE(sheen);
  EXPECT_EQ(sheen->object(), b.material_sheen.object());
  specular = std::get_if<DeviceBuffer>(&with.args()[SceneBuffers::arg_count - 1]);
  ASSERT_TRUE(specular);
  EXPECT_EQ(specular->object(), b.material_specular.object());
}

TEST(KernelArgs, UnsetBufferIsAnErrorNamingIt) {
  WfSimdEfficiencyArgs args;
  args.steps = some_buffer();
  DeviceKernel kernel(nullptr, "wf_simd_efficiency");
  try {
    args.bind(kernel);
    FAIL() << "bind accepted an unset buffer";
  } catch (const std::logic_error& e) {
    EXPECT_NE(std::string(e.what()).find("counters"), std::string::npos) << e.what();
  }
}

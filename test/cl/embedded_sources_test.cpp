// The production table carries no test kernels, and the tests' table finds its kernels together
// with the production headers they include.
#include <gtest/gtest.h>

#include <string>

#include "kernels/test_kernels.h"
#include "runtime/backend/embedded_sources.h"

using namespace cohort;

TEST(EmbeddedSources, ProductionTableHasNoTestKernels) {
  bool has_renderer = false;
  for (const auto& s : embedded_sources()) {
    EXPECT_EQ(std::string(s.path).find("_test"), std::string::npos) << s.path;
    has_renderer |= std::string(s.path) == "wavefront.cl";
  }
  EXPECT_TRUE(has_renderer);
  EXPECT_THROW(expand_kernel_source("bsdf_test.cl"), std::runtime_error);
}

TEST(EmbeddedSources, TestKernelsExpandWithProductionHeaders) {
  for (const char* path : {"bsdf_test.cl", "environment_test.cl", "cuda/bsdf_test.cu"}) {
    const std::string src = expand_test_kernel_source(path);
    EXPECT_NE(src.find("#line 1 \"common/core/port.h\""), std::string::npos) << path;  // a production header
  }
  EXPECT_NE(expand_test_kernel_source("bsdf_test.cl").find("#line 1 \"bsdf_test_kernel.h\""),
            std::string::npos);
  EXPECT_NE(expand_test_kernel_source("naive.cl").find("naive"), std::string::npos);  // production files too
}

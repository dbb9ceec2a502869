// Analytic tests: inside a closed sphere whose surface emits Le everywhere and reflects diffusely
// with albedo rho, radiance is Le * sum_{k<D} rho^k for paths of at most D segments, and
// Le / (1 - rho) without a bound. scenes/furnace-sphere.gltf has Le = 1, rho = 0.5.
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include "render_fixture.h"

using namespace cohort;
using namespace cohort::test;

namespace {

constexpr double kLe = 1.0, kRho = 0.5;

double finite_series(unsigned depth) {
  double sum = 0, term = kLe;
  for (unsigned k = 0; k < depth; ++k, term *= kRho) sum += term;
  return sum;
}

struct FurnaceCase {
  const char* name;
  bool nee, mis, rr;
  unsigned max_depth;  // 0: unbounded
};

class Furnace : public ::testing::TestWithParam<std::tuple<FurnaceCase, const char*>> {};

TEST_P(Furnace, ConvergesToTheAnalyticRadiance) {
  const FurnaceCase c = std::get<0>(GetParam());
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 64;
  s.max_depth = c.max_depth;
  s.nee = c.nee;
  s.mis = c.mis;
  s.russian_roulette = c.rr;
  s.rr_depth = 3;
  s.seed = 7;
  s.method = std::get<1>(GetParam());
  const RenderResult r = render_scene(shipped_scene("furnace-sphere.gltf"), s);
  const double expected = c.max_depth ? finite_series(c.max_depth) : kLe / (1 - kRho);
  EXPECT_EQ(r.dropped_samples, 0u);
  for (int ch = 0; ch < 3; ++ch) {
    const PixelStats st = channel_stats(r.image, ch);
    // 5 standard errors: a false alarm about once in 1.7 million runs; the small absolute term
    // covers float rounding where the estimator has (almost) no variance
    const double bound = 5 * st.standard_error + 1e-4 * expected;
    EXPECT_NEAR(st.mean, expected, bound) << c.name << " channel " << ch << " stderr " << st.standard_error;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Sphere, Furnace,
    ::testing::Combine(::testing::Values(FurnaceCase{"bsdf_only_unbounded", false, false, true, 0},
                      FurnaceCase{"nee_mis_unbounded", true, true, true, 0},
                      FurnaceCase{"nee_without_mis_unbounded", true, false, true, 0},
                      FurnaceCase{"emitters_only_depth1", true, true, false, 1},
                      FurnaceCase{"direct_depth2", true, true, false, 2},
                      FurnaceCase{"bsdf_only_depth4", false, false, false, 4},
                      FurnaceCase{"nee_mis_depth5", true, true, false, 5}),
                       ::testing::Values("naive", "wavefront", "sc", "rg", "sc+rg", "hash", "pth")),
    [](const auto& info) {
      std::string method = std::get<1>(info.param);
      for (char& ch : method)
        if (ch == '+') ch = '_';
      return std::string(std::get<0>(info.param).name) + "_" + method;
    });

}  // namespace

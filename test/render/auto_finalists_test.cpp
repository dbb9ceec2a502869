// auto's choice of finalists from the screen's rates (no device needed).
#include <gtest/gtest.h>

#include <vector>

#include "runtime/render/methods/auto_finalists.h"

namespace cohort {
namespace {

using Finalists = std::vector<std::size_t>;

TEST(AutoFinalists, FastestWithinKeepFirstAtMostThree) {
  // naive far behind; four wavefront methods close together; nothing sorts
  const std::vector<ScreenedMethod> screened{{600, false}, {850, false}, {860, false}, {855, false}, {858, false}};
  EXPECT_EQ(auto_finalists(screened, 0.9, 3), (Finalists{2, 4, 3}));
  EXPECT_EQ(auto_finalists(screened, 0.9, 10), (Finalists{2, 4, 3, 1}));
  EXPECT_EQ(auto_finalists(screened, 0.0, 10), (Finalists{2, 4, 3, 1, 0}));
}

TEST(AutoFinalists, TheBestSortingMethodWithinKeepTakesTheLastPlace) {
  // what the H200 showed through CUDA: at a quarter wave hash and pth screen behind four methods
  // that do not sort, though hash is the fastest at full waves
  const std::vector<ScreenedMethod> screened{{600, false}, {850, false}, {860, false}, {855, false},
                                             {858, false}, {840, true},  {845, true}};
  EXPECT_EQ(auto_finalists(screened, 0.9, 3), (Finalists{2, 4, 6}));
  // already a finalist on its own: nothing moves
  const std::vector<ScreenedMethod> ahead{{600, false}, {850, false}, {860, true}, {855, false}, {858, false}};
  EXPECT_EQ(auto_finalists(ahead, 0.9, 3), (Finalists{2, 4, 3}));
  // a sorting method below keep stays out
  const std::vector<ScreenedMethod> behind{{850, false}, {860, false}, {855, false}, {858, false}, {700, true}};
  EXPECT_EQ(auto_finalists(behind, 0.9, 3), (Finalists{1, 3, 2}));
  // one place is no final: the screen's fastest keeps it
  EXPECT_EQ(auto_finalists(screened, 0.9, 1), (Finalists{2}));
  EXPECT_EQ(auto_finalists(screened, 0.9, 2), (Finalists{2, 6}));
}

TEST(AutoFinalists, UnscreenedMethodsNeverQualify) {
  const std::vector<ScreenedMethod> screened{{-1, false}, {500, false}, {-1, true}};
  EXPECT_EQ(auto_finalists(screened, 0.0, 3), (Finalists{1}));
  EXPECT_TRUE(auto_finalists(std::vector<ScreenedMethod>{{-1, false}}, 0.9, 3).empty());
  EXPECT_TRUE(auto_finalists(screened, 0.9, 0).empty());
}


TEST(AutoPick, TheDefaultStaysUnlessBeatenBeyondItsOwnNoise) {
  // naive (0) timed at 100 and 96: 4 % noise, a bar of 8 %
  const std::vector<double> rates = {100, 105, 90, -1};
  EXPECT_EQ(auto_pick(rates, 0, 96, 0.05), 0u);
  const std::vector<double> faster = {100, 109, 90, -1};
  EXPECT_EQ(auto_pick(faster, 0, 96, 0.05), 1u);
}

TEST(AutoPick, AQuietProbeStillNeedsTheMinimumMargin) {
  const std::vector<double> rates = {100, 104, 103};
  EXPECT_EQ(auto_pick(rates, 0, 100, 0.05), 0u);
  const std::vector<double> clear = {100, 104, 106};
  EXPECT_EQ(auto_pick(clear, 0, 100, 0.05), 2u);
}

TEST(AutoPick, TheBetterOfTheDefaultsTwoTimingsIsTheReference) {
  // a default slowed in its first timing (the other core was busy) is not beaten by that dip
  const std::vector<double> rates = {40, 95, 90};
  EXPECT_EQ(auto_pick(rates, 0, 100, 0.05), 0u);
}

TEST(AutoPick, TheFastestOfThoseAboveTheBarWins) {
  const std::vector<double> rates = {30, 80, 100, 90};
  EXPECT_EQ(auto_pick(rates, 0, 31, 0.05), 2u);
}

TEST(AutoPick, AnUntimedSecondTimingLeavesTheMinimumMargin) {
  const std::vector<double> rates = {100, 106};
  EXPECT_EQ(auto_pick(rates, 0, -1, 0.05), 1u);
}

}  // namespace
}  // namespace cohort

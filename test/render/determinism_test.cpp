#include <gtest/gtest.h>

#include <cstring>

#include "render_fixture.h"

using namespace cohort;
using namespace cohort::test;

TEST(Determinism, SameSeedSameImageBitForBit) {
  RenderSettings s;
  s.width = 48;
  s.height = 40;
  s.spp = 8;
  s.seed = 3;
  const auto path = shipped_scene("cornell-box.gltf");
  const RenderResult a = render_scene(path, s);
  const RenderResult b = render_scene(path, s);
  ASSERT_EQ(a.image.rgb.size(), b.image.rgb.size());
  EXPECT_EQ(0, std::memcmp(a.image.rgb.data(), b.image.rgb.data(), a.image.rgb.size() * sizeof(float)));
  EXPECT_EQ(a.rays, b.rays);

  s.seed = 4;
  const RenderResult c = render_scene(path, s);
  EXPECT_NE(0, std::memcmp(a.image.rgb.data(), c.image.rgb.data(), a.image.rgb.size() * sizeof(float)));
}

TEST(Determinism, CornellBoxIsLitAndFinite) {
  RenderSettings s;
  s.width = s.height = 32;
  s.spp = 4;
  s.max_depth = 6;
  const RenderResult r = render_scene(shipped_scene("cornell-box.gltf"), s);
  double sum = 0;
  for (float v : r.image.rgb) {
    ASSERT_TRUE(std::isfinite(v));
    ASSERT_GE(v, 0.f);
    sum += v;
  }
  EXPECT_GT(sum / r.image.rgb.size(), 0.05);  // a black image would prove nothing
  EXPECT_EQ(r.samples, 4u);
  EXPECT_GT(r.rays, 32u * 32u * 4u);
}

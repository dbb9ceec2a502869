// Proof against an independent renderer: the shipped Cornell box, rendered by Cohort, converges to
// Mitsuba 3's render of cbox-rgb.xml (test/reference/, made by scripts/reference: 10,368 spp,
// max_depth 6, box filter, 128x128). Bounds come from the per-pixel spread of the difference, so
// a bias of a fraction of a percent fails while noise does not.
#include <gtest/gtest.h>

#include <cmath>

#include "render_fixture.h"

using namespace cohort;
using namespace cohort::test;

TEST(MitsubaReference, CornellBoxMatchesMitsuba3) {
  const Image reference = read_exr(std::filesystem::path(COHORT_SOURCE_DIR) / "test/reference/cornell-box-mitsuba-rgb.exr");
  ASSERT_EQ(reference.width, 128);
  ASSERT_EQ(reference.height, 128);
  RenderSettings s;
  s.width = s.height = 128;
  s.spp = 256;
  s.max_depth = 6;
  s.seed = 1;
  const RenderResult r = render_scene(shipped_scene("cornell-box.gltf"), s);
  // the whole image, then 8 x 8 blocks: 5 standard errors each (a false alarm about once in
  // 10^4 runs over all 195 checks), plus 0.2% of the value for the reference's own noise
  for (int c = 0; c < 3; ++c) {
    const BlockDifference all = block_difference(r.image, reference, 0, 0, 128, 128, c);
    EXPECT_LT(std::abs(all.mean), 5 * all.standard_error + 2e-3 * all.reference_mean)
        << "channel " << c << ": cohort - mitsuba = " << all.mean << " of " << all.reference_mean;
    for (int by = 0; by < 8; ++by)
      for (int bx = 0; bx < 8; ++bx) {
        const BlockDifference d = block_difference(r.image, reference, bx * 16, by * 16, 16, 16, c);
        EXPECT_LT(std::abs(d.mean), 5 * d.standard_error + 2e-3 * d.reference_mean + 1e-6)
            << "block (" << bx << ", " << by << ") channel " << c << ": " << d.mean << " of " << d.reference_mean;
      }
  }
}

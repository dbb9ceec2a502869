// The coherence code of kernels/common/pth/coherence.h, compiled for the host, against the layouts of
// runtime/render/pth/coherence.cpp: keys fit the width the sort is given, and the two-point key's end
// part is the cell of the estimated end point.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "kernels/common/pth/coherence.h"
#include "runtime/render/pth/coherence.h"

using namespace cohort;

namespace {

const Bounds kBox{{-1.f, -2.f, 0.f}, {3.f, 2.f, 1.f}};

}  // namespace

// A key wider than key_bits would sort by bits the 32-bit sort never sees (or, for 32-bit keys,
// lose them in the store): every layout's codes must stay below 2^key_bits.
TEST(CoherenceCode, CodesFitTheLayoutsWidth) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> unit(0.f, 1.f), sym(-1.f, 1.f);
  for (const char* layout : {"origin-first", "two-point", "pth-32", "end:10,dir:1", "origin:4,end:4,pth:2,dir:1",
                             "paper", "dir:16,pth:6,origin:4", "origin-uniform:10,end:10,pth:2"}) {
    const CodeParams c = parse_code_layout(layout, 0, kBox);
    // an adaptive grid's boundaries: any sorted values will do
    std::vector<float> boundaries;
    const std::uint32_t per_axis = c.origin_bits ? (1u << c.origin_bits) - 1u : 0u;
    for (std::uint32_t a = 0; a < 3; ++a)
      for (std::uint32_t k = 0; k < per_axis; ++k) boundaries.push_back(-2.f + 5.f * float(k + 1) / float(per_axis + 1));
    std::uint64_t seen = 0;
    for (int i = 0; i < 2000; ++i) {
      const co_vec3 org = v3(-1.f + 4.f * unit(rng), -2.f + 4.f * unit(rng), unit(rng));
      const co_vec3 dir = v3_normalize(v3(sym(rng), sym(rng), sym(rng)));
      const std::uint32_t pth_bits = c.pth_levels ? std::uint32_t(rng()) & ((1u << (2 * c.pth_levels)) - 1u) : 0u;
      const std::uint64_t code = coherence_code(&c, boundaries.data(), org, dir, pth_bits, 10.f * unit(rng));
      if (c.key_bits < 64) {
        EXPECT_LT(code, std::uint64_t(1) << c.key_bits) << layout;
      }
      seen |= code;
    }
    // and every part reaches the top bit: the parts tile the key without a gap
    EXPECT_EQ(seen >> (c.key_bits - 1), 1u) << layout;
  }
  EXPECT_LE(parse_code_layout(default_code_layout(true), 0, kBox).key_bits, 32u);
  EXPECT_LE(parse_code_layout(default_code_layout(false), 0, kBox).key_bits, 32u);
}

TEST(CoherenceCode, EndPartIsTheCellOfTheEstimatedEndPoint) {
  const CodeParams end = parse_code_layout("end:6", 0, kBox);
  const CodeParams origin = parse_code_layout("origin-uniform:6", 0, kBox);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.f, 1.f), sym(-1.f, 1.f);
  for (int i = 0; i < 1000; ++i) {
    const co_vec3 org = v3(-1.f + 4.f * unit(rng), -2.f + 4.f * unit(rng), unit(rng));
    const co_vec3 dir = v3_normalize(v3(sym(rng), sym(rng), sym(rng)));
    const float t = 3.f * unit(rng);
    EXPECT_EQ(coherence_code(&end, nullptr, org, dir, 0u, t),
              coherence_code(&origin, nullptr, v3_madd(org, dir, t), dir, 0u, 0.f));
  }
  // the estimate: the previous segment's length from segment 2 on, never past the box's exit
  EXPECT_EQ(estimated_end(1u, 0.5f, 4.f), 4.f);
  EXPECT_EQ(estimated_end(2u, 0.5f, 4.f), 0.5f);
  EXPECT_EQ(estimated_end(3u, INFINITY, 4.f), 4.f);
}

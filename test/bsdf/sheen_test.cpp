// KHR_materials_sheen (kernels/common/shading/sheen.h, bsdf.h's BSDF_SHEEN and bsdf_sheen_select): the
// log its powers go through against double precision, the albedo table against the lobe integrated
// here, the stochastic layering against the glTF sum it stands for, and the white furnace.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>

#include "bsdf/bsdf_check.h"

using namespace cohort::bsdf_test;

namespace {

// Distance in floats between a float and a double reference rounded to float.
double ulps_from(float got, double want) {
  const float w = static_cast<float>(want);
  if (got == w) return 0.0;
  const double ulp = std::ldexp(1.0, std::ilogb(w) - 23);
  return std::abs(double(got) - want) / ulp;
}

co_vec3 at_cos(double mu) { return v3(static_cast<float>(std::sqrt(1.0 - mu * mu)), 0.0f, static_cast<float>(mu)); }

// The glTF base used below: a white (or `base`) Lambertian, roughness 1, not metal, not transmissive.
Bsdf layered(co_vec3 sheen, float roughness, co_vec3 wi, float u_select, co_vec3 base = v3_splat(1.0f)) {
  Bsdf b;
  if (!bsdf_sheen_select(sheen, roughness, wi, &u_select, &b)) b = bsdf_from_gltf(base, 0.0f, 1.0f, 0.0f, 1.5f, u_select);
  return b;
}

}  // namespace

TEST(SheenMath, CoLogMatchesDoublePrecision) {
  TestRng rng(3);
  double worst = 0;
  float worst_x = 0;
  for (int i = 0; i < 2000000; ++i) {
    // every binade of the normal floats, and densely around 1 where log is small
    float x;
    if (i % 2) {
      const std::uint32_t bits = 0x00800000u + static_cast<std::uint32_t>(rng.next_u64() % (0x7f7fffffu - 0x00800000u));
      std::memcpy(&x, &bits, 4);
    } else {
      x = 0.5f + 1.5f * rng.next();
    }
    const double e = ulps_from(co_log(x), std::log(double(x)));
    if (e > worst) worst = e, worst_x = x;
  }
  std::printf("co_log: at most %.2f ulp from double precision (at %.9g)\n", worst, worst_x);
  EXPECT_LE(worst, 3.0);
  EXPECT_EQ(co_log(1.0f), 0.0f);
  EXPECT_EQ(co_log(0.0f), -INFINITY);
  EXPECT_EQ(co_log(1e-40f), -INFINITY) << "subnormals count as 0 on every device";
  EXPECT_EQ(co_log(-1.0f), -INFINITY);
  EXPECT_EQ(co_log(INFINITY), INFINITY);
  EXPECT_TRUE(std::isnan(co_log(std::numeric_limits<float>::quiet_NaN())));
  // the powers the sheen takes: x^c of the Lambda fit (c near 0.2) and sin^(1/alpha) (up to 500)
  double worst_pow = 0;
  for (int i = 0; i < 200000; ++i) {
    const float x = rng.next(), y = (i % 2) ? 0.15f + 0.06f * rng.next() : 0.5f + 499.5f * rng.next();
    const double want = std::pow(double(x), double(y));
    if (want < 1e-30) {
      EXPECT_LE(co_pow(x, y), 1e-29f);
      continue;
    }
    // x^y's relative error is exp's own and the absolute error of y log x: log's few ulp (and the
    // product's rounding) times |y ln x|
    const double bound = 4.0 + 3.0 * std::abs(double(y) * std::log(double(x)));
    const double e = ulps_from(co_pow(x, y), want);
    worst_pow = std::max(worst_pow, e / bound);
    EXPECT_LE(e, bound) << x << "^" << y;
  }
  EXPECT_EQ(co_pow(0.0f, 0.2f), 0.0f);
  std::printf("co_pow: at most %.2f of its bound\n", worst_pow);
}

// The table (written by scripts/lib/sheen-albedo.py) against the albedo of bsdf_eval integrated here by
// adaptive quadrature: at its nodes within 2e-3 (the kernel's float arithmetic against the generator's
// double) and between them within the bilinear interpolation's error.
TEST(SheenAlbedo, TableIsTheLobesAlbedo) {
  double worst_node = 0, worst_between = 0;  // relative, where the albedo is above 0.05
  for (int j : {6, 9, 15, 25, 31}) {
    for (int i : {6, 10, 15, 20, 25, 30}) {
      for (bool node : {true, false}) {
        const double x = (i + (node ? 0.0 : 0.5)) / 31.0, r = (j + (node ? 0.0 : 0.5)) / 31.0;
        if (r > 1.0) continue;
        const co_vec3 wi = at_cos(x * x);
        const Bsdf b = bsdf_sheen(v3_splat(1.0f), static_cast<float>(r));
        const double e = integrate_sphere([&](co_vec3 wo) { return double(bsdf_eval(&b, wi, wo).x); }, 0.0, 1.0);
        const double table = sheen_albedo(wi.z, static_cast<float>(r));
        const double rel = e > 0.05 ? std::abs(table - e) / e : 0.0;
        (node ? worst_node : worst_between) = std::max(node ? worst_node : worst_between, rel);
        EXPECT_NEAR(table, e, node ? 2e-3 * e : 2e-2 * e + 2e-3) << "cos_i " << wi.z << " roughness " << r;
      }
    }
  }
  std::printf("sheen albedo table (where above 0.05): within %.2g relative at its nodes, %.2g between them\n",
              worst_node, worst_between);
}

// Averaged over u_select, the BSDF a shading point takes evaluates to the glTF layering,
// f_sheen + base (1 - max3(sheen) E(cos_i)): the selection's probability and the lobe's 1/q cancel.
TEST(SheenLayer, SelectionAveragesToTheGltfSum) {
  const co_vec3 sheen = v3(0.9f, 0.5f, 0.3f), base = v3(0.1f, 0.2f, 0.6f);
  const int n = 1 << 16;
  for (float roughness : {0.3f, 0.8f}) {
    for (double theta : {20.0, 60.0, 80.0}) {
      const co_vec3 wi = direction_at(theta);
      const co_vec3 wo = direction_at(35.0, false);
      const co_vec3 wo_mirror = v3(-wo.x, wo.y, wo.z);
      for (const co_vec3& w : {wo, wo_mirror}) {
        double sum[3] = {0, 0, 0};
        for (int k = 0; k < n; ++k) {
          const Bsdf b = layered(sheen, roughness, wi, (k + 0.5f) / n, base);
          const co_vec3 f = bsdf_eval(&b, wi, w);
          sum[0] += f.x, sum[1] += f.y, sum[2] += f.z;
        }
        const Bsdf lobe = bsdf_sheen(sheen, roughness);
        const co_vec3 fs = bsdf_eval(&lobe, wi, w);
        const double scale = 1.0 - 0.9 * sheen_albedo(wi.z, roughness);
        const double want[3] = {fs.x + base.x * w.z / kPi * scale, fs.y + base.y * w.z / kPi * scale,
                                fs.z + base.z * w.z / kPi * scale};
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(sum[c] / n, want[c], 2e-4 * want[c] + 1e-6) << theta << " deg, roughness " << roughness;
      }
    }
  }
  // no sheen: u_select passes through untouched, and the base is what it was
  float u = 0.37f;
  Bsdf b;
  EXPECT_FALSE(bsdf_sheen_select(v3_splat(0.0f), 0.5f, direction_at(30.0), &u, &b));
  EXPECT_EQ(u, 0.37f);
}

// White furnace of the layered material: a white sheen over a white Lambertian reflects everything
// (E + (1 - E) = 1, up to the table) where the lobe's albedo is at most 1; a coloured sheen reflects
// less in every channel. Monte Carlo over u_select and the sampled direction, both sides.
TEST(SheenLayer, WhiteFurnaceOverWhiteLambertian) {
  for (float roughness : {0.3f, 0.5f, 0.8f, 1.0f}) {
    for (double theta : {0.0, 30.0, 60.0, 75.0}) {
      for (bool below : {false, true}) {
        for (bool white : {true, false}) {
          const co_vec3 sheen = white ? v3_splat(1.0f) : v3(0.9f, 0.5f, 0.3f);
          const co_vec3 wi = direction_at(theta, below);
          TestRng rng(11);
          const int n = 1 << 17;
          double sum[3] = {0, 0, 0}, sum2 = 0;
          for (int k = 0; k < n; ++k) {
            const Bsdf b = layered(sheen, roughness, wi, rng.next());
            const BsdfSample s = bsdf_sample(&b, wi, rng.next(), rng.next(), rng.next());
            if (!s.flags) continue;
            sum[0] += s.weight.x, sum[1] += s.weight.y, sum[2] += s.weight.z;
            sum2 += double(s.weight.x) * s.weight.x;
          }
          const double mean = sum[0] / n, sigma = std::sqrt((sum2 / n - mean * mean) / n);
          if (white) {
            EXPECT_NEAR(mean, 1.0, 5 * sigma + 2e-3) << "roughness " << roughness << ", " << theta << " deg";
          } else {
            for (double v : sum) EXPECT_LE(v / n, 1.0 + 5 * sigma) << "roughness " << roughness << ", " << theta;
            EXPECT_LT(sum[2] / n, sum[0] / n) << "the red sheen reflects more red than blue";
          }
        }
      }
    }
  }
}

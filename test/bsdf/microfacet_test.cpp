// The building blocks of kernels/common/shading/microfacet.h against independent double-precision values.
#include <gtest/gtest.h>

#include <cmath>

#include "bsdf/bsdf_check.h"

using namespace cohort::bsdf_test;

TEST(Microfacet, SinCosOfTwoPiUIsAccurate) {
  double worst = 0;
  for (int i = 0; i <= (1 << 20); ++i) {
    const float u = static_cast<float>(i) / float(1 << 20);
    float s, c;
    co_sincos_2pi(u, &s, &c);
    const double phi = 2.0 * kPi * double(u);
    worst = std::max({worst, std::abs(s - std::sin(phi)), std::abs(c - std::cos(phi))});
  }
  std::printf("co_sincos_2pi: max abs error %.3g\n", worst);
  EXPECT_LT(worst, 2.5e-7);  // about 2 ulp of 1
}

TEST(Microfacet, FresnelMatchesReference) {
  for (double eta : {1.05, 1.33, 1.5, 2.4})
    for (int i = -100; i <= 100; ++i) {
      const float cos_i = static_cast<float>(i) / 100.0f;
      float cos_t, eta_ti;
      const float f = fresnel_dielectric(cos_i, static_cast<float>(eta), &cos_t, &eta_ti);
      ASSERT_NEAR(f, fresnel_dielectric_ref(cos_i, eta), 1e-5) << eta << " " << cos_i;  // float cancels near the critical angle
      if (f < 1.0f && cos_i != 0.0f) {  // Snell: sin_t = eta_ti sin_i, on the other side
        const double sin_i = std::sqrt(1.0 - double(cos_i) * cos_i), sin_t = std::sqrt(1.0 - double(cos_t) * cos_t);
        ASSERT_NEAR(sin_t, eta_ti * sin_i, 1e-5);
        ASSERT_LT(cos_t * cos_i, 0.0f);
      }
    }
  const co_vec3 one = fresnel_schlick(v3_splat(1.0f), 0.3f);
  EXPECT_EQ(one.x, 1.0f);
  EXPECT_NEAR(fresnel_schlick(v3_splat(0.04f), 0.0f).x, 1.0f, 1e-6);
  // F_dr fits against the integral 2 int_0^1 F(mu) mu dmu (eta = IOR of the incident side's other side)
  for (double eta : {1.33, 1.5, 1.0 / 1.5}) {
    double integral = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
      const double mu = (i + 0.5) / n;
      integral += 2.0 * fresnel_dielectric_ref(mu, eta) * mu / n;
    }
    EXPECT_NEAR(fresnel_diffuse_reflectance(static_cast<float>(eta)), integral, 1.5e-3 * integral) << eta;
  }
}

// D is normalised on projected area, int D(m) cos(theta_m) dm = 1, and the visible-normal density
// integrates to 1 for every view direction (Heitz 2014, eq. 2 and 17).
TEST(Microfacet, DistributionsAreNormalised) {
  for (float alpha : {0.05f, 0.2f, 0.6f, 1.0f}) {
    const double proj = integrate_sphere([&](co_vec3 m) { return double(ggx_d(m, alpha)) * m.z; }, 0.0, 1.0);
    EXPECT_NEAR(proj, 1.0, 1e-5) << alpha;
    for (double theta : {0.0, 45.0, 85.0}) {
      const co_vec3 wi = direction_at(theta);
      const double vis = integrate_sphere([&](co_vec3 m) { return double(ggx_vndf_pdf(wi, m, alpha)); }, 0.0, 1.0);
      EXPECT_NEAR(vis, 1.0, 1e-4) << alpha << " " << theta;
    }
  }
}

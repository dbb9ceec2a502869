// KHR_materials_specular (kernels/common/shading/specular.h, bsdf.h's BSDF_SPECULAR): the re-shaped
// Fresnel term against the exact Fresnel in double precision, the stochastic layering against the glTF
// mix it stands for, specular 0 as exactly the Lambertian, the metal and the transmissive dielectric
// left as they are, and the white furnace.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include <fmt/format.h>

#include "bsdf/bsdf_check.h"
#include "common/shading/specular.h"

using namespace cohort::bsdf_test;

namespace {

double f0_of(double eta) { return (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0)); }

// The layered material's BSDF at a shading point as path_shade takes it: bsdf_from_gltf's choice,
// then the layering in place of its opaque dielectric.
Bsdf layered(co_vec3 base, float metallic, float roughness, float transmission, float ior, co_vec3 color,
             float specular, co_vec3 wi, float u_select) {
  const Bsdf b = bsdf_from_gltf(base, metallic, roughness, transmission, ior, u_select);
  return bsdf_specular_base(b, base, metallic, roughness, transmission, ior, color, specular, wi, u_select);
}

bool same_bits(const Bsdf& a, const Bsdf& b) { return std::memcmp(&a, &b, sizeof(Bsdf)) == 0; }
bool same_bits(const BsdfSample& a, const BsdfSample& b) { return std::memcmp(&a, &b, sizeof(BsdfSample)) == 0; }

}  // namespace

// F = f0' + (f90' - f0') s with s the exact Fresnel's shape: the exact Fresnel itself at specular 1 and
// colour 1, f0' at normal incidence and f90' at grazing, and within [f0', f90'] everywhere (s is clamped
// to [0, 1]; the exact Fresnel dips below f0 only for IORs above about 3.7).
TEST(SpecularFresnel, ReshapesTheExactFresnel) {
  for (double eta : {1.01, 1.33, 1.5, 2.0, 3.0}) {
    const float f0 = static_cast<float>(f0_of(eta));
    double worst = 0;
    for (int i = 0; i <= 1000; ++i) {
      const double c = i / 1000.0;
      const co_vec3 f = specular_fresnel(v3_splat(f0), 1.0f, static_cast<float>(c), static_cast<float>(eta));
      const double want = c == 0.0 ? 1.0 : fresnel_dielectric_ref(c, eta);
      worst = std::max(worst, std::abs(double(f.x) - want));
      ASSERT_NEAR(f.x, want, 2e-6) << "eta " << eta << ", cos " << c;
      ASSERT_EQ(f.x, f.y);
      ASSERT_EQ(f.x, f.z);
    }
    std::printf("specular 1, colour 1, eta %.2f: the exact Fresnel within %.2g\n", eta, worst);
  }
  const co_vec3 f0 = v3(0.06f, 0.024f, 0.0096f);
  const float f90 = 0.6f;
  EXPECT_EQ(specular_fresnel(f0, f90, 1.0f, 1.5f).x, f0.x);
  EXPECT_EQ(specular_fresnel(f0, f90, 0.0f, 1.5f).z, f90);
  for (double eta : {1.5, 5.0, 10.0})
    for (int i = 0; i <= 200; ++i) {
      const co_vec3 f = specular_fresnel(f0, f90, i / 200.0f, static_cast<float>(eta));
      EXPECT_GE(f.x, f0.x);
      EXPECT_LE(f.x, f90);
      EXPECT_GE(f.z, f0.z);
      EXPECT_LE(f.z, f90);
    }
}

// Averaged over u_select, the BSDF a shading point takes evaluates to glTF's layering,
// (1 - max3 F(cos_i)) base cos_o / pi + F f_specular: the choice's probability and the lobe's 1/q cancel.
TEST(SpecularLayer, SelectionAveragesToTheGltfMix) {
  const co_vec3 base = v3(0.1f, 0.5f, 0.3f), color = v3(2.5f, 1.0f, 0.4f);
  const float specular = 0.6f, eta = 1.5f;
  const int n = 1 << 16;
  for (float roughness : {0.3f, 0.8f, 1.0f}) {
    for (double theta : {20.0, 60.0, 80.0}) {
      const co_vec3 wi = direction_at(theta);
      const co_vec3 wo = direction_at(35.0);
      const co_vec3 wo_mirror = v3(-wi.x, -wi.y, wi.z);  // in the lobe's peak
      for (const co_vec3& w : {wo, wo_mirror}) {
        double sum[3] = {0, 0, 0};
        for (int k = 0; k < n; ++k) {
          const Bsdf b = layered(base, 0.0f, roughness, 0.0f, eta, color, specular, wi, (k + 0.5f) / n);
          const co_vec3 f = bsdf_eval(&b, wi, w);
          sum[0] += f.x, sum[1] += f.y, sum[2] += f.z;
        }
        const double f0 = f0_of(eta);
        const co_vec3 f0_tint = v3(float(std::min(f0 * 2.5, 1.0) * specular), float(f0 * specular),
                                   float(f0 * 0.4 * specular));
        const Bsdf lobe = bsdf_specular(eta, roughness * roughness, f0_tint, specular, 1.0f);
        const co_vec3 fs = bsdf_eval(&lobe, wi, w);
        // max3 F(cos_i): red, the largest colour, in double precision
        const double s = (fresnel_dielectric_ref(wi.z, eta) - f0) / (1.0 - f0);
        const double keep = 1.0 - (f0_tint.x + (specular - f0_tint.x) * s);
        const double want[3] = {fs.x + base.x * w.z / kPi * keep, fs.y + base.y * w.z / kPi * keep,
                                fs.z + base.z * w.z / kPi * keep};
        for (int c = 0; c < 3; ++c)
          EXPECT_NEAR(sum[c] / n, want[c], 2e-4 * want[c] + 1e-6) << theta << " deg, roughness " << roughness;
      }
    }
  }
}

// Specular 0 (whatever the colour) is exactly the Lambertian of the base colour: the same BSDF, bit for
// bit, at every u_select and roughness, and so the same samples; not the plastic, whose internal
// reflections would scale the base by 1 / (1 - F_dr).
TEST(SpecularLayer, SpecularZeroIsExactlyTheLambertian) {
  const co_vec3 base = v3(0.8f, 0.5f, 0.2f);
  TestRng rng(5);
  for (float roughness : {0.0f, 0.3f, 1.0f})
    for (double theta : {0.0, 45.0, 85.0})
      for (bool below : {false, true}) {
        const co_vec3 wi = direction_at(theta, below);
        for (int k = 0; k < 256; ++k) {
          const float u = rng.next();
          const Bsdf b = layered(base, 0.0f, roughness, 0.0f, 1.5f, v3(3.0f, 1.0f, 0.0f), 0.0f, wi, u);
          const Bsdf lambert = bsdf_diffuse(base);
          ASSERT_TRUE(same_bits(b, lambert)) << "roughness " << roughness << ", " << theta << " deg";
          const float ul = rng.next(), u1 = rng.next(), u2 = rng.next();
          ASSERT_TRUE(same_bits(bsdf_sample(&b, wi, ul, u1, u2), bsdf_sample(&lambert, wi, ul, u1, u2)));
        }
      }
}

// The metal and the transmissive dielectric are bsdf_from_gltf's, bit for bit (the layering is the
// opaque dielectric's only), and the opaque part's share of u_select is spread over [0, 1) again: with
// metallic 0.3 and transmission 0.5, the lobe's share of the opaque part is q.
TEST(SpecularLayer, MetalAndTransmissionStayAsTheyAre) {
  const co_vec3 base = v3(0.8f, 0.5f, 0.2f), wi = direction_at(40.0);
  const float metallic = 0.3f, transmission = 0.5f, specular = 0.5f;
  const int n = 1 << 16;
  int lobe = 0, opaque = 0;
  for (int k = 0; k < n; ++k) {
    const float u = (k + 0.5f) / n;
    const Bsdf core = bsdf_from_gltf(base, metallic, 0.4f, transmission, 1.5f, u);
    const Bsdf b = layered(base, metallic, 0.4f, transmission, 1.5f, v3_splat(1.0f), specular, wi, u);
    if (core.type == BSDF_CONDUCTOR || core.type == BSDF_DIELECTRIC) {
      ASSERT_TRUE(same_bits(b, core)) << u;
      continue;
    }
    ASSERT_EQ(core.type, BSDF_PLASTIC);
    ++opaque;
    lobe += b.type == BSDF_SPECULAR;
    ASSERT_TRUE(b.type == BSDF_SPECULAR || same_bits(b, bsdf_diffuse(base))) << u;
  }
  EXPECT_NEAR(double(opaque) / n, 0.7 * 0.5, 1e-3);
  const double f0 = f0_of(1.5);
  const double q = specular * (f0 + (1.0 - f0) * (fresnel_dielectric_ref(wi.z, 1.5) - f0) / (1.0 - f0));
  EXPECT_NEAR(double(lobe) / opaque, q, 2e-3);
}

// Roughness 1 with the extension is the layering with a GGX lobe of alpha 1 (the roughness-1 Lambertian
// of bsdf_from_gltf stands for Mitsuba's diffuse in scenes without the extension).
TEST(SpecularLayer, RoughnessOneKeepsItsGgxLobe) {
  const co_vec3 wi = direction_at(30.0);
  const Bsdf b = layered(v3_splat(0.5f), 0.0f, 1.0f, 0.0f, 1.5f, v3_splat(1.0f), 0.5f, wi, 0.0f);
  EXPECT_EQ(b.type, BSDF_SPECULAR);
  EXPECT_EQ(b.alpha, 1.0f);
  EXPECT_EQ(layered(v3_splat(0.5f), 0.0f, 1.0f, 0.0f, 1.5f, v3_splat(1.0f), 0.5f, wi, 0.99f).type, BSDF_DIFFUSE);
}

// White furnace of the layered material over a white Lambertian, the choice drawn as the path tracer
// draws it: specular 1 and colour 1 reflect exactly 1 when smooth (every sample weighs F / q = 1 or 1)
// and at most 1 + 1e-3 when rough (the lobe's albedo passes F(cos_i) a little at medium roughness, as the
// coat's); a coloured or weaker specular reflects at most 1 too, and less blue than red for a red tint.
TEST(SpecularLayer, WhiteFurnaceReflectsAtMostAll) {
  for (float roughness : {0.0f, 0.1f, 0.3f, 0.7f, 1.0f})
    for (double theta : {0.0, 10.0, 45.0, 60.0, 80.0, 89.0})
      for (bool below : {false, true})
        for (int kind = 0; kind < 3; ++kind) {
          const co_vec3 color = kind == 2 ? v3(8.0f, 1.0f, 0.2f) : v3_splat(1.0f);
          const float specular = kind == 1 ? 0.3f : 1.0f;
          const co_vec3 wi = direction_at(theta, below);
          TestRng rng(static_cast<std::uint64_t>(1000 * roughness + theta) * 6 + 2 * kind + below);
          constexpr int n = 1 << 17;
          double sum[3] = {0, 0, 0}, sum2 = 0;
          for (int k = 0; k < n; ++k) {
            const Bsdf b = layered(v3_splat(1.0f), 0.0f, roughness, 0.0f, 1.5f, color, specular, wi, rng.next());
            const BsdfSample s = bsdf_sample(&b, wi, rng.next(), rng.next(), rng.next());
            if (!s.flags) continue;
            sum[0] += s.weight.x, sum[1] += s.weight.y, sum[2] += s.weight.z;
            sum2 += double(s.weight.x) * s.weight.x;
          }
          const double mean = sum[0] / n, sigma = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
          const std::string name = fmt::format("roughness {} theta {}{} kind {}", roughness, theta, below ? " below" : "", kind);
          if (kind == 0) std::printf("specular 1 over white: %-34s albedo %.5f +- %.5f\n", name.c_str(), mean, sigma);
          for (double v : sum) EXPECT_LE(v / n, 1.0 + 5.0 * sigma + 1e-3) << name;
          if (roughness == 0.0f && kind < 2) {
            EXPECT_NEAR(mean, 1.0, 1e-5) << name;  // every sample weighs 1
          }
          if (kind == 2 && theta < 85.0) {
            EXPECT_LT(sum[2], sum[0]) << name;
          }
        }
}

// Consistency of sample / eval / pdf, reciprocity, energy conservation and white-furnace albedos
// (docs/decisions.md: 1 for Lambertian, smooth dielectric and smooth conductor of albedo 1; for rough
// microfacet BSDFs the directional albedo integrated numerically on the host).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "bsdf/bsdf_check.h"

using namespace cohort::bsdf_test;

namespace {

float rel_diff(float a, float b) {
  const float m = std::max(std::abs(a), std::abs(b));
  return m > 0 ? std::abs(a - b) / m : 0.0f;
}

// Energy carried by a sample: the radiance weight with the (eta_i/eta_t)^2 of refraction undone,
// as a furnace measures it (a closed dielectric object enters and leaves, and the factors cancel).
double energy_of(const BsdfSample& s) {
  const double w = s.weight.x;
  return (s.flags & BSDF_TRANSMISSION) ? w * double(s.eta) * double(s.eta) : w;
}

// Eval in the same energy units, as a function of wo.
double energy_eval(const Bsdf& b, co_vec3 wi, co_vec3 wo) {
  double f = bsdf_eval(&b, wi, wo).x;
  if (b.type == BSDF_DIELECTRIC && wi.z * wo.z < 0) {
    const double eta_r = wi.z > 0 ? b.eta : 1.0 / b.eta;
    f *= eta_r * eta_r;
  }
  return f;
}

struct Albedo {
  double mean, sigma;  // Monte Carlo estimate and its standard error
};

// E[energy_of(sample)] over n samples, in fixed blocks summed in order (deterministic under TBB).
Albedo albedo_mc(const Config& c, std::size_t n, std::uint64_t seed) {
  constexpr std::size_t kBlocks = 64;
  std::vector<double> sum(kBlocks, 0.0), sum2(kBlocks, 0.0);
  tbb::parallel_for(std::size_t(0), kBlocks, [&](std::size_t blk) {
    TestRng rng(seed * 1000 + blk);
    for (std::size_t i = 0; i < n / kBlocks; ++i) {
      const float ul = rng.next(), u1 = rng.next(), u2 = rng.next();
      const double e = energy_of(bsdf_sample(&c.bsdf, c.wi, ul, u1, u2));
      sum[blk] += e;
      sum2[blk] += e * e;
    }
  });
  double s = 0, s2 = 0;
  for (std::size_t b = 0; b < kBlocks; ++b) {
    s += sum[b];
    s2 += sum2[b];
  }
  const double m = static_cast<double>(n / kBlocks * kBlocks);
  const double mean = s / m;
  const double var = std::max(0.0, s2 / m - mean * mean);
  return {mean, std::sqrt(var / m)};
}

// Integral of energy_eval over the sphere (non-delta lobes only), by adaptive quadrature per cell.
double albedo_quadrature(const Config& c) {
  const Bsdf b = c.bsdf;
  const co_vec3 wi = c.wi;
  return integrate_sphere([&](co_vec3 wo) { return energy_eval(b, wi, wo); }, -1.0, 1.0, 1e-4);
}

bool is_smooth(const Bsdf& b) { return b.alpha < BSDF_SMOOTH_ALPHA; }

}  // namespace

// sample's weight == eval / pdf and sample's pdf == pdf(wi, wo) (relative 1e-3) wherever the sample
// is not a delta; delta directions have eval = pdf = 0 for pure delta BSDFs.
TEST(BsdfConsistency, SampleAgreesWithEvalAndPdf) {
  std::size_t checked = 0;
  for (const Config& c : standard_configs(false)) {
    const auto queries = make_queries(c, 20000, 5);
    std::size_t bad_pdf = 0, bad_weight = 0, bad_delta = 0, valid = 0;
    float worst_pdf = 0, worst_weight = 0;
    for (const BsdfTestIn& q : queries) {
      const BsdfTestOut r = bsdf_test_run(&q);
      const BsdfSample& s = r.sample;
      if (s.flags == 0u) continue;
      ++valid;
      EXPECT_TRUE(v3_is_finite(s.weight) && s.weight.x >= 0 && s.weight.y >= 0 && s.weight.z >= 0) << c.name;
      EXPECT_NEAR(v3_length(s.wo), 1.0f, 1e-5f) << c.name;
      if (s.flags & BSDF_DELTA) {
        if (bsdf_is_delta(&c.bsdf) && (r.pdf_sample != 0.0f || v3_max_component(r.eval_sample) != 0.0f)) ++bad_delta;
        continue;
      }
      const float dp = rel_diff(s.pdf, r.pdf_sample);
      worst_pdf = std::max(worst_pdf, dp);
      if (dp > 1e-3f) ++bad_pdf;
      for (int ch = 0; ch < 3; ++ch) {
        const float w = ch == 0 ? s.weight.x : ch == 1 ? s.weight.y : s.weight.z;
        const float e = ch == 0 ? r.eval_sample.x : ch == 1 ? r.eval_sample.y : r.eval_sample.z;
        const float dw = rel_diff(w, e / r.pdf_sample);
        worst_weight = std::max(worst_weight, dw);
        if (dw > 1e-3f) ++bad_weight;
      }
    }
    EXPECT_GT(valid, queries.size() / 2) << c.name;
    EXPECT_EQ(bad_pdf, 0u) << c.name << ": worst relative pdf difference " << worst_pdf;
    EXPECT_EQ(bad_weight, 0u) << c.name << ": worst relative weight difference " << worst_weight;
    EXPECT_EQ(bad_delta, 0u) << c.name;
    checked += valid;
  }
  std::printf("checked %zu samples\n", checked);
}

// eval(a, b) / |cos b| == eval(b, a) / |cos a| for every reflection lobe; for refraction the
// radiance BTDF obeys f(a, b) / eta_a^2 = f(b, a) / eta_b^2, eta_x the IOR on the side of x (Veach
// 1997, eq. 5.14, with his light-side direction as our second argument).
TEST(BsdfConsistency, Reciprocity) {
  TestRng rng(11);
  int pairs = 0;
  double worst = 0;
  for (const Config& c : standard_configs(false)) {
    if (is_smooth(c.bsdf) && c.bsdf.type != BSDF_PLASTIC) continue;
    for (int i = 0; i < 2000; ++i) {
      co_vec3 a = sphere_direction(2.0 * rng.next() - 1.0, 2.0 * kPi * rng.next());
      co_vec3 b = sphere_direction(2.0 * rng.next() - 1.0, 2.0 * kPi * rng.next());
      if (c.bsdf.type != BSDF_DIELECTRIC) {
        // reflection-only: both on one side (the two-sided BSDFs mirror the lower side)
        b.z = std::abs(b.z) * (a.z < 0 ? -1.0f : 1.0f);
      }
      if (std::abs(a.z) < 1e-3f || std::abs(b.z) < 1e-3f) continue;
      const co_vec3 fab = bsdf_eval(&c.bsdf, a, b), fba = bsdf_eval(&c.bsdf, b, a);
      double lhs = fab.y / std::abs(b.z), rhs = fba.y / std::abs(a.z);
      if (a.z * b.z < 0) {
        const double eta_a = a.z > 0 ? 1.0 : c.bsdf.eta, eta_b = b.z > 0 ? 1.0 : c.bsdf.eta;
        lhs /= eta_a * eta_a;
        rhs /= eta_b * eta_b;
      }
      const double m = std::max(std::abs(lhs), std::abs(rhs));
      if (m == 0) continue;
      ++pairs;
      // refraction rounds worse: its Jacobian divides by (wi.m + eta wo.m)^2, a difference of
      // terms of opposite sign, and near the critical angle 1 - F from the dense side cancels; a
      // wrong formula is off by O(1), not by 0.5% (or 1e-6 absolute, on values of order 0.1-10)
      const double tol = a.z * b.z < 0 ? 5e-3 : 2e-4;
      if (m > 1e-3) worst = std::max(worst, std::abs(lhs - rhs) / m);
      ASSERT_LE(std::abs(lhs - rhs), tol * m + 1e-6) << c.name << " a=(" << a.x << "," << a.y << "," << a.z
                                                      << ") b=(" << b.x << "," << b.y << "," << b.z << ")";
    }
  }
  std::printf("%d reciprocal pairs checked, worst relative difference %.3g where f/cos > 1e-3\n", pairs, worst);
  EXPECT_GT(pairs, 20000);
}

// The pdf and the sampler of a two-sided BSDF treat the back exactly as the mirrored front.
TEST(BsdfConsistency, TwoSidedMirrorsTheBack) {
  for (const Config& c : standard_configs(false)) {
    if (c.bsdf.type == BSDF_DIELECTRIC || c.wi.z < 0) continue;
    co_vec3 back = c.wi;
    back.z = -back.z;
    TestRng rng(3);
    for (int i = 0; i < 200; ++i) {
      const float ul = rng.next(), u1 = rng.next(), u2 = rng.next();
      const BsdfSample f = bsdf_sample(&c.bsdf, c.wi, ul, u1, u2), b = bsdf_sample(&c.bsdf, back, ul, u1, u2);
      ASSERT_EQ(f.flags, b.flags) << c.name;
      ASSERT_EQ(f.wo.z, -b.wo.z) << c.name;
      ASSERT_EQ(f.pdf, b.pdf) << c.name;
      ASSERT_EQ(f.weight.x, b.weight.x) << c.name;
    }
  }
}

// Energy: the directional albedo (energy units) never exceeds 1 for white BSDFs.
TEST(BsdfEnergy, AlbedoAtMostOne) {
  for (const Config& c : standard_configs(true)) {
    const Albedo a = albedo_mc(c, 1u << 18, 21);
    std::printf("%-34s albedo %.5f +- %.5f\n", c.name.c_str(), a.mean, a.sigma);
    // 5 sigma of noise, and 2e-3 for the F_dr fit of the plastic (relative error 0.1% at IOR 1.5)
    EXPECT_LE(a.mean, 1.0 + 5.0 * a.sigma + 2e-3) << c.name;
  }
}

// White furnace for the energy-conserving BSDFs: directional albedo 1.
TEST(BsdfFurnace, EnergyConservingBsdfsReflectEverything) {
  const co_vec3 one = v3_splat(1.0f);
  for (double theta : {0.0, 10.0, 45.0, 60.0, 80.0, 89.0}) {
    for (bool below : {false, true}) {
      const Config cs[] = {
          make_config("diffuse", bsdf_diffuse(one), -1, theta, below),
          make_config("smooth_conductor", bsdf_conductor(one, 0.0f), -1, theta, below),
          make_config("smooth_dielectric", bsdf_dielectric(1.5f, 0.0f, one), -1, theta, below),
          make_config("smooth_dielectric_eta1.33", bsdf_dielectric(1.33f, 0.0f, one), -1, theta, below),
      };
      for (const Config& c : cs) {
        const Albedo a = albedo_mc(c, 1u << 16, 7);
        EXPECT_NEAR(a.mean, 1.0, 1e-5) << c.name;  // every sample carries exactly the energy 1
      }
      // the smooth plastic with a white base: 1 up to the F_dr fit of Mitsuba (0.1% at IOR 1.5)
      const Config p = make_config("smooth_plastic", bsdf_plastic(one, 1.5f, 0.0f), -1, theta, below);
      const Albedo a = albedo_mc(p, 1u << 20, 8);
      EXPECT_NEAR(a.mean, 1.0, 5.0 * a.sigma + 1.5e-3) << p.name << " sigma " << a.sigma;
    }
  }
}

// glTF's clearcoat over a white Lambertian as the path tracer combines them (shading/clearcoat.h):
// the coat with probability q = c F(cos_i) and weight c / q, else the base. The expected energy is
// c A_coat + (1 - c F) with A_coat the coat's albedo: exactly 1 for a smooth coat (A_coat = F). A
// rough coat's albedo may pass F(cos_i) a little at medium roughness (F at the microfacets averages
// above F about the normal, as for the rough plastic's coat): measured at most 1.0006 (45 degrees,
// roughness 0.3), hence the 1e-3; it falls well below 1 at high roughness and grazing angles.
TEST(BsdfFurnace, ClearcoatOverWhiteLambertianReflectsAtMostAll) {
  const Bsdf base = bsdf_diffuse(v3_splat(1.0f));
  for (double c : {0.3, 1.0})
    for (double roughness : {0.0, 0.1, 0.3, 0.7, 1.0})
      for (double theta : {0.0, 10.0, 45.0, 60.0, 80.0, 89.0})
        for (bool below : {false, true}) {
          const co_vec3 wi = direction_at(theta, below);
          const double q = float(c) * fresnel_dielectric_r(std::fabs(wi.z), 1.5f);
          const Bsdf coat = bsdf_coat(1.5f, float(roughness * roughness), float(c / q));
          constexpr std::size_t n = 1u << 17;
          double sum = 0, sum2 = 0;
          TestRng rng(static_cast<std::uint64_t>(1000 * c + 100 * roughness + theta) * 2 + below);
          for (std::size_t i = 0; i < n; ++i) {
            const float u_select = rng.next(), ul = rng.next(), u1 = rng.next(), u2 = rng.next();
            const BsdfSample s = u_select < q ? bsdf_sample(&coat, wi, ul, u1, u2) : bsdf_sample(&base, wi, ul, u1, u2);
            const double e = s.flags ? double(s.weight.x) : 0.0;
            sum += e;
            sum2 += e * e;
          }
          const double mean = sum / n, sigma = std::sqrt(std::max(0.0, sum2 / n - mean * mean) / n);
          const std::string name = fmt::format("c {} roughness {} theta {}{}", c, roughness, theta, below ? " below" : "");
          std::printf("clearcoat over white: %-40s albedo %.5f +- %.5f\n", name.c_str(), mean, sigma);
          EXPECT_LE(mean, 1.0 + 5.0 * sigma + 1e-3) << name;
          if (roughness == 0.0) {
            EXPECT_NEAR(mean, 1.0, 1e-5) << name;  // every sample carries exactly 1
          }
        }
}

// Radiance through a smooth dielectric: entering scales by 1/eta^2, leaving by eta^2, and a ray that
// enters and leaves again through a parallel face comes out with weight 1 (glass slab in a furnace).
TEST(BsdfFurnace, SmoothDielectricRadianceScalingCancelsThroughASlab) {
  const Bsdf glass = bsdf_dielectric(1.5f, 0.0f, v3_splat(1.0f));
  for (double theta : {0.0, 30.0, 70.0}) {
    const co_vec3 wi = direction_at(theta);
    const BsdfSample in = bsdf_sample(&glass, wi, 0.999f, 0.5f, 0.5f);  // u_lobe >= F: refract
    ASSERT_TRUE(in.flags & BSDF_TRANSMISSION);
    EXPECT_NEAR(in.weight.x, 1.0 / (1.5 * 1.5), 1e-6);
    EXPECT_NEAR(in.eta, 1.5f, 1e-6);
    // at the far face the path continues from inside: wi there is -in.wo mirrored to the normal
    // side of that (parallel) face, i.e. the same local direction with z still negative
    const co_vec3 wi2 = v3(-in.wo.x, -in.wo.y, in.wo.z);
    const BsdfSample out = bsdf_sample(&glass, wi2, 0.999f, 0.5f, 0.5f);
    ASSERT_TRUE(out.flags & BSDF_TRANSMISSION);
    EXPECT_NEAR(out.weight.x * in.weight.x, 1.0, 1e-5);
    EXPECT_NEAR(out.wo.z, wi.z, 1e-5);  // leaves parallel to where it came from
  }
}

// Rough BSDFs lose energy with single scattering: their furnace value is the albedo integrated
// numerically (quadrature of eval), which the sampler's Monte Carlo estimate must reproduce.
TEST(BsdfFurnace, RoughBsdfsMatchNumericallyIntegratedAlbedo) {
  int n = 0;
  for (const Config& c : standard_configs(true)) {
    if (is_smooth(c.bsdf) || c.bsdf.type == BSDF_DIFFUSE) continue;
    const Albedo a = albedo_mc(c, 1u << 19, 31);
    const double q = albedo_quadrature(c);
    std::printf("%-34s albedo MC %.5f +- %.5f, quadrature %.5f\n", c.name.c_str(), a.mean, a.sigma, q);
    EXPECT_NEAR(a.mean, q, 5.0 * a.sigma + 5e-4) << c.name;  // quadrature: 1e-4 relative per cell
    EXPECT_LE(q, 1.0 + 2e-3) << c.name;
    ++n;
  }
  EXPECT_GT(n, 30);
}

// As roughness goes to 0 the rough dielectric must approach the smooth one (albedo 1): this holds
// only with Walter's transmission Jacobian and the right normalisation of D and G.
TEST(BsdfFurnace, RoughDielectricTendsToSmooth) {
  for (double theta : {10.0, 45.0, 70.0}) {
    for (bool below : {false, true}) {
      const Config c = make_config("dielectric", bsdf_dielectric(1.5f, 0.01f * 0.01f * 25.0f, v3_splat(1.0f)), 0.05,
                                   theta, below);
      const double q = albedo_quadrature(c);
      const Albedo a = albedo_mc(c, 1u << 18, 41);
      EXPECT_NEAR(q, 1.0, 0.01) << c.name;
      EXPECT_NEAR(a.mean, 1.0, 0.01) << c.name;
    }
  }
}

// A conductor with F0 = 1 conserves energy when smooth and loses some, increasingly with roughness
// and grazing angles, when rough (no multiple scattering).
TEST(BsdfFurnace, RoughConductorLosesEnergyMonotonically) {
  for (double theta : {45.0, 80.0}) {
    double previous = 1.0 + 1e-6;
    for (double r : {0.1, 0.3, 0.7, 1.0}) {
      const Config c = make_config("conductor", bsdf_conductor(v3_splat(1.0f), float(r * r)), r, theta);
      const double q = albedo_quadrature(c);
      EXPECT_LT(q, previous) << c.name;
      EXPECT_GT(q, 0.3) << c.name;  // GGX at alpha 1 keeps ~40% (Kulla & Conty 2017)
      previous = q;
    }
  }
}

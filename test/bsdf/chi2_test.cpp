// Chi-square goodness of fit of bsdf_sample against bsdf_pdf (and the reference delta-lobe
// probabilities) for every configuration of standard_configs(), after Mitsuba's test suite. Also
// shows that the test has power: BSDFs with the classic bugs (a pdf that misses a Jacobian or a
// factor of the visible-normal density, a 2% normalisation error) are rejected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <mutex>

#include "bsdf/bsdf_check.h"

using namespace cohort::bsdf_test;

namespace {

constexpr std::size_t kSamples = 1u << 20;
constexpr double kAlpha = 0.01;  // probability that the whole suite rejects correct BSDFs

const std::vector<Config>& configs() {
  static const std::vector<Config> c = standard_configs(false);
  return c;
}
// every chi-square test of the suite counts towards the Sidak correction, mutants included
int test_count() { return static_cast<int>(configs().size()) + 8; }
double threshold() { return sidak_alpha(kAlpha, test_count()); }

struct Summary {
  std::mutex mutex;
  int tests = 0;
  double min_p = 1.0;
  std::string min_name;
  ~Summary() {
    if (tests)
      std::printf("chi-square summary: %d configurations, smallest p-value %.4g (%s), Sidak threshold %.3g\n", tests,
                  min_p, min_name.c_str(), threshold());
  }
} summary;

class Chi2 : public ::testing::TestWithParam<std::size_t> {};

TEST_P(Chi2, SampleMatchesPdf) {
  const Config& c = configs()[GetParam()];
  const auto queries = make_queries(c, kSamples, 1000 + GetParam());
  const auto samples = sample_host(queries);
  const FitReport rep = goodness_of_fit(c, samples);
  std::printf("%-34s chi2 %9.1f  dof %4d  p %.4f  (pdf integrates to %.6f)\n", c.name.c_str(), rep.chi2.statistic,
              rep.chi2.dof, rep.chi2.p_value, rep.total_pdf);
  ASSERT_TRUE(rep.chi2.error.empty()) << c.name << ": " << rep.chi2.error;
  EXPECT_GE(rep.chi2.p_value, threshold()) << c.name << ": sample() does not follow pdf()";
  std::lock_guard<std::mutex> lock(summary.mutex);
  ++summary.tests;
  if (rep.chi2.p_value < summary.min_p) {
    summary.min_p = rep.chi2.p_value;
    summary.min_name = c.name;
  }
}

INSTANTIATE_TEST_SUITE_P(AllBsdfs, Chi2, ::testing::Range(std::size_t(0), configs().size()),
                         [](const ::testing::TestParamInfo<std::size_t>& info) { return configs()[info.param].name; });

}  // namespace

// ---- The test must be able to fail ----------------------------------------------------------------

namespace {

double mutant_p(const Config& c, const std::function<double(co_vec3)>& wrong_pdf) {
  const auto samples = sample_host(make_queries(c, kSamples, 77));
  const FitReport rep = goodness_of_fit(c, samples, wrong_pdf);
  std::printf("mutant %-27s chi2 %9.1f  dof %4d  p %.3g%s\n", c.name.c_str(), rep.chi2.statistic, rep.chi2.dof,
              rep.chi2.p_value, rep.chi2.error.empty() ? "" : (" (" + rep.chi2.error + ")").c_str());
  return rep.chi2.error.empty() ? rep.chi2.p_value : 0.0;
}

}  // namespace

TEST(Chi2Power, RejectsPdfOffByTwoPercent) {
  const Config c = make_config("diffuse", bsdf_diffuse(v3_splat(0.5f)), -1, 30);
  EXPECT_LT(mutant_p(c, [&](co_vec3 wo) { return 1.02 * bsdf_pdf(&c.bsdf, c.wi, wo); }), threshold());
}

TEST(Chi2Power, RejectsReflectionWithoutHalfVectorJacobian) {
  for (double r : {0.3, 0.7}) {
    const Config c = make_config("conductor", bsdf_conductor(v3_splat(1.0f), float(r * r)), r, 45);
    // density of the half vector used as if it were the density of wo (1 / (4 wo.m) missing)
    auto wrong = [&](co_vec3 wo) {
      const co_vec3 m = v3_normalize(v3_add(c.wi, wo));
      return wo.z > 0 ? double(ggx_vndf_pdf(c.wi, m, c.bsdf.alpha)) : 0.0;
    };
    EXPECT_LT(mutant_p(c, wrong), threshold()) << r;
  }
}

TEST(Chi2Power, RejectsDistributionOfNormalsInsteadOfVisibleNormals) {
  for (double r : {0.3, 0.7}) {
    const Config c = make_config("conductor", bsdf_conductor(v3_splat(1.0f), float(r * r)), r, 80);
    // D(m) cos(theta_m) / (4 wo.m): the pdf of classic (Walter 2007) sampling, not of the VNDF
    auto wrong = [&](co_vec3 wo) {
      if (!(wo.z > 0)) return 0.0;
      const co_vec3 m = v3_normalize(v3_add(c.wi, wo));
      return double(ggx_d(m, c.bsdf.alpha) * m.z / (4.0f * v3_dot(wo, m)));
    };
    EXPECT_LT(mutant_p(c, wrong), threshold()) << r;
  }
}

TEST(Chi2Power, RejectsTransmissionWithoutEtaSquared) {
  for (double r : {0.3, 0.7}) {
    const Config c = make_config("dielectric", bsdf_dielectric(1.5f, float(r * r), v3_splat(1.0f)), r, 45);
    // refraction Jacobian written as |wo.m| / (wi.m + eta wo.m)^2, without Walter's eta^2
    auto wrong = [&](co_vec3 wo) {
      const double p = bsdf_pdf(&c.bsdf, c.wi, wo);
      return wo.z * c.wi.z < 0 ? p / (1.5 * 1.5) : p;
    };
    EXPECT_LT(mutant_p(c, wrong), threshold()) << r;
  }
}

TEST(Chi2Power, RejectsWrongFresnelLobeProbability) {
  const Config c = make_config("smooth_dielectric", bsdf_dielectric(1.5f, 0.0f, v3_splat(1.0f)), -1, 60);
  // a sampler that picks reflection with Schlick's F instead of the exact F must be caught: here,
  // the samples come from the right sampler and the expectation from the Schlick probability
  const auto samples = sample_host(make_queries(c, kSamples, 78));
  std::vector<double> exp(kCells, 0.0), obs = histogram(samples);
  const double f0 = 0.04, m = 1.0 - c.wi.z;
  const double schlick = f0 + (1.0 - f0) * m * m * m * m * m;
  exp[kZBins * kPhiBins] = schlick * kSamples;
  exp[kZBins * kPhiBins + 1] = (1.0 - schlick) * kSamples;
  const Chi2Result r = chi2_from_counts(obs, exp);
  std::printf("mutant schlick lobe probability: chi2 %.1f dof %d p %.3g\n", r.statistic, r.dof, r.p_value);
  EXPECT_LT(r.p_value, threshold());
}

TEST(Chi2Math, IncompleteGammaMatchesKnownValues) {
  // chi-square survival function values (R: pchisq(x, k, lower.tail = FALSE))
  EXPECT_NEAR(chi2_p_value(3.841458820694124, 1), 0.05, 1e-9);
  EXPECT_NEAR(chi2_p_value(18.30703805327515, 10), 0.05, 1e-9);
  EXPECT_NEAR(chi2_p_value(135.8067, 100), 0.01, 1e-6);
  EXPECT_NEAR(chi2_p_value(1000.0, 1000), 0.49405, 1e-4);
  EXPECT_NEAR(chi2_p_value(2.0, 2), std::exp(-1.0), 1e-12);
  EXPECT_NEAR(sidak_alpha(0.01, 1), 0.01, 1e-15);
  EXPECT_NEAR(1.0 - std::pow(1.0 - sidak_alpha(0.01, 50), 50), 0.01, 1e-12);
}

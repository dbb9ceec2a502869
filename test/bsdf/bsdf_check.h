// Test machinery for the BSDFs of kernels/common/shading/bsdf.h: configurations, a deterministic random
// stream, numerical integration over the sphere, and the chi-square goodness-of-fit test (after the
// one in Mitsuba's test suite: binned sphere, pdf integrated per bin, low-expectation bins pooled,
// p-value from the regularised incomplete gamma function, Sidak correction over the tests).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "test/kernels/bsdf_test_io.h"

namespace cohort::bsdf_test {

inline constexpr double kPi = 3.14159265358979323846;

// ---- Random numbers: SplitMix64 (Steele et al. 2014), 24-bit floats in [0, 1) as rng_next --------
struct TestRng {
  std::uint64_t state;
  // The seed goes through the mixer first: SplitMix64 streams whose states differ by a multiple of
  // the increment are the same stream shifted, so seeds 1, 2, 3 must not map to such states.
  explicit TestRng(std::uint64_t seed) : state(mix(seed ^ 0x632be59bd9b4e019ull)) {}
  static std::uint64_t mix(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  std::uint64_t next_u64() { return mix(state += 0x9e3779b97f4a7c15ull); }
  float next() { return static_cast<float>(next_u64() >> 40) * (1.0f / 16777216.0f); }
};

// ---- Configurations -------------------------------------------------------------------------------
struct Config {
  std::string name;
  Bsdf bsdf;
  co_vec3 wi;
};

// wi at polar angle theta (degrees) from the normal, at a fixed azimuth that is not a bin edge;
// below = true puts it under the surface (inside a dielectric, or the back of a two-sided BSDF).
co_vec3 direction_at(double theta_deg, bool below = false);
Config make_config(const std::string& family, const Bsdf& bsdf, double roughness, double theta_deg,
                   bool below = false);

// The configurations every test suite walks: all BSDF families, roughness 0.1 / 0.3 / 0.7 / 1.0
// (glTF roughness; alpha = roughness^2), incident angles 10 / 45 / 80 degrees, both sides of a
// dielectric. `white` makes every colour 1 (furnace tests).
std::vector<Config> standard_configs(bool white);

// ---- Reference formulas in double precision, written independently of the device code -------------
double fresnel_dielectric_ref(double cos_i, double eta);
// Probability with which the smooth plastic picks its delta coat (Mitsuba's formula).
double plastic_coat_probability_ref(const Bsdf& b, double cos_i);

// ---- Integration over the sphere -----------------------------------------------------------------
// Directions are parameterised by (z = cos theta, phi), where d(omega) = dz dphi, so equal
// rectangles are equal solid angles.
co_vec3 sphere_direction(double z, double phi);
// Adaptive 2D Gauss-Legendre (4x4 nodes, split into quarters until two levels agree to
// max(abs_tol, rel_tol * value) or max_depth is reached) of f over a (z, phi) rectangle. The first
// min_depth levels are always split: the support of a pdf may cover only a corner of a rectangle
// (transmission near the pole), where all 16 nodes of the whole rectangle can read 0.
double integrate_rect(const std::function<double(co_vec3)>& f, double z0, double z1, double p0, double p1,
                      double abs_tol = 1e-10, double rel_tol = 1e-5, int max_depth = 7, int min_depth = 2);

// Integral of f over the cells of the chi-square grid (below) whose z lies in [z_lo, z_hi]
// (z_lo, z_hi on cell edges: multiples of 0.1), each cell by integrate_rect, in parallel.
double integrate_sphere(const std::function<double(co_vec3)>& f, double z_lo = -1.0, double z_hi = 1.0,
                        double rel_tol = 1e-5);

// ---- Chi-square ----------------------------------------------------------------------------------
// Regularised upper incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a): series for x < a + 1, Lentz's
// continued fraction otherwise (Numerical Recipes, 3rd ed., sec. 6.2). p-value of a chi-square
// statistic s with k degrees of freedom is Q(k/2, s/2).
double gamma_q(double a, double x);
double chi2_p_value(double statistic, int dof);
// Per-test significance so that m independent tests together reject a correct BSDF with
// probability alpha: 1 - (1 - alpha)^(1/m) (Sidak).
double sidak_alpha(double alpha, int m);

struct Chi2Result {
  double statistic = 0;
  int dof = 0;
  double p_value = 0;
  int cells = 0;        // cells after pooling
  std::string error;    // non-empty: a sample fell where the pdf is zero, or no cell to test
};
// Pools every cell with expectation < min_expected (and, if the pool stays below it, the smallest
// remaining cells) into one, then sums (obs - exp)^2 / exp. Cells with zero expectation must be empty.
Chi2Result chi2_from_counts(const std::vector<double>& observed, const std::vector<double>& expected,
                            double min_expected = 5.0);

// The binned sphere: kZBins x kPhiBins equal-solid-angle cells, then three extra cells for delta
// reflections, delta transmissions and failed samples (flags 0).
constexpr int kZBins = 20;
constexpr int kPhiBins = 40;
constexpr int kCells = kZBins * kPhiBins + 3;

// Expected fraction of samples per cell: the integrated pdf per direction cell; the delta cells
// from the reference probabilities given; the failure cell takes the rest (clamped at 0).
// Also returns, through total_pdf, the integral of the pdf over the sphere.
std::vector<double> expected_fractions(const std::function<double(co_vec3)>& pdf, double delta_reflect,
                                       double delta_transmit, double* total_pdf = nullptr);
int cell_of(const BsdfSample& s);
std::vector<double> histogram(const std::vector<BsdfSample>& samples);

// The delta-lobe probabilities a correct sampler has for this configuration (reference formulas).
void delta_probabilities(const Config& c, double* reflect, double* transmit);

// Host samples of a configuration with u = (u_lobe, u1, u2) from TestRng(seed), in index order
// (the device test feeds the very same numbers).
std::vector<BsdfTestIn> make_queries(const Config& c, std::size_t n, std::uint64_t seed);
std::vector<BsdfSample> sample_host(const std::vector<BsdfTestIn>& queries);

struct FitReport {
  Chi2Result chi2;
  double total_pdf = 0;
};
// The whole test: samples vs. expected fractions from `pdf` (bsdf_pdf by default).
FitReport goodness_of_fit(const Config& c, const std::vector<BsdfSample>& samples,
                          const std::function<double(co_vec3)>& pdf = nullptr);

}  // namespace cohort::bsdf_test

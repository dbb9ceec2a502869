#include "bsdf/bsdf_check.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

namespace cohort::bsdf_test {

namespace {
constexpr double kAzimuth = 0.7;  // radians; not a multiple of the phi bin width
}  // namespace

co_vec3 direction_at(double theta_deg, bool below) {
  const double t = theta_deg * kPi / 180.0;
  const double z = std::cos(t) * (below ? -1.0 : 1.0);
  return v3_normalize(v3(static_cast<float>(std::sin(t) * std::cos(kAzimuth)),
                         static_cast<float>(std::sin(t) * std::sin(kAzimuth)), static_cast<float>(z)));
}

Config make_config(const std::string& family, const Bsdf& bsdf, double roughness, double theta_deg, bool below) {
  std::string name = family;
  if (roughness >= 0) name += fmt::format("_r{:02d}", static_cast<int>(std::lround(roughness * 10)));
  name += fmt::format("_{}deg", static_cast<int>(theta_deg));
  if (below) name += "_below";
  return Config{name, bsdf, direction_at(theta_deg, below)};
}

std::vector<Config> standard_configs(bool white) {
  const co_vec3 one = v3_splat(1.0f);
  const co_vec3 albedo = white ? one : v3(0.8f, 0.5f, 0.2f);
  const co_vec3 f0 = white ? one : v3(0.95f, 0.64f, 0.54f);  // copper-like
  const co_vec3 base = white ? one : v3(0.5f, 0.3f, 0.2f);
  const float eta = 1.5f;
  const double roughness[] = {0.1, 0.3, 0.7, 1.0};
  const double angles[] = {10, 45, 80};
  std::vector<Config> out;
  for (double a : angles) out.push_back(make_config("diffuse", bsdf_diffuse(albedo), -1, a));
  out.push_back(make_config("diffuse", bsdf_diffuse(albedo), -1, 45, true));
  for (double r : roughness)
    for (double a : angles)
      out.push_back(make_config("conductor", bsdf_conductor(f0, static_cast<float>(r * r)), r, a));
  out.push_back(make_config("conductor", bsdf_conductor(f0, 0.3f * 0.3f), 0.3, 45, true));
  for (double a : angles) out.push_back(make_config("smooth_conductor", bsdf_conductor(f0, 0.0f), -1, a));
  for (double r : roughness)
    for (double a : angles)
      for (bool below : {false, true})
        out.push_back(make_config("dielectric", bsdf_dielectric(eta, static_cast<float>(r * r), one), r, a, below));
  for (double a : angles)
    for (bool below : {false, true})
      out.push_back(make_config("smooth_dielectric", bsdf_dielectric(eta, 0.0f, one), -1, a, below));
  for (double r : roughness)
    for (double a : angles)
      out.push_back(make_config("plastic", bsdf_plastic(base, eta, static_cast<float>(r * r)), r, a));
  for (double a : angles) out.push_back(make_config("smooth_plastic", bsdf_plastic(base, eta, 0.0f), -1, a));
  out.push_back(make_config("smooth_plastic", bsdf_plastic(base, eta, 0.0f), -1, 45, true));
  // glTF's clearcoat layer alone, with the scale c / q its selection gives it (1 in the furnace)
  const float coat_scale = white ? 1.0f : 0.7f;
  for (double r : roughness)
    for (double a : angles)
      out.push_back(make_config("coat", bsdf_coat(eta, static_cast<float>(r * r), coat_scale), r, a));
  out.push_back(make_config("coat", bsdf_coat(eta, 0.3f * 0.3f, coat_scale), 0.3, 45, true));
  for (double a : angles) out.push_back(make_config("smooth_coat", bsdf_coat(eta, 0.0f, coat_scale), -1, a));
  // the sheen lobe alone (KHR_materials_sheen), its colour not divided by a selection probability
  const co_vec3 sheen = white ? one : v3(0.9f, 0.5f, 0.3f);
  for (double r : roughness)
    for (double a : angles) out.push_back(make_config("sheen", bsdf_sheen(sheen, static_cast<float>(r)), r, a));
  out.push_back(make_config("sheen", bsdf_sheen(sheen, 0.5f), 0.5, 45, true));
  // glTF's specular reflection alone (KHR_materials_specular): white, the exact Fresnel (specular 1,
  // colour 1) with scale 1; else specular 0.6, colour (2.5, 1, 0.4) and the scale 1.5 of a choice
  const float fr = (eta - 1.0f) * (eta - 1.0f) / ((eta + 1.0f) * (eta + 1.0f));
  const co_vec3 spec_f0 = white ? v3_splat(fr) : v3(fr * 2.5f * 0.6f, fr * 0.6f, fr * 0.4f * 0.6f);
  const float spec_f90 = white ? 1.0f : 0.6f, spec_scale = white ? 1.0f : 1.5f;
  for (double r : roughness)
    for (double a : angles)
      out.push_back(make_config("specular", bsdf_specular(eta, static_cast<float>(r * r), spec_f0, spec_f90, spec_scale),
                                r, a));
  out.push_back(make_config("specular", bsdf_specular(eta, 0.3f * 0.3f, spec_f0, spec_f90, spec_scale), 0.3, 45, true));
  for (double a : angles)
    out.push_back(make_config("smooth_specular", bsdf_specular(eta, 0.0f, spec_f0, spec_f90, spec_scale), -1, a));
  return out;
}

double fresnel_dielectric_ref(double cos_i, double eta) {
  if (cos_i < 0) {
    cos_i = -cos_i;
    eta = 1.0 / eta;
  }
  const double sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta);
  if (sin_t2 >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t2);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

double plastic_coat_probability_ref(const Bsdf& b, double cos_i) {
  const double f = fresnel_dielectric_ref(std::abs(cos_i), b.eta);
  const double mean = (double(b.color.x) + b.color.y + b.color.z) / 3.0;
  const double w = 1.0 / (1.0 + mean);
  const double ps = f * w, pd = (1.0 - f) * (1.0 - w);
  return ps / (ps + pd);
}

co_vec3 sphere_direction(double z, double phi) {
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return v3(static_cast<float>(r * std::cos(phi)), static_cast<float>(r * std::sin(phi)), static_cast<float>(z));
}

namespace {

// 4-point Gauss-Legendre on [-1, 1]
constexpr std::array<double, 4> kGlX = {-0.8611363115940526, -0.3399810435848563, 0.3399810435848563,
                                        0.8611363115940526};
constexpr std::array<double, 4> kGlW = {0.3478548451374538, 0.6521451548625461, 0.6521451548625461,
                                        0.3478548451374538};

double gl4(const std::function<double(co_vec3)>& f, double z0, double z1, double p0, double p1) {
  const double hz = 0.5 * (z1 - z0), cz = 0.5 * (z1 + z0), hp = 0.5 * (p1 - p0), cp = 0.5 * (p1 + p0);
  double sum = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sum += kGlW[i] * kGlW[j] * f(sphere_direction(cz + hz * kGlX[i], cp + hp * kGlX[j]));
  return sum * hz * hp;
}

double adapt(const std::function<double(co_vec3)>& f, double z0, double z1, double p0, double p1, double whole,
             double abs_tol, double rel_tol, int depth, int forced) {
  const double zm = 0.5 * (z0 + z1), pm = 0.5 * (p0 + p1);
  const double q[4] = {gl4(f, z0, zm, p0, pm), gl4(f, zm, z1, p0, pm), gl4(f, z0, zm, pm, p1), gl4(f, zm, z1, pm, p1)};
  const double sum = q[0] + q[1] + q[2] + q[3];
  if (forced <= 0 && (depth <= 0 || std::abs(sum - whole) <= std::max(abs_tol, rel_tol * std::abs(sum)))) return sum;
  return adapt(f, z0, zm, p0, pm, q[0], abs_tol * 0.25, rel_tol, depth - 1, forced - 1) +
         adapt(f, zm, z1, p0, pm, q[1], abs_tol * 0.25, rel_tol, depth - 1, forced - 1) +
         adapt(f, z0, zm, pm, p1, q[2], abs_tol * 0.25, rel_tol, depth - 1, forced - 1) +
         adapt(f, zm, z1, pm, p1, q[3], abs_tol * 0.25, rel_tol, depth - 1, forced - 1);
}

}  // namespace

double integrate_rect(const std::function<double(co_vec3)>& f, double z0, double z1, double p0, double p1,
                      double abs_tol, double rel_tol, int max_depth, int min_depth) {
  return adapt(f, z0, z1, p0, p1, gl4(f, z0, z1, p0, p1), abs_tol, rel_tol, max_depth, min_depth);
}

double integrate_sphere(const std::function<double(co_vec3)>& f, double z_lo, double z_hi, double rel_tol) {
  const double dz = 2.0 / kZBins, dp = 2.0 * kPi / kPhiBins;
  const int iz0 = static_cast<int>(std::lround((z_lo + 1.0) / dz)), iz1 = static_cast<int>(std::lround((z_hi + 1.0) / dz));
  const int cells = (iz1 - iz0) * kPhiBins;
  std::vector<double> v(std::max(cells, 0), 0.0);
  tbb::parallel_for(0, cells, [&](int k) {
    const int iz = iz0 + k / kPhiBins, ip = k % kPhiBins;
    v[k] = integrate_rect(f, -1.0 + iz * dz, -1.0 + (iz + 1) * dz, ip * dp, (ip + 1) * dp, 1e-10, rel_tol);
  });
  return std::accumulate(v.begin(), v.end(), 0.0);
}

double gamma_q(double a, double x) {
  if (x <= 0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1.0) {  // series for P(a, x)
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 100000; ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
      if (std::abs(del) < std::abs(sum) * 1e-15) break;
    }
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  // continued fraction for Q(a, x), modified Lentz
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

double chi2_p_value(double statistic, int dof) { return gamma_q(0.5 * dof, 0.5 * statistic); }

double sidak_alpha(double alpha, int m) { return 1.0 - std::pow(1.0 - alpha, 1.0 / m); }

Chi2Result chi2_from_counts(const std::vector<double>& observed, const std::vector<double>& expected,
                            double min_expected) {
  Chi2Result r;
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (expected[i] <= 0) {
      if (observed[i] > 0) {
        r.error = fmt::format("{} sample(s) in cell {} where the pdf integrates to 0", observed[i], i);
        return r;
      }
      continue;
    }
    order.push_back(i);
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return expected[a] < expected[b]; });
  double pool_obs = 0, pool_exp = 0;
  std::size_t k = 0;
  while (k < order.size() && (expected[order[k]] < min_expected || (pool_exp > 0 && pool_exp < min_expected))) {
    pool_obs += observed[order[k]];
    pool_exp += expected[order[k]];
    ++k;
  }
  int cells = 0;
  double stat = 0;
  if (pool_exp > 0) {
    stat += (pool_obs - pool_exp) * (pool_obs - pool_exp) / pool_exp;
    ++cells;
  }
  for (; k < order.size(); ++k) {
    const double o = observed[order[k]], e = expected[order[k]];
    stat += (o - e) * (o - e) / e;
    ++cells;
  }
  if (cells < 2) {
    // one cell holds everything (a pure delta BSDF): nothing to fit, but nothing may be off either
    r.cells = cells;
    r.dof = 0;
    r.statistic = stat;
    r.p_value = 1.0;
    return r;
  }
  r.cells = cells;
  r.dof = cells - 1;
  r.statistic = stat;
  r.p_value = chi2_p_value(stat, r.dof);
  return r;
}

std::vector<double> expected_fractions(const std::function<double(co_vec3)>& pdf, double delta_reflect,
                                       double delta_transmit, double* total_pdf) {
  std::vector<double> exp(kCells, 0.0);
  const double dz = 2.0 / kZBins, dp = 2.0 * kPi / kPhiBins;
  tbb::parallel_for(0, kZBins * kPhiBins, [&](int cell) {
    const int iz = cell / kPhiBins, ip = cell % kPhiBins;
    exp[cell] = integrate_rect(pdf, -1.0 + iz * dz, -1.0 + (iz + 1) * dz, ip * dp, (ip + 1) * dp, 1e-10, 1e-4);
  });
  const double total = std::accumulate(exp.begin(), exp.begin() + kZBins * kPhiBins, 0.0);
  if (total_pdf) *total_pdf = total;
  exp[kZBins * kPhiBins] = delta_reflect;
  exp[kZBins * kPhiBins + 1] = delta_transmit;
  exp[kZBins * kPhiBins + 2] = std::max(0.0, 1.0 - total - delta_reflect - delta_transmit);
  return exp;
}

int cell_of(const BsdfSample& s) {
  if (s.flags == 0u) return kZBins * kPhiBins + 2;
  if (s.flags & BSDF_DELTA) return kZBins * kPhiBins + ((s.flags & BSDF_TRANSMISSION) ? 1 : 0);
  const double z = std::clamp(static_cast<double>(s.wo.z), -1.0, 1.0);
  double phi = std::atan2(static_cast<double>(s.wo.y), static_cast<double>(s.wo.x));
  if (phi < 0) phi += 2.0 * kPi;
  const int iz = std::clamp(static_cast<int>((z + 1.0) * 0.5 * kZBins), 0, kZBins - 1);
  const int ip = std::clamp(static_cast<int>(phi / (2.0 * kPi) * kPhiBins), 0, kPhiBins - 1);
  return iz * kPhiBins + ip;
}

std::vector<double> histogram(const std::vector<BsdfSample>& samples) {
  std::vector<double> h(kCells, 0.0);
  for (const BsdfSample& s : samples) h[cell_of(s)] += 1.0;
  return h;
}

void delta_probabilities(const Config& c, double* reflect, double* transmit) {
  *reflect = 0;
  *transmit = 0;
  const Bsdf& b = c.bsdf;
  if (b.alpha >= BSDF_SMOOTH_ALPHA) return;
  if (b.type == BSDF_CONDUCTOR) {
    *reflect = 1.0;
  } else if (b.type == BSDF_DIELECTRIC) {
    *reflect = fresnel_dielectric_ref(c.wi.z, b.eta);
    *transmit = 1.0 - *reflect;
  } else if (b.type == BSDF_PLASTIC) {
    *reflect = plastic_coat_probability_ref(b, c.wi.z);
  } else if (b.type == BSDF_COAT || b.type == BSDF_SPECULAR) {
    *reflect = 1.0;
  }
}

std::vector<BsdfTestIn> make_queries(const Config& c, std::size_t n, std::uint64_t seed) {
  TestRng rng(seed);
  std::vector<BsdfTestIn> q(n);
  for (std::size_t i = 0; i < n; ++i) {
    q[i].bsdf = c.bsdf;
    q[i].wi = c.wi;
    q[i].u_lobe = rng.next();
    q[i].u1 = rng.next();
    q[i].u2 = rng.next();
    // a query direction spread over the whole sphere
    const double z = 2.0 * rng.next() - 1.0, phi = 2.0 * kPi * rng.next();
    q[i].wo_query = sphere_direction(z, phi);
  }
  return q;
}

std::vector<BsdfSample> sample_host(const std::vector<BsdfTestIn>& queries) {
  std::vector<BsdfSample> s(queries.size());
  tbb::parallel_for(std::size_t(0), queries.size(), [&](std::size_t i) {
    const BsdfTestIn& q = queries[i];
    s[i] = bsdf_sample(&q.bsdf, q.wi, q.u_lobe, q.u1, q.u2);
  });
  return s;
}

FitReport goodness_of_fit(const Config& c, const std::vector<BsdfSample>& samples,
                          const std::function<double(co_vec3)>& pdf) {
  const Bsdf b = c.bsdf;
  const co_vec3 wi = c.wi;
  std::function<double(co_vec3)> f = pdf ? pdf : [b, wi](co_vec3 wo) { return double(bsdf_pdf(&b, wi, wo)); };
  double dr, dt;
  delta_probabilities(c, &dr, &dt);
  FitReport rep;
  std::vector<double> exp = expected_fractions(f, dr, dt, &rep.total_pdf);
  const double n = static_cast<double>(samples.size());
  for (double& e : exp) e *= n;
  rep.chi2 = chi2_from_counts(histogram(samples), exp);
  return rep;
}

}  // namespace cohort::bsdf_test

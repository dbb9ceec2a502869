// The environment map's importance sampling (kernels/common/shading/environment.h, built by
// runtime/render/scene/environment_map.cpp): the pdf integrates to 1, samples fit the pdf (chi-square
// with the BSDF suite's machinery), sample/pdf/eval agree, the lookup follows Mitsuba's envmap
// convention, and the device (PoCL in CI) computes what the host computes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "bsdf/bsdf_check.h"
#include "common/shading/environment.h"
#include "kernels/test_kernels.h"
#include "runtime/cl/context.h"
#include "runtime/render/scene/environment_map.h"
#include "runtime/util/error.h"

using namespace cohort;
using namespace cohort::bsdf_test;

namespace {

// A map with a sun, a sky gradient, a black band and a coloured stripe: far from uniform.
Image test_image(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float* p = img.pixel(x, y);
      const float sky = 0.2f + 0.8f * float(h - y) / h;
      p[0] = sky * 0.6f;
      p[1] = sky * 0.8f;
      p[2] = sky;
      if (y == h / 2) p[0] = p[1] = p[2] = 0.f;           // black band (cells beside it still see light)
      if (x == w / 4) p[0] = 3.f, p[1] = 0.f, p[2] = 0.f;  // red stripe
    }
  float* sun = img.pixel(3 * w / 4, h / 4);
  sun[0] = sun[1] = sun[2] = 200.f;
  return img;
}

struct Map {
  EnvironmentMap tables;
  EnvironmentView view() const {
    EnvironmentView v;
    v.texels = tables.texels.data();
    v.tables = tables.tables.data();
    v.width = tables.width;
    v.height = tables.height;
    return v;
  }
};

Map make_map(int w = 16, int h = 9) { return Map{make_environment_map(test_image(w, h), "test")}; }

// The chi-square grid's pole is +z; the map's is +y. Grid direction (x, y, z) -> map (x, z, -y).
co_vec3 to_map(co_vec3 g) { return v3(g.x, g.z, -g.y); }
co_vec3 to_grid(co_vec3 m) { return v3(m.x, -m.z, m.y); }

// co_atan2 and co_acos replace the library functions, whose last bits differ between OpenCL
// implementations: they must stay as accurate (OpenCL allows atan2 6 ulp, acos 4).
TEST(EnvironmentLookup, OwnAtan2AndAcosAreAccurate) {
  double worst_atan2 = 0, worst_acos = 0;
  for (int i = 0; i <= 2000; ++i) {
    const float a = float(i) * (2.0f * 3.14159265f / 2000.0f);
    for (float r : {1.0f, 1e-3f, 7.5f}) {
      const float y = r * std::sin(a), x = r * std::cos(a);
      const double exact = std::atan2(double(y), double(x));
      const double ulp = std::nextafter(std::abs(float(exact)), 10.0f) - std::abs(float(exact));
      worst_atan2 = std::max(worst_atan2, std::abs(co_atan2(y, x) - exact) / std::max(ulp, 1e-12));
    }
    const float c = -1.0f + float(i) / 1000.0f;
    const double exact = std::acos(double(c));
    const double ulp = std::nextafter(float(exact), 10.0f) - float(exact);
    worst_acos = std::max(worst_acos, std::abs(co_acos(c) - exact) / std::max(ulp, 1e-12));
  }
  EXPECT_LE(worst_atan2, 4.0);
  EXPECT_LE(worst_acos, 4.0);
  EXPECT_EQ(co_atan2(0.0f, 0.0f), 0.0f);
  EXPECT_EQ(co_atan2(0.0f, -1.0f), float(M_PI));
  EXPECT_EQ(co_acos(1.0f), 0.0f);
  std::printf("co_atan2 within %.2f ulp, co_acos within %.2f ulp of the exact values\n", worst_atan2, worst_acos);
}

}  // namespace

TEST(EnvironmentSampling, PdfIntegratesToOne) {
  const Map m = make_map();
  const EnvironmentView e = m.view();
  const double total = integrate_sphere([&](co_vec3 d) { return double(env_pdf(&e, to_map(d))); });
  EXPECT_NEAR(total, 1.0, 2e-3);
  // and exactly, cell by cell: probability over solid angle times solid angle
  double sum = 0;
  for (std::uint32_t j = 0; j + 1 < e.height; ++j)
    for (std::uint32_t i = 0; i < e.width; ++i)
      sum += double(env_cell_pdf(&e, i, j)) * (2 * M_PI / e.width) *
             (double(e.tables[j]) - double(e.tables[j + 1]));
  EXPECT_NEAR(sum, 1.0, 1e-5);
}

TEST(EnvironmentSampling, SamplesFitThePdf) {
  const Map m = make_map();
  const EnvironmentView e = m.view();
  TestRng rng(7);
  std::vector<BsdfSample> samples(1u << 20);
  for (BsdfSample& s : samples) {
    const float u1 = rng.next(), u2 = rng.next();
    float pdf;
    s = BsdfSample{};
    s.wo = to_grid(env_sample(&e, u1, u2, &pdf));
    s.flags = BSDF_REFLECTION;
  }
  std::vector<double> expected =
      expected_fractions([&](co_vec3 d) { return double(env_pdf(&e, to_map(d))); }, 0, 0);
  for (double& x : expected) x *= double(samples.size());
  const Chi2Result r = chi2_from_counts(histogram(samples), expected);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_GT(r.p_value, 0.01) << "chi2 " << r.statistic << " dof " << r.dof;

  // power: the same samples against a uniform pdf must fail
  std::vector<double> uniform = expected_fractions([](co_vec3) { return 0.25 / M_PI; }, 0, 0);
  for (double& x : uniform) x *= double(samples.size());
  EXPECT_LT(chi2_from_counts(histogram(samples), uniform).p_value, 1e-6);
}

TEST(EnvironmentSampling, SampleEvalPdfConsistent) {
  const Map m = make_map();
  const EnvironmentView e = m.view();
  TestRng rng(3);
  int mismatches = 0;
  const int n = 100000;
  for (int k = 0; k < n; ++k) {
    float pdf;
    const co_vec3 d = env_sample(&e, rng.next(), rng.next(), &pdf);
    ASSERT_NEAR(v3_length(d), 1.0f, 1e-5f);
    ASSERT_GT(pdf, 0.f);
    // the pdf of the direction recomputed from it: the same cell but at cell edges (rounding)
    if (std::abs(env_pdf(&e, d) - pdf) > 1e-4f * pdf) ++mismatches;
    // the bilinear radiance where the sampler goes is positive: the pdf covers the radiance
    ASSERT_GT(v3_max_component(env_eval(&e, d)), 0.f);
  }
  EXPECT_LT(mismatches, n / 1000);
  // and every direction with radiance has a positive pdf
  for (int k = 0; k < n; ++k) {
    const co_vec3 d = sphere_direction(2.0 * rng.next() - 1.0, 2 * M_PI * rng.next());
    if (v3_max_component(env_eval(&e, d)) > 0.f) {
      ASSERT_GT(env_pdf(&e, d), 0.f);
    }
  }
}

TEST(EnvironmentSampling, MitsubaConvention) {
  // texel (i, j) of a W x H map sits at u = (i + 1/2) / W, theta = j pi / (H - 1), where the
  // direction is (sin phi sin theta, cos theta, -cos phi sin theta), phi = 2 pi u
  const int w = 8, h = 5;
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.pixel(x, y)[0] = float(10 * y + x), img.pixel(x, y)[1] = 1.f;
  const Map m{make_environment_map(img, "grid")};
  const EnvironmentView e = m.view();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const double phi = 2 * M_PI * (x + 0.5) / w, theta = M_PI * y / (h - 1);
      const co_vec3 d = v3(float(std::sin(phi) * std::sin(theta)), float(std::cos(theta)),
                           float(-std::cos(phi) * std::sin(theta)));
      if (y == 0 || y == h - 1) continue;  // at the poles every column meets
      EXPECT_NEAR(env_eval(&e, d).x, 10 * y + x, 1e-3) << x << ", " << y;
    }
  // halfway between the last and the first column: the seam wraps
  const co_vec3 seam = v3(0.f, 0.f, -1.f);  // phi = 0, theta = pi / 2: u = 0
  EXPECT_NEAR(env_eval(&e, seam).x, 0.5 * (20 + 7) + 0.5 * (20 + 0), 1e-3);
}

TEST(EnvironmentSampling, BadMapsAreInputErrors) {
  EXPECT_THROW(make_environment_map(Image(4, 1), "flat.exr"), InputError);
  Image nan_image(4, 4);
  nan_image.pixel(1, 2)[1] = std::nanf("");
  EXPECT_THROW(make_environment_map(nan_image, "nan.exr"), InputError);
  Image negative(4, 4);
  negative.pixel(0, 0)[0] = -1.f;
  EXPECT_THROW(make_environment_map(negative, "negative.exr"), InputError);
  try {
    load_environment_map("/nonexistent/sky.exr");
    FAIL();
  } catch (const InputError& err) {
    EXPECT_NE(std::string(err.what()).find("sky.exr"), std::string::npos);
  }
}

TEST(EnvironmentSampling, DeviceAgreesWithHost) {
  std::unique_ptr<ClContext> cl;
  ProgramBuild build;
  try {
    cl = std::make_unique<ClContext>(select_device(""));
    build = build_test_kernel_program(*cl, ProgramCache(ProgramCache::default_directory()), "environment_test.cl");
  } catch (const std::exception& ex) {
    GTEST_SKIP() << "no OpenCL device: " << ex.what();
  }
  const Map m = make_map();
  const EnvironmentView e = m.view();
  const std::size_t n = 1u << 16;
  TestRng rng(11);
  std::vector<co_float4> u(n / 2 + 1), query(n);  // float2 pairs packed two per float4
  std::vector<float> us(2 * n);
  for (float& x : us) x = rng.next();
  for (std::size_t i = 0; i < n; ++i) {
    const co_vec3 q = sphere_direction(2.0 * rng.next() - 1.0, 2 * M_PI * rng.next());
    query[i] = co_float4{q.x, q.y, q.z, 0.f};
  }
  auto texels = cl->buffer("env texels", m.tables.texels.size() * 16, m.tables.texels.data());
  auto tables = cl->buffer("env tables", m.tables.tables.size() * 4, m.tables.tables.data());
  auto u_buf = cl->buffer("u", us.size() * 4, us.data());
  auto q_buf = cl->buffer("queries", n * 16, query.data());
  auto out_buf = cl->buffer("out", n * 64);
  cl::Kernel k(build.program, "environment_test");
  cl_uint arg = 0;
  k.setArg(arg++, texels);
  k.setArg(arg++, tables);
  k.setArg(arg++, cl_uint(e.width));
  k.setArg(arg++, cl_uint(e.height));
  k.setArg(arg++, u_buf);
  k.setArg(arg++, q_buf);
  k.setArg(arg++, out_buf);
  k.setArg(arg++, cl_uint(n));
  cl->queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n));
  std::vector<co_float4> out(4 * n);
  cl->queue.enqueueReadBuffer(out_buf, CL_TRUE, 0, out.size() * 16, out.data());
  std::size_t values = 0, bitwise = 0, far = 0;
  auto check = [&](float h, float d) {
    ++values;
    if (h == d) ++bitwise;
    if (std::abs(h - d) > std::max(1e-4f * std::max(std::abs(h), std::abs(d)), 1e-6f)) ++far;
  };
  for (std::size_t i = 0; i < n; ++i) {
    float pdf;
    const co_vec3 d = env_sample(&e, us[2 * i], us[2 * i + 1], &pdf);
    const co_vec3 le = env_eval(&e, d);
    const co_vec3 q = v3_from4(query[i]);
    const co_vec3 lq = env_eval(&e, q);
    const float host[12] = {d.x, d.y, d.z, pdf, le.x, le.y, le.z, env_pdf(&e, d), lq.x, lq.y, lq.z, env_pdf(&e, q)};
    const float* dev = &out[4 * i].x;
    for (int c = 0; c < 12; ++c) check(host[c], dev[c]);
  }
  // no library trigonometry (co_sincos_2pi, co_atan2, co_acos): the CPU runtimes (PoCL, Intel),
  // which round / and sqrt correctly, compute the host's very bits; on a GPU a rare query may cross
  // a cell edge
  if (cl->device.is_cpu) {
    EXPECT_EQ(bitwise, values) << cl->device.platform_name;
  }
  EXPECT_LT(far, values / 2000) << bitwise << " of " << values << " bitwise equal";
  RecordProperty("bitwise", std::to_string(bitwise) + " of " + std::to_string(values));
  std::printf("environment map, device vs host: %zu of %zu values bitwise equal, %zu far apart\n", bitwise, values, far);
}

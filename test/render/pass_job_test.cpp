// The pass schedule and the job that shares passes out and adds their films in pass order.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <thread>

#include "runtime/render/run/pass_job.h"

using namespace cohort;

namespace {

RenderSettings settings(std::uint32_t w, std::uint32_t h, std::uint32_t spp, std::uint32_t pass_spp) {
  RenderSettings s;
  s.width = w;
  s.height = h;
  s.spp = spp;
  s.pass_samples = pass_spp;
  return s;
}

// A film whose sums make float addition order visible: large and small values per pass.
PassFilm film_of(const SamplePass& pass, std::size_t pixels) {
  PassFilm f{pass, std::vector<co_float4>(pixels), pass.index, 10};
  for (std::size_t i = 0; i < pixels; ++i) {
    const float v = pass.index % 2 ? 1e7f : 0.3f + float(i) * 1e-3f;
    f.sums[i] = co_float4{v, v * 0.5f, 1.f / (1.f + float(pass.index)), 0};
  }
  return f;
}

}  // namespace

TEST(PassSchedule, DefaultPassesHoldOneToFourMillionSamples) {
  EXPECT_EQ(default_pass_samples(1024, 1024, 1024), 4u);  // 256 passes of 4 M samples
  EXPECT_EQ(default_pass_samples(1024, 1024, 64), 4u);    // 16 passes of 4 M samples
  EXPECT_EQ(default_pass_samples(256, 256, 4), 64u);       // one pass
  EXPECT_EQ(default_pass_samples(256, 256, 64), 64u);      // one pass of 64 samples a pixel, not 4 of 16
  EXPECT_EQ(default_pass_samples(256, 256, 1024), 64u);    // 16 passes of 4 M samples
  EXPECT_EQ(default_pass_samples(128, 128, 256), 64u);     // 4 passes of 1 M samples
  EXPECT_EQ(default_pass_samples(2048, 2048, 64), 1u);     // at least one sample per pixel
  EXPECT_EQ(default_pass_samples(512, 512, 256), 16u);     // 16 passes
  EXPECT_EQ(default_pass_samples(512, 512, 64), 16u);      // 4 passes of 4 M samples
  EXPECT_EQ(default_pass_samples(16, 16, 0), 1024u);       // time-limited: ~256 K samples
}

TEST(PassSchedule, CoversTheSamplesOnceInOrderFromTheResumePoint) {
  const PassSchedule schedule(3, 4, 11);
  std::uint32_t next = 4, index = 0;
  while (const auto p = schedule.pass(index)) {
    EXPECT_EQ(p->index, index);
    EXPECT_EQ(p->first_sample, next);
    next += p->samples;
    ++index;
  }
  EXPECT_EQ(next, 11u);
  EXPECT_EQ(index, 3u);  // 3 + 3 + 1
}

TEST(PassJob, FilmsFinishingOutOfOrderAddUpInPassOrder) {
  const std::size_t pixels = 6;
  const RenderSettings s = settings(3, 2, 8, 1);
  PassJob in_order(s, {}, {}, 8, 0), shuffled(s, {}, {}, 8, 0);
  std::vector<SamplePass> passes;
  while (const auto p = shuffled.next()) passes.push_back(*p);
  ASSERT_EQ(passes.size(), 8u);
  while (const auto p = in_order.next()) in_order.deliver(film_of(*p, pixels));
  for (const std::size_t i : {3, 1, 0, 7, 2, 6, 4, 5}) shuffled.deliver(film_of(passes[i], pixels));
  const FilmState a = in_order.finish(), b = shuffled.finish();
  EXPECT_EQ(a.samples, 8u);
  EXPECT_EQ(b.samples, 8u);
  EXPECT_EQ(a.dropped_samples, 28u);  // 0 + 1 + ... + 7
  EXPECT_EQ(shuffled.rays(), 80u);
  EXPECT_EQ(0, std::memcmp(a.sums.data(), b.sums.data(), pixels * sizeof(co_float4)));
}

TEST(PassJob, TheWindowHoldsBackPassesUntilTheOldestIsCombined) {
  PassJob job(settings(2, 2, 10, 1), {}, {}, 2, 0);
  SamplePass a, b, c;
  ASSERT_EQ(job.try_next(a), PassJob::Offer::pass);
  ASSERT_EQ(job.try_next(b), PassJob::Offer::pass);
  EXPECT_EQ(job.try_next(c), PassJob::Offer::wait);
  job.deliver(film_of(b, 4));
  EXPECT_EQ(job.try_next(c), PassJob::Offer::wait) << "pass 0 still holds the window";
  job.deliver(film_of(a, 4));
  EXPECT_EQ(job.try_next(c), PassJob::Offer::pass);
  EXPECT_EQ(c.index, 2u);
}

TEST(PassJob, AStopEndsTheHandOutAndEveryPassHandedOutIsCombined) {
  bool stop = false;
  RenderControl control;
  control.stop_requested = [&] { return stop; };
  PassJob job(settings(2, 2, 100, 1), {}, control, 8, 0);
  const auto first = job.next(), second = job.next();
  stop = true;
  EXPECT_FALSE(job.next().has_value());
  EXPECT_FALSE(job.finished()) << "two passes are still out";
  job.deliver(film_of(*second, 4));
  job.deliver(film_of(*first, 4));
  EXPECT_TRUE(job.finished());
  EXPECT_TRUE(job.interrupted());
  EXPECT_EQ(job.finish().samples, 2u);
}

TEST(PassJob, HandsOutNothingUntilEveryDeviceIsReady) {
  PassJob job(settings(2, 2, 4, 1), {}, {}, 8, 2);
  SamplePass p;
  job.device_ready();
  EXPECT_EQ(job.try_next(p), PassJob::Offer::wait);
  std::thread second([&] { job.device_ready(); });
  second.join();
  EXPECT_EQ(job.try_next(p), PassJob::Offer::pass);
}

TEST(PassJob, AResumedJobContinuesTheCheckpointsSchedule) {
  RenderControl control;
  FilmState saved{2, 2, 6, 3, 0, std::vector<co_float4>(4, co_float4{1, 1, 1, 0})};
  control.resume_from = saved;
  PassJob job(settings(2, 2, 12, 0), {}, control, 8, 0);
  const auto p = job.next();
  ASSERT_TRUE(p.has_value());
  EXPECT_EQ(p->first_sample, 6u);
  EXPECT_EQ(p->samples, 3u);
  EXPECT_THROW(PassJob(settings(2, 2, 12, 2), {}, control, 8, 0), std::exception) << "other --pass-spp";
}

TEST(PassJob, TheImageMeanAndItsStandardErrorComeFromThePassMeans) {
  PassJob job(settings(1, 1, 4, 1), {}, {}, 8, 0);
  for (const float v : {1.f, 3.f, 1.f, 3.f}) {
    const auto p = job.next();
    job.deliver(PassFilm{*p, {co_float4{v, 2 * v, 0, 0}}, 0, 0});
  }
  const auto m = job.image_mean();
  EXPECT_DOUBLE_EQ(m.mean[0], 2.0);
  EXPECT_DOUBLE_EQ(m.mean[1], 4.0);
  EXPECT_DOUBLE_EQ(m.standard_error[0], std::sqrt(4.0 / 3.0 / 4.0));  // sample sd of {1,3,1,3} over sqrt(4)
  EXPECT_DOUBLE_EQ(m.standard_error[2], 0.0);
}

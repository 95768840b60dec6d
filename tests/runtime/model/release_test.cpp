// When an entry's bodies are released (model/release.h): by rate, body k at start + k / rate; at
// listed times, the count split into bursts in order, the first count % n one body larger; the
// first step at or after a time.
#include "model/release.h"

#include <gtest/gtest.h>

#include <vector>

namespace lrigid {
namespace {

TEST(Release, ByRateBodyKLeavesAtStartPlusKOverRate) {
  BodySpec b;
  b.count = 5;
  EXPECT_EQ(release_time(b, 3), 0.0) << "without release every body starts at t = 0";
  b.release_rate = 4;
  b.release_start = 0.5;
  for (int k = 0; k < b.count; ++k) EXPECT_EQ(release_time(b, k), 0.5 + k / 4.0) << k;
}

TEST(Release, TimesSplitTheCountInBurstsTheFirstOnesOneLarger) {
  BodySpec b;
  b.count = 11;
  b.release_times = {0, 1, 2, 3};  // 11 = 3 + 3 + 3 + 2
  std::vector<int> per_time(4, 0);
  double before = 0;
  for (int k = 0; k < b.count; ++k) {
    const double t = release_time(b, k);
    EXPECT_GE(t, before) << "bodies leave in order, k = " << k;
    before = t;
    ++per_time[size_t(t)];
  }
  EXPECT_EQ(per_time, (std::vector<int>{3, 3, 3, 2}));
  b.count = 2;  // fewer bodies than times: one each in the first two
  EXPECT_EQ(release_time(b, 0), 0);
  EXPECT_EQ(release_time(b, 1), 1);
}

TEST(Release, FirstStepAtOrAfterATime) {
  EXPECT_EQ(first_step_at(0, 0.002), 0u);
  EXPECT_EQ(first_step_at(0.1, 0.002), 50u) << "0.1 / 0.002 rounds above 50";
  EXPECT_EQ(first_step_at(0.003, 0.002), 2u);
  EXPECT_EQ(first_step_at(0.0041, 0.002), 3u);
  for (int k = 0; k < 200; ++k) {
    const double t = 0.5 + k / 7.0, dt = 1e-3;
    const uint64_t s = first_step_at(t, dt);
    EXPECT_GE(double(s) * dt, t - 1e-9) << "not before its time, t = " << t;
    EXPECT_LT(double(s - 1) * dt, t) << "the first such step, t = " << t;
  }
}

}  // namespace
}  // namespace lrigid

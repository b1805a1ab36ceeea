// A peer's clock against ours from its samples alone: the smallest apparent delay of the last
// ten seconds, whatever the offset, following a clock that steps.
#include "teleop/common/clock_offset.h"

#include <gtest/gtest.h>

namespace teleop {
namespace {

constexpr int64_t kMs = 1'000'000;
constexpr int64_t kS = 1'000'000'000;

TEST(ClockOffsetEstimate, IsTheFastestSamplesApparentDelay) {
  ClockOffsetEstimate e;
  EXPECT_FALSE(e.valid());
  EXPECT_EQ(e.estimate_ns(), 0);
  // the peer's clock 2 s ahead, latencies of 0.3 to 5 ms
  const int64_t ahead = 2 * kS;
  for (int i = 0; i < 3000; ++i) {
    const int64_t latency = 300'000 + (i * 7919 % 47) * 100'000;
    e.add(latency - ahead, 100 * kS + i * kMs);
  }
  EXPECT_TRUE(e.valid());
  EXPECT_EQ(e.estimate_ns(), 300'000 - ahead);
}

TEST(ClockOffsetEstimate, FollowsAClockThatStepsWithinTenSeconds) {
  ClockOffsetEstimate e;
  for (int s = 0; s < 5; ++s) e.add(-kS, s * kS);
  EXPECT_EQ(e.estimate_ns(), -kS);
  // the peer's clock was set back by 1 s (its samples now look 1 s older)
  for (int s = 5; s < 14; ++s) e.add(0, s * kS);
  EXPECT_EQ(e.estimate_ns(), -kS) << "the old minimum is still within the window";
  for (int s = 14; s < 16; ++s) e.add(0, s * kS);
  EXPECT_EQ(e.estimate_ns(), 0) << "forgotten after ten seconds of buckets";
}

TEST(ClockOffsetEstimate, ABacklogAfterAnOutageIsJudgedAgainstTheSamplesBeforeIt) {
  ClockOffsetEstimate e;
  for (int i = 0; i < 1000; ++i) e.add(kMs, 50 * kS + i * kMs);
  // 2 s without samples, then the queued ones, 2 s late
  for (int i = 0; i < 100; ++i) e.add(2 * kS + kMs, 53 * kS + i * kMs);
  EXPECT_EQ(e.estimate_ns(), kMs);
}

TEST(ClockOffsetEstimate, ResetForgetsTheWriter) {
  ClockOffsetEstimate e;
  e.add(-5 * kS, kS);
  e.reset();
  EXPECT_FALSE(e.valid());
  e.add(kMs, 2 * kS);
  EXPECT_EQ(e.estimate_ns(), kMs);
}

}  // namespace
}  // namespace teleop

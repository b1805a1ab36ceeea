// When a cycle comes after a stall of its own loop.
#include "teleop/common/stall_watch.h"

#include <gtest/gtest.h>

namespace teleop {
namespace {

constexpr int64_t kMs = 1'000'000;

TEST(StallWatch, OnTimeCyclesWithJitterBelowTheThresholdAreNoStall) {
  StallWatch watch(20 * kMs);
  for (uint64_t i = 0; i < 100; ++i) {
    const int64_t deadline = static_cast<int64_t>(i) * kMs;
    EXPECT_FALSE(watch.stalled(CycleTick{i, deadline, deadline + (i % 3) * 5 * kMs}));
  }
  EXPECT_EQ(watch.stalls(), 0u);
}

TEST(StallWatch, SkippedDeadlinesBeyondTheThresholdAreAStall) {
  StallWatch watch(20 * kMs);
  EXPECT_FALSE(watch.stalled(CycleTick{0, 0, 0}));
  EXPECT_FALSE(watch.stalled(CycleTick{1, kMs, kMs}));
  EXPECT_TRUE(watch.stalled(CycleTick{2, 1500 * kMs, 1500 * kMs}));
  EXPECT_FALSE(watch.stalled(CycleTick{3, 1501 * kMs, 1501 * kMs}));
  EXPECT_EQ(watch.stalls(), 1u);
}

TEST(StallWatch, ACycleReleasedLateOnItsOwnDeadlineIsAStall) {
  // stopped while sleeping for deadline 2 ms: released 1.5 s later on that very deadline
  StallWatch watch(20 * kMs);
  EXPECT_FALSE(watch.stalled(CycleTick{0, 0, 0}));
  EXPECT_FALSE(watch.stalled(CycleTick{1, kMs, kMs}));
  EXPECT_TRUE(watch.stalled(CycleTick{2, 2 * kMs, 1502 * kMs}));
  // the pacer then skips the missed deadlines: the same stall, not another
  EXPECT_FALSE(watch.stalled(CycleTick{3, 1503 * kMs, 1503 * kMs}));
  EXPECT_FALSE(watch.stalled(CycleTick{4, 1504 * kMs, 1504 * kMs}));
  EXPECT_EQ(watch.stalls(), 1u);
}

}  // namespace
}  // namespace teleop

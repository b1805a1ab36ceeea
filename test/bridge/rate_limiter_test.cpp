#include "rate_limiter.h"

#include <gtest/gtest.h>

namespace teleop::bridge {
namespace {

constexpr int64_t kMs = 1'000'000;

// `count` arrivals `period_ns` apart from `start_ns`; how many passed
int admitted(RateLimiter& limiter, int64_t start_ns, int64_t period_ns, int count) {
  int passed = 0;
  for (int i = 0; i < count; ++i) passed += limiter.admit(start_ns + i * period_ns) ? 1 : 0;
  return passed;
}

TEST(BridgeRateLimiter, ZeroLetsEverythingThrough) {
  RateLimiter limiter(0.0);
  EXPECT_EQ(admitted(limiter, 0, kMs, 1000), 1000);
  EXPECT_EQ(admitted(limiter, 5 * kMs, 0, 10), 10);  // even at one instant
}

TEST(BridgeRateLimiter, ThinsAOneKilohertzStreamToTheLimitOnAverage) {
  RateLimiter limiter(50.0);
  // ten seconds at 1 kHz: 50 Hz is 500 (one more for the first slot), never more
  const int passed = admitted(limiter, 123 * kMs, kMs, 10'000);
  EXPECT_LE(passed, 501);
  EXPECT_GE(passed, 499);
}

TEST(BridgeRateLimiter, NeverExceedsTheLimitInAnyWindow) {
  RateLimiter limiter(100.0);
  std::vector<int64_t> passed;
  // irregular arrivals: bursts of five within a millisecond, then a gap
  for (int64_t t = 0; t < 2000 * kMs; t += 3 * kMs) {
    for (int64_t b = 0; b < 5; ++b) {
      if (limiter.admit(t + b * 100'000)) passed.push_back(t + b * 100'000);
    }
  }
  ASSERT_GT(passed.size(), 100u);
  // any span T holds fewer than T * 100 Hz + 2 (a message late in its slot, the next on time)
  for (size_t i = 0; i + 1 < passed.size(); ++i) {
    for (size_t j = i + 1; j < passed.size() && j < i + 30; ++j) {
      const double span_s = static_cast<double>(passed[j] - passed[i]) * 1e-9;
      EXPECT_LT(static_cast<double>(j - i + 1), span_s * 100.0 + 2.0 + 1e-9) << "between " << i << " and " << j;
    }
  }
}

TEST(BridgeRateLimiter, APauseDoesNotSaveUpABurst) {
  RateLimiter limiter(50.0);
  EXPECT_TRUE(limiter.admit(0));
  // a second of silence, then a burst within one period: one passes, not fifty
  EXPECT_EQ(admitted(limiter, 1000 * kMs, kMs / 10, 100), 1);
}

TEST(BridgeRateLimiter, FirstMessagePassesAtAnyTime) {
  RateLimiter limiter(1.0);
  EXPECT_TRUE(limiter.admit(-5));
  EXPECT_FALSE(limiter.admit(999 * kMs - 5));
  EXPECT_TRUE(limiter.admit(1000 * kMs - 5));
}

}  // namespace
}  // namespace teleop::bridge

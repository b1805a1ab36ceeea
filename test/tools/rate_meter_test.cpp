// `teleop topic hz`'s arithmetic: rate and period over the window, loss per writer.
#include <gtest/gtest.h>

#include "teleop/tools/rate_meter.h"

namespace teleop::tools {
namespace {

WriterId writer(uint8_t n) {
  WriterId w;
  w.bytes[15] = n;
  return w;
}

TEST(RateMeter, MeasuresRateAndPeriodSpreadOverTheWindow) {
  RateMeter meter(4);
  // periods 1, 1, 2, 1 ms; the window keeps the last 4 arrivals: periods 1, 2, 1
  const int64_t t[] = {0, 1'000'000, 2'000'000, 4'000'000, 5'000'000};
  for (int i = 0; i < 5; ++i) meter.add(t[i], 200'000, writer(1), static_cast<uint64_t>(i + 1));
  const RateStats s = meter.stats();
  EXPECT_EQ(s.window, 4u);
  EXPECT_EQ(s.received, 5u);
  EXPECT_NEAR(s.rate_hz, 3 / 4e-3, 1e-6);
  EXPECT_NEAR(s.period_min_s, 1e-3, 1e-12);
  EXPECT_NEAR(s.period_max_s, 2e-3, 1e-12);
  EXPECT_NEAR(s.period_mean_s, 4e-3 / 3, 1e-12);
  EXPECT_NEAR(s.age_mean_s, 2e-4, 1e-12);
  EXPECT_EQ(s.lost, 0u);
}

TEST(RateMeter, CountsGapsPerWriterSoThatEveryNumberIsAccountedFor) {
  RateMeter meter(100);
  for (uint64_t seq : {1, 2, 5, 6, 10}) meter.add(static_cast<int64_t>(seq) * 1'000'000, 0, writer(1), seq);
  // a restarted writer begins at 1 again: no loss, no negative gap
  for (uint64_t seq : {1, 2, 3}) meter.add(20'000'000 + static_cast<int64_t>(seq) * 1'000'000, 0, writer(2), seq);
  const RateStats s = meter.stats();
  EXPECT_EQ(s.lost, 2u + 3u);
  EXPECT_EQ(s.received, 8u);
  EXPECT_EQ(s.first_seq, 1u);
  EXPECT_EQ(s.last_seq, 3u);
  EXPECT_NEAR(s.span_s, 2e-3, 1e-12);
}

}  // namespace
}  // namespace teleop::tools

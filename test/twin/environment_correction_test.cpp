// MMT's model update (issue 6): the estimate of where the real surface is, from the follower's
// measurements, and the rate-limited, bounded offset the twin applies.
#include "environment_correction.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "allocation_counter.h"

namespace teleop::twin {
namespace {

constexpr double kCycleS = 0.001;
constexpr double kPressingN = 15.0;

// A follower pressed towards the surface along -n by the twin's feed-forward: its probe ends up
// `overshoot_m` behind the twin's surface unless the real surface (at `real_m`) stops it first.
SurfaceMeasurement follower_at(const EnvironmentCorrection& c, double real_m, double overshoot_m) {
  const double probe_m = std::max(c.applied_m() - overshoot_m, real_m);
  SurfaceMeasurement m;
  m.gap_m = probe_m - c.applied_m();
  m.normal_force_n = probe_m == real_m ? kPressingN : 0.0;
  m.age_s = 0.0175;  // the 35 ms round trip's one way
  return m;
}

// runs the loop for `seconds`; returns the largest step of the applied offset
double run(EnvironmentCorrection& c, double real_m, double overshoot_m, double seconds) {
  double largest_step = 0.0;
  for (int k = 0; k < static_cast<int>(seconds / kCycleS); ++k) {
    (void)c.measure(follower_at(c, real_m, overshoot_m));
    const double before = c.applied_m();
    largest_step = std::max(largest_step, std::abs(c.advance(kCycleS) - before));
  }
  return largest_step;
}

TEST(EnvironmentCorrection, ConvergesToASurfaceNearerThanTheModel) {
  EnvironmentCorrection c{CorrectionConfig{}};
  // the real wall 2 cm in front of the twin's: the follower touches it while the twin is free
  run(c, 0.02, 0.01, 1.5);
  EXPECT_NEAR(c.estimate_m(), 0.02, 1e-9);
  EXPECT_NEAR(c.applied_m(), 0.02, 1e-9);
  EXPECT_GT(c.contact_updates(), 0u);
}

TEST(EnvironmentCorrection, ConvergesToASurfaceFurtherThanTheModel) {
  EnvironmentCorrection c{CorrectionConfig{}};
  // the real wall 2 cm behind the twin's: the follower passes the twin's surface without force
  run(c, -0.02, 0.01, 2.0);
  EXPECT_GT(c.free_updates(), 0u) << "free behind the twin's surface moves it out";
  EXPECT_GT(c.contact_updates(), 0u) << "then the follower reaches the real surface";
  EXPECT_NEAR(c.applied_m(), -0.02, 1e-9);
}

TEST(EnvironmentCorrection, MovesNoFasterThanTheRateLimit) {
  CorrectionConfig config;
  config.rate_m_per_s = 0.02;
  EnvironmentCorrection c{config};
  const double largest_step = run(c, 0.02, 0.01, 0.5);
  EXPECT_LE(largest_step, 0.02 * kCycleS + 1e-15);
  EXPECT_NEAR(c.applied_m(), 0.01, 1e-9) << "half way after half a second at 2 cm/s";
  EXPECT_NEAR(c.estimate_m(), 0.02, 1e-9) << "the estimate itself is not rate-limited";
}

TEST(EnvironmentCorrection, StaysWithinTheMaximumOffset) {
  CorrectionConfig config;
  config.max_offset_m = 0.01;
  EnvironmentCorrection c{config};
  run(c, 0.03, 0.01, 3.0);
  EXPECT_DOUBLE_EQ(c.estimate_m(), 0.01);
  EXPECT_DOUBLE_EQ(c.applied_m(), 0.01);
  EXPECT_GT(c.clamped(), 0u);
  run(c, -0.05, 0.01, 3.0);
  EXPECT_DOUBLE_EQ(c.applied_m(), -0.01);
}

TEST(EnvironmentCorrection, IgnoresAndCountsStaleAndNonFiniteMeasurements) {
  CorrectionConfig config;
  config.timeout_s = 0.1;
  EnvironmentCorrection c{config};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(c.measure({0.02, kPressingN, 0.2}), EnvironmentCorrection::Outcome::kStale);
  EXPECT_EQ(c.measure({nan, kPressingN, 0.01}), EnvironmentCorrection::Outcome::kNonFinite);
  EXPECT_EQ(c.measure({0.02, inf, 0.01}), EnvironmentCorrection::Outcome::kNonFinite);
  EXPECT_EQ(c.measure({0.02, kPressingN, nan}), EnvironmentCorrection::Outcome::kNonFinite);
  EXPECT_EQ(c.stale(), 1u);
  EXPECT_EQ(c.non_finite(), 3u);
  c.advance(1.0);
  EXPECT_EQ(c.estimate_m(), 0.0);
  EXPECT_EQ(c.applied_m(), 0.0);
  EXPECT_EQ(c.measure({0.02, kPressingN, 0.05}), EnvironmentCorrection::Outcome::kContact) << "fresh again";
}

TEST(EnvironmentCorrection, LearnsNothingBetweenTheForceThresholdsOrInFrontOfTheSurface) {
  CorrectionConfig config;
  config.contact_force_n = 6.0;
  config.free_force_n = 4.0;
  EnvironmentCorrection c{config};
  // the observer's reading of joint friction while moving: neither contact nor free
  EXPECT_EQ(c.measure({-0.01, 5.0, 0.01}), EnvironmentCorrection::Outcome::kNoChange);
  // free in front of the surface: consistent with it
  EXPECT_EQ(c.measure({0.03, 0.0, 0.01}), EnvironmentCorrection::Outcome::kNoChange);
  EXPECT_EQ(c.estimate_m(), 0.0);
  // free just behind it, within the margin: still consistent
  EXPECT_EQ(c.measure({-0.5 * config.free_margin_m, 0.0, 0.01}), EnvironmentCorrection::Outcome::kNoChange);
}

TEST(EnvironmentCorrection, MeasureAndAdvanceDoNotAllocate) {
  EnvironmentCorrection c{CorrectionConfig{}};
  test::ScopedAllocationCounter allocations;
  run(c, -0.02, 0.01, 0.2);
  EXPECT_EQ(allocations.count(), 0u);
}

}  // namespace
}  // namespace teleop::twin

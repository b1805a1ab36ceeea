#include "teleop/follower/torque_limiter.h"

#include <gtest/gtest.h>

namespace teleop::follower {
namespace {

JointVector torques(double a, double b) {
  JointVector t{};
  t[0] = a;
  t[1] = b;
  return t;
}

TEST(TorqueLimiter, SaturatesEachJointAtItsOwnLimitAndCountsIt) {
  TorqueLimiter limiter(2, torques(87, 12), 0, 0.001);
  JointVector t = torques(100, -20);
  limiter.apply(t);
  EXPECT_EQ(t[0], 87);
  EXPECT_EQ(t[1], -12);
  EXPECT_EQ(limiter.saturations(), 2u);
  EXPECT_DOUBLE_EQ(limiter.peak_ratio(), 1.0);
  t = torques(10, 6);
  limiter.apply(t);
  EXPECT_EQ(t[0], 10);
  EXPECT_EQ(t[1], 6);
  EXPECT_EQ(limiter.saturations(), 2u);
}

TEST(TorqueLimiter, LimitsTheChangePerCycleToTheRateTimesTheCycle) {
  TorqueLimiter limiter(2, torques(87, 12), 1000, 0.001);  // 1 Nm per cycle
  limiter.reset(torques(0, 0));
  JointVector t = torques(5, -0.5);
  limiter.apply(t);
  EXPECT_DOUBLE_EQ(t[0], 1.0);
  EXPECT_DOUBLE_EQ(t[1], -0.5);
  EXPECT_EQ(limiter.rate_limited(), 1u);
  for (int i = 0; i < 3; ++i) {
    t = torques(5, -0.5);
    limiter.apply(t);
  }
  EXPECT_DOUBLE_EQ(t[0], 4.0) << "ramps 1 Nm per cycle";
  t = torques(5, -0.5);
  limiter.apply(t);
  EXPECT_DOUBLE_EQ(t[0], 5.0);
  EXPECT_DOUBLE_EQ(limiter.largest_step_nm(), 1.0);
}

TEST(TorqueLimiter, StartsFromTheResetTorqueNotFromZero) {
  TorqueLimiter limiter(1, torques(87, 0), 1000, 0.001);
  limiter.reset(torques(30, 0));
  JointVector t = torques(30.5, 0);
  limiter.apply(t);
  EXPECT_DOUBLE_EQ(t[0], 30.5) << "holding the arm's weight is not a step";
  EXPECT_EQ(limiter.rate_limited(), 0u);
}

}  // namespace
}  // namespace teleop::follower

// The study's control parts: PD gains from a bandwidth, the PD law (the minimum-jerk motion:
// test/control/min_jerk_test.cpp).
#include "teleop/hand/position_control.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>


namespace teleop::hand {
namespace {

TEST(PdGains, PlaceACriticallyDampedLoopOfTheBandwidthOnTheInertia) {
  const PdGains g = pd_gains_for(0.002, 40.0, 1.0);
  EXPECT_DOUBLE_EQ(g.kp_nm_per_rad, 0.002 * 1600.0);
  EXPECT_DOUBLE_EQ(g.kd_nms_per_rad, 2.0 * 0.002 * 40.0);
  EXPECT_DOUBLE_EQ(pd_torque(g, 0.1, 0.0, 0.0, 0.5), 0.002 * 1600.0 * 0.1 - 2.0 * 0.002 * 40.0 * 0.5);
  EXPECT_THROW(pd_gains_for(0.0, 40.0, 1.0), std::invalid_argument);
  EXPECT_THROW(pd_gains_for(0.1, -1.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::hand

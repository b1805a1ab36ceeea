// The limits a follower enforces: the robot's where the config is silent, tightened where it
// types them, refused where neither gives one or the two do not overlap (follower/limits_in_force.h).
#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "limits_in_force.h"

namespace teleop::follower {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

robot::HardwareLimits robot_limits() {
  robot::HardwareLimits h;
  for (size_t i = 0; i < 2; ++i) {
    h.q_min_rad[i] = -2.0;
    h.q_max_rad[i] = 2.0;
    h.max_torque_nm[i] = 87.0;
  }
  return h;
}

JointLimits silent() {
  JointLimits l;
  l.q_min_rad.fill(-kInf);
  l.q_max_rad.fill(kInf);
  l.max_torque_nm.fill(kInf);
  return l;
}

TEST(LimitsInForce, ASilentConfigTakesTheRobotsAndSaysSo) {
  const JointLimits l = limits_in_force(silent(), robot_limits(), 2, "mujoco:panda.xml");
  EXPECT_EQ(l.q_min_rad[1], -2.0);
  EXPECT_EQ(l.q_max_rad[1], 2.0);
  EXPECT_EQ(l.max_torque_nm[0], 87.0);
  EXPECT_EQ(limits_text(l, silent(), 2), "1: [-2.0000, 2.0000] rad (robot), 87.0 Nm (robot); 2: [-2.0000, 2.0000] rad (robot), 87.0 Nm (robot)");
}

TEST(LimitsInForce, TypedLimitsOnlyTighten) {
  JointLimits typed = silent();
  typed.q_min_rad[0] = -1.0;
  typed.q_max_rad[0] = 3.0;  // wider than the robot: the robot's holds
  typed.max_torque_nm[1] = 20.0;
  const JointLimits l = limits_in_force(typed, robot_limits(), 2, "mujoco:panda.xml");
  EXPECT_EQ(l.q_min_rad[0], -1.0);
  EXPECT_EQ(l.q_max_rad[0], 2.0);
  EXPECT_EQ(l.max_torque_nm[1], 20.0);
  EXPECT_NE(limits_text(l, typed, 2).find("2: [-2.0000, 2.0000] rad (robot), 20.0 Nm (config)"), std::string::npos)
      << limits_text(l, typed, 2);
}

TEST(LimitsInForce, NoLimitAnywhereOrNoOverlapStopsTheStartNamingTheJoint) {
  robot::HardwareLimits unbounded = robot_limits();
  unbounded.q_max_rad[1] = kInf;  // a continuous joint, or a robot that tells nothing
  try {
    limits_in_force(silent(), unbounded, 2, "ros2:fr3");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "joint 2 has no position limit: neither follower.q_min_rad/q_max_rad nor the robot (ros2:fr3) gives one");
  }
  unbounded = robot_limits();
  unbounded.max_torque_nm[0] = kInf;
  EXPECT_THROW(limits_in_force(silent(), unbounded, 2, "ros2:fr3"), std::runtime_error);
  JointLimits outside = silent();
  outside.q_min_rad[0] = 2.5;
  outside.q_max_rad[0] = 3.0;
  try {
    limits_in_force(outside, robot_limits(), 2, "mujoco:panda.xml");
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("joint 1: follower.q_min_rad/q_max_rad [2.500000, 3.000000] lies outside"),
              std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::follower

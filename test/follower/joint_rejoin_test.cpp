#include "teleop/follower/joint_rejoin.h"

#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.h"

namespace teleop::follower {
namespace {

constexpr size_t kJoints = 2;
constexpr double kCycleS = 0.001;

ValidCommand joint_command(double q0, double q1) {
  ValidCommand c;
  c.mode = msg::CONTROL_JOINT_IMPEDANCE;
  c.q_des_rad[0] = q0;
  c.q_des_rad[1] = q1;
  c.dq_des_radps[0] = 0.4;
  c.tau_ff_nm[1] = 3.0;
  return c;
}

TEST(JointRejoin, PassesTheCommandThroughWhenNotStarted) {
  JointRejoin rejoin(kJoints, 2.0, kCycleS);
  const ValidCommand cmd = joint_command(0.5, -0.5);
  EXPECT_EQ(&rejoin.apply(cmd), &cmd);
  EXPECT_FALSE(rejoin.active());
}

TEST(JointRejoin, MovesFromTheHeldPoseAtTheBoundedSpeedUntilItCatchesUp) {
  JointRejoin rejoin(kJoints, 2.0, kCycleS);  // 2 mrad per cycle
  JointVector held{};
  held[0] = 0.0;
  held[1] = 0.01;
  rejoin.start(held);
  const ValidCommand cmd = joint_command(0.1, 0.01);  // joint 0: 100 mrad away, joint 1: there
  int cycles = 0;
  double last = 0.0;
  while (rejoin.active() || cycles == 0) {
    const ValidCommand& out = rejoin.apply(cmd);
    ++cycles;
    if (!rejoin.active()) {
      EXPECT_EQ(&out, &cmd);  // caught up: the command itself, velocity and feed-forward included
      break;
    }
    // never a step: at most 2 mrad per cycle, at rest, no feed-forward
    EXPECT_LE(std::abs(out.q_des_rad[0] - last), 0.002 + 1e-12);
    EXPECT_DOUBLE_EQ(out.q_des_rad[1], 0.01);
    EXPECT_EQ(out.dq_des_radps[0], 0.0);
    EXPECT_EQ(out.tau_ff_nm[1], 0.0);
    last = out.q_des_rad[0];
    ASSERT_LT(cycles, 1000);
  }
  EXPECT_EQ(cycles, 50);  // 0.1 rad at 2 rad/s
  EXPECT_EQ(rejoin.rejoins(), 1u);
}

TEST(JointRejoin, FollowsAMovingTargetAndEndsOnACartesianCommand) {
  JointRejoin rejoin(kJoints, 1.0, kCycleS);
  rejoin.start(JointVector{});
  (void)rejoin.apply(joint_command(1.0, 0.0));
  EXPECT_TRUE(rejoin.active());
  ValidCommand cartesian;
  cartesian.mode = msg::CONTROL_CARTESIAN_IMPEDANCE;
  EXPECT_EQ(&rejoin.apply(cartesian), &cartesian);  // the controller switch blends that one in
  EXPECT_FALSE(rejoin.active());
}

TEST(JointRejoin, AppliesWithoutAllocating) {
  JointRejoin rejoin(kJoints, 1.0, kCycleS);
  const ValidCommand cmd = joint_command(3.0, -3.0);
  rejoin.start(JointVector{});
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 100; ++i) (void)rejoin.apply(cmd);
  EXPECT_EQ(counter.count(), 0u);
  EXPECT_TRUE(rejoin.active());
}

}  // namespace
}  // namespace teleop::follower

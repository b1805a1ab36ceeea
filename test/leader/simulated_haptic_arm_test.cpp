#include "simulated_haptic_arm.h"

#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.h"

namespace teleop::leader {
namespace {

HapticArmConfig config() {
  HapticArmConfig c;
  c.model.model_path = std::string(TELEOP_SOURCE_DIR) + "/config/models/panda.xml";
  c.model.keyframe = "ready";
  c.model.period_s = 0.001;
  return c;
}

TEST(SimulatedHapticArm, FollowsTheOperatorsHandWithoutFeedback) {
  SimulatedHapticArm arm(config());
  DeviceState s;
  ASSERT_TRUE(arm.read(s));
  JointVector target = s.q_rad;
  target[0] += 0.2;
  arm.set_operator_target(target, JointVector{}, JointVector{});
  const JointVector none{};
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(arm.write(none));
    ASSERT_TRUE(arm.read(s));
  }
  EXPECT_NEAR(s.q_rad[0], target[0], 0.02) << "joint friction against the 60 Nm/rad grip";
}

TEST(SimulatedHapticArm, IsStoppedByFeedbackThatBalancesTheOperator) {
  SimulatedHapticArm arm(config());
  DeviceState s;
  ASSERT_TRUE(arm.read(s));
  const double start = s.q_rad[0];
  JointVector target = s.q_rad;
  target[0] += 0.2;  // the hand pulls with 60 * 0.2 = 12 Nm
  arm.set_operator_target(target, JointVector{}, JointVector{});
  JointVector feedback{};
  feedback[0] = -12.0;  // a wall that pushes back exactly as hard
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(arm.write(feedback));
    ASSERT_TRUE(arm.read(s));
  }
  EXPECT_NEAR(s.q_rad[0], start, 0.02) << "the operator feels the wall and the device stays";
  EXPECT_NEAR(s.tau_operator_nm[0], 12.0, 1.0);
}

TEST(SimulatedHapticArm, PressesWithTheOperatorsIntendedTorqueAgainstFeedback) {
  SimulatedHapticArm arm(config());
  DeviceState s;
  ASSERT_TRUE(arm.read(s));
  const double start = s.q_rad[0];
  JointVector intended{};
  intended[0] = 8.0;  // the operator presses with 8 Nm where the hand already is
  arm.set_operator_target(s.q_rad, JointVector{}, intended);
  JointVector feedback{};
  feedback[0] = -8.0;  // something that pushes back as hard: the device stays, the press is felt
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(arm.write(feedback));
    ASSERT_TRUE(arm.read(s));
  }
  EXPECT_NEAR(s.q_rad[0], start, 0.02);
  EXPECT_NEAR(s.tau_operator_nm[0], 8.0, 1.0);
  // without the push-back the press moves the device until the hand's spring takes it up: 8 / 60 rad
  feedback[0] = 0.0;
  for (int i = 0; i < 3000; ++i) {
    ASSERT_TRUE(arm.write(feedback));
    ASSERT_TRUE(arm.read(s));
  }
  EXPECT_NEAR(s.q_rad[0] - start, 8.0 / 60.0, 0.02);
}

TEST(SimulatedHapticArm, DoesNotAllocate) {
  SimulatedHapticArm arm(config());
  DeviceState s;
  const JointVector fb{};
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 1000; ++i) {
    EXPECT_TRUE(arm.write(fb));
    EXPECT_TRUE(arm.read(s));
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::leader

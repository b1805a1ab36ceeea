// The simulated operator's hand on a master arm's joint (emulator/operator_hand.h).
#include "teleop/emulator/operator_hand.h"

#include <gtest/gtest.h>

namespace teleop::emulator {
namespace {

TEST(OperatorHand, GripsWhereTheJointIsMovesItsGripAtItsSpeedAndHoldsItThere) {
  OperatorHand hand({.joint = 0, .delta_rad = 0.2, .speed_radps = 0.2, .stiffness_nm_per_rad = 60, .damping_nms_per_rad = 4});
  EXPECT_EQ(hand.torque(1.0, 0.0, 0.01), 0.0) << "not holding: nothing";
  hand.grip(1.0);
  EXPECT_NEAR(hand.torque(1.0, 0.0, 0.5), 60 * 0.1 + 4 * 0.2, 1e-12) << "0.5 s at 0.2 rad/s: 0.1 rad ahead, moving";
  EXPECT_NEAR(hand.torque(1.15, 0.2, 0.25), 0.0, 1e-12) << "the joint keeps up";
  EXPECT_NEAR(hand.torque(1.2, 0.0, 10.0), 0.0, 1e-12) << "there: it holds";
  EXPECT_NEAR(hand.torque(1.15, 0.0, 0.1), 60 * 0.05, 1e-12) << "pushed back, the grip pulls";
  hand.let_go();
  EXPECT_EQ(hand.torque(1.0, 0.3, 0.01), 0.0);
  OperatorHand back({.joint = 2, .delta_rad = -0.1});
  back.grip(0.0);
  EXPECT_LT(back.torque(0.0, 0.0, 0.1), 0.0) << "the other way";
}

}  // namespace
}  // namespace teleop::emulator

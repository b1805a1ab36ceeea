#include "teleop/common/joint_ramp.h"

#include <gtest/gtest.h>

#include <cmath>

namespace teleop {
namespace {

TEST(JointRamp, UsesTheTargetWhenNotStarted) {
  JointRamp ramp(2, 1.0, 0.001);
  JointVector target{};
  target[0] = 3.0;
  EXPECT_FALSE(ramp.step(target));
  EXPECT_FALSE(ramp.active());
}

TEST(JointRamp, TravelsFromTheHeldPoseAtTheBoundedSpeedAndHandsOverOnArrival) {
  JointRamp ramp(2, 0.5, 0.001);  // 0.5 mrad per cycle
  JointVector held{};
  held[1] = -0.01;
  ramp.start(held);
  JointVector target{};
  target[0] = 0.05;   // 100 cycles away
  target[1] = -0.01;  // there already
  int cycles = 0;
  double last = 0.0;
  while (ramp.step(target)) {
    ++cycles;
    EXPECT_LE(std::abs(ramp.reference()[0] - last), 0.0005 + 1e-12);
    EXPECT_DOUBLE_EQ(ramp.reference()[1], -0.01);
    last = ramp.reference()[0];
    ASSERT_LT(cycles, 1000);
  }
  EXPECT_EQ(cycles, 99);  // the 100th step arrives: the target itself from then on
  EXPECT_FALSE(ramp.active());
  EXPECT_EQ(ramp.starts(), 1u);
}

TEST(JointRamp, StopsWhenTold) {
  JointRamp ramp(1, 0.5, 0.001);
  ramp.start(JointVector{});
  JointVector far{};
  far[0] = 1.0;
  EXPECT_TRUE(ramp.step(far));
  ramp.stop();
  EXPECT_FALSE(ramp.step(far));
}

}  // namespace
}  // namespace teleop

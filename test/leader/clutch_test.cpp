#include "clutch.h"

#include <gtest/gtest.h>

namespace teleop::leader {
namespace {

JointVector at(double a, double b) {
  JointVector v{};
  v[0] = a;
  v[1] = b;
  return v;
}

TEST(Clutch, ScalesTheDeviceMotionFromTheStartReferences) {
  Clutch c(2, 0.5);
  c.start(at(1.0, 2.0), at(10.0, 20.0));
  const JointVector& cmd = c.map(at(1.4, 1.0), false);
  EXPECT_DOUBLE_EQ(cmd[0], 10.2);
  EXPECT_DOUBLE_EQ(cmd[1], 19.5);
}

TEST(Clutch, FreezesWhilePressedAndReindexesWithoutAJumpOnRelease) {
  Clutch c(2, 1.0);
  c.start(at(0, 0), at(0, 0));
  c.map(at(0.3, 0.1), false);
  // pressed: the operator moves the device back, the command stays
  for (double x = 0.3; x > -0.5; x -= 0.01) EXPECT_DOUBLE_EQ(c.map(at(x, 0.1), true)[0], 0.3);
  // released at -0.5: the command continues from 0.3, not from -0.5
  EXPECT_DOUBLE_EQ(c.map(at(-0.5, 0.1), false)[0], 0.3);
  EXPECT_NEAR(c.map(at(-0.4, 0.1), false)[0], 0.4, 1e-12);
  EXPECT_DOUBLE_EQ(c.command()[1], 0.1);
}

}  // namespace
}  // namespace teleop::leader

// A 6-DoF mouse's or a gamepad's deflection integrated into a pose (leader/rate_pose.h): the dead
// band, the speed at full deflection, rotations about the base frame's axes.
#include "rate_pose.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace teleop::leader {
namespace {

constexpr double kPeriod = 1e-3;

TEST(RatePose, TheDeadBandReadsAsRestAndFullDeflectionAsFullSpeed) {
  EXPECT_EQ(RatePose::shaped(0.05, 0.1), 0.0);
  EXPECT_EQ(RatePose::shaped(-0.1, 0.1), 0.0);
  EXPECT_DOUBLE_EQ(RatePose::shaped(0.55, 0.1), 0.5);
  EXPECT_DOUBLE_EQ(RatePose::shaped(-1.0, 0.1), -1.0);
  EXPECT_DOUBLE_EQ(RatePose::shaped(3.0, 0.1), 1.0) << "beyond full scale is full scale";
  EXPECT_EQ(RatePose::shaped(std::nan(""), 0.1), 0.0) << "a NaN moves nothing";
}

TEST(RatePose, FullDeflectionForOneSecondMovesTheFullSpeedAndStopsAtRest) {
  RatePose pose({0.05, 0.3, 0.1}, kPeriod);
  for (int i = 0; i < 1000; ++i) pose.step({1.0, -1.0, 0.0, 0.0, 0.0, 0.0});
  EXPECT_NEAR(pose.position().x(), 0.05, 1e-12);
  EXPECT_NEAR(pose.position().y(), -0.05, 1e-12);
  EXPECT_EQ(pose.position().z(), 0.0);
  EXPECT_DOUBLE_EQ(pose.twist()[0], 0.05);
  // the cap let go (within the dead band): the pose holds
  for (int i = 0; i < 100; ++i) pose.step({0.05, 0.0, 0.0, 0.0, 0.0, 0.0});
  EXPECT_NEAR(pose.position().x(), 0.05, 1e-12);
  EXPECT_EQ(pose.twist().norm(), 0.0);
}

TEST(RatePose, RotatesAboutTheBaseFramesAxesInTheOrderTurned) {
  RatePose pose({0.05, std::numbers::pi / 2, 0.0}, kPeriod);
  // a quarter turn about z, then one about x: the second turns the first about the base's x
  for (int i = 0; i < 1000; ++i) pose.step({0.0, 0.0, 0.0, 0.0, 0.0, 1.0});
  for (int i = 0; i < 1000; ++i) pose.step({0.0, 0.0, 0.0, 1.0, 0.0, 0.0});
  const Eigen::Matrix3d expected = (Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitX()) *
                                    Eigen::AngleAxisd(std::numbers::pi / 2, Eigen::Vector3d::UnitZ()))
                                       .toRotationMatrix();
  EXPECT_TRUE(pose.orientation().toRotationMatrix().isApprox(expected, 1e-9)) << pose.orientation().toRotationMatrix();
  EXPECT_NEAR(pose.orientation().norm(), 1.0, 1e-12);
}

}  // namespace
}  // namespace teleop::leader

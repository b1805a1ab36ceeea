// The SVH motor -> joint coupling q = S_m m + q0.
#include "teleop/hand/hand_coupling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "allocation_counter.h"

namespace teleop::hand {
namespace {

size_t joint(std::string_view name) {
  for (size_t j = 0; j < kHandJoints; ++j) {
    if (kHandJointNames[j] == name) return j;
  }
  ADD_FAILURE() << "no joint " << name;
  return 0;
}

TEST(HandCoupling, SvhHasOneTermPerJointAndEveryMotorDrivesItsNamesake) {
  const HandCoupling c = HandCoupling::svh();
  for (size_t k = 0; k < kHandMotors; ++k) {
    // the joint named like the motor follows it 1:1
    EXPECT_DOUBLE_EQ(c.coefficient(joint(kHandMotorNames[k]), k), 1.0) << kHandMotorNames[k];
  }
  for (size_t j = 0; j < kHandJoints; ++j) {
    int nonzero = 0;
    for (size_t k = 0; k < kHandMotors; ++k) nonzero += c.coefficient(j, k) != 0.0;
    EXPECT_EQ(nonzero, 1) << kHandJointNames[j];
  }
  EXPECT_EQ(c.offsets(), HandJointVector{});
}

TEST(HandCoupling, RingAndPinkyEachDriveTwoMoreJoints) {
  const HandCoupling c = HandCoupling::svh();
  int ring = 0;
  int pinky = 0;
  for (size_t j = 0; j < kHandJoints; ++j) {
    ring += c.coefficient(j, hand_motor::kRing) != 0.0;
    pinky += c.coefficient(j, hand_motor::kPinky) != 0.0;
  }
  EXPECT_EQ(ring, 3);
  EXPECT_EQ(pinky, 3);
  EXPECT_DOUBLE_EQ(c.coefficient(joint("j12"), hand_motor::kRing), 1.3588);
  EXPECT_DOUBLE_EQ(c.coefficient(joint("j16"), hand_motor::kRing), 1.42093);
  EXPECT_DOUBLE_EQ(c.coefficient(joint("j13"), hand_motor::kPinky), 1.3588);
  EXPECT_DOUBLE_EQ(c.coefficient(joint("j17"), hand_motor::kPinky), 1.42307);
}

TEST(HandCoupling, SpreadDrivesIndexAndRingSpreadAtHalf) {
  const HandCoupling c = HandCoupling::svh();
  EXPECT_DOUBLE_EQ(c.coefficient(joint("index_spread"), hand_motor::kFingerSpread), 0.5);
  EXPECT_DOUBLE_EQ(c.coefficient(joint("ring_spread"), hand_motor::kFingerSpread), 0.5);
  EXPECT_DOUBLE_EQ(c.coefficient(joint("Finger_Spread"), hand_motor::kFingerSpread), 1.0);
}

TEST(HandCoupling, MapsKnownMotorVectorToTwentyJoints) {
  const HandCoupling c = HandCoupling::svh();
  // thumb flexion, thumb opposition, index distal, index proximal, middle distal,
  // middle proximal, ring, pinky, spread
  const HandMotorVector m = {0.5, 0.3, 0.4, 0.2, 0.6, 0.1, 0.7, 0.8, 0.4};
  const HandJointVector q = c.joints_from_motors(m);
  // clang-format off
  const HandJointVector expected = {
      0.5,  0.5 * 1.01511,  0.5 * 1.44889,   // thumb flexion, j3, j4
      0.3,  0.3,                            // thumb opposition, j5
      0.4,  0.4 * 1.045,                    // index distal, j14
      0.2,                                  // index proximal
      0.6,  0.6 * 1.0454,                   // middle distal, j15
      0.1,                                  // middle proximal
      0.7,  0.7 * 1.3588,   0.7 * 1.42093,  // ring, j12, j16
      0.8,  0.8 * 1.3588,   0.8 * 1.42307,  // pinky, j13, j17
      0.4,  0.2,            0.2,            // finger spread, index spread, ring spread
  };  // clang-format on

  for (size_t j = 0; j < kHandJoints; ++j) EXPECT_NEAR(q[j], expected[j], 1e-12) << kHandJointNames[j];
}

TEST(HandCoupling, UnitMotorVectorsGiveTheColumnsOfSm) {
  const HandCoupling c = HandCoupling::svh();
  for (size_t k = 0; k < kHandMotors; ++k) {
    HandMotorVector m{};
    m[k] = 1.0;
    const HandJointVector q = c.joints_from_motors(m);
    for (size_t j = 0; j < kHandJoints; ++j) EXPECT_DOUBLE_EQ(q[j], c.coefficient(j, k));
  }
}

TEST(HandCoupling, AddsOffsets) {
  std::array<CouplingTerm, kHandJoints> terms = HandCoupling::svh().terms();
  HandJointVector q0{};
  q0[joint("j12")] = 0.1;
  q0[joint("index_spread")] = -0.05;
  const HandCoupling c(terms, q0);
  const HandJointVector q = c.joints_from_motors(HandMotorVector{});
  EXPECT_DOUBLE_EQ(q[joint("j12")], 0.1);
  EXPECT_DOUBLE_EQ(q[joint("index_spread")], -0.05);
  EXPECT_DOUBLE_EQ(q[joint("Pinky")], 0.0);
}

TEST(HandCoupling, LeastSquaresInvertsTheCoupling) {
  HandJointVector q0{};
  for (size_t j = 0; j < kHandJoints; ++j) q0[j] = 0.01 * static_cast<double>(j);
  const HandCoupling c(HandCoupling::svh().terms(), q0);
  const HandMotorVector m = {0.9, -0.2, 0.4, 0.25, 0.6, 0.15, 0.7, 0.8, 0.3};
  const HandMotorVector back = c.motors_from_joints(c.joints_from_motors(m));
  for (size_t k = 0; k < kHandMotors; ++k) EXPECT_NEAR(back[k], m[k], 1e-12);
}

TEST(HandCoupling, RejectsBadTerms) {
  auto terms = HandCoupling::svh().terms();
  auto bad_motor = terms;
  bad_motor[3].motor = 9;
  EXPECT_THROW(HandCoupling(bad_motor, {}), std::invalid_argument);
  auto nan_factor = terms;
  nan_factor[0].factor = std::nan("");
  EXPECT_THROW(HandCoupling(nan_factor, {}), std::invalid_argument);
  auto orphan = terms;
  orphan[joint("Index_Finger_Proximal")].motor = hand_motor::kIndexDistal;  // motor 3 drives nothing
  EXPECT_THROW(HandCoupling(orphan, {}), std::invalid_argument);
  HandJointVector nan_offset{};
  nan_offset[5] = std::nan("");
  EXPECT_THROW(HandCoupling(terms, nan_offset), std::invalid_argument);
}

TEST(HandCoupling, MappingDoesNotAllocate) {
  const HandCoupling c = HandCoupling::svh();
  const HandMotorVector m = {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9};
  test::ScopedAllocationCounter counter;
  const HandMotorVector back = c.motors_from_joints(c.joints_from_motors(m));
  EXPECT_NEAR(back[8], 0.9, 1e-12);
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::hand

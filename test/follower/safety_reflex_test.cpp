#include "teleop/follower/safety_reflex.h"

#include <gtest/gtest.h>
#include <teleop/msg/status.h>

#include <cmath>

#include "allocation_counter.h"

namespace teleop::follower {
namespace {

using control::JointVector;
using control::Vector6;

const JointVector kRest = JointVector::Zero();

TEST(SafetyReflex, StaysQuietBelowEveryThreshold) {
  SafetyReflex reflex(SafetyReflexConfig{});
  const JointVector tau = JointVector::Constant(11.9);  // under the smallest (joint 7: 12 Nm)
  const JointVector dq = JointVector::Constant(2.17);   // under the shoulder's 2.175 rad/s
  Vector6 wrench;
  wrench << 19.9, -19.9, 19.9, 24.9, -24.9, 24.9;
  EXPECT_FALSE(reflex.check(tau, wrench, dq));
  EXPECT_FALSE(reflex.latched());
  EXPECT_EQ(reflex.trips(), 0u);
  EXPECT_GT(reflex.peak_ratio(), 0.99);
  EXPECT_LT(reflex.peak_ratio(), 1.0);
}

TEST(SafetyReflex, TripsOnAJointTorqueAndLatchesUntilReset) {
  SafetyReflex reflex(SafetyReflexConfig{});
  JointVector tau = JointVector::Zero();
  tau[6] = -12.5;  // joint 7's threshold is 12 Nm, either sign
  EXPECT_TRUE(reflex.check(tau, Vector6::Zero(), kRest));
  EXPECT_EQ(reflex.last_cause(), ReflexCause::kJointTorque);
  EXPECT_EQ(reflex.fault_code(), msg::FAULT_CONTACT_REFLEX);
  EXPECT_NEAR(reflex.last_trip_ratio(), 12.5 / 12.0, 1e-12);
  // latched: the load going away does not clear it, nor does it trip again
  EXPECT_FALSE(reflex.check(JointVector::Zero(), Vector6::Zero(), kRest));
  EXPECT_TRUE(reflex.latched());
  reflex.reset();
  EXPECT_FALSE(reflex.latched());
  EXPECT_EQ(reflex.trips(), 1u);
}

TEST(SafetyReflex, NamesTheLargestExcessAsTheCause) {
  SafetyReflex reflex(SafetyReflexConfig{});
  JointVector tau = JointVector::Zero();
  tau[0] = 21.0;  // 1.05 of its threshold
  Vector6 wrench = Vector6::Zero();
  wrench[2] = -30.0;  // 1.5 of the force threshold along z
  EXPECT_TRUE(reflex.check(tau, wrench, kRest));
  EXPECT_EQ(reflex.last_cause(), ReflexCause::kForce);
  EXPECT_NEAR(reflex.last_trip_ratio(), 1.5, 1e-12);
}

TEST(SafetyReflex, TripsOnAMomentOnASpeedAndOnANonFiniteEstimate) {
  SafetyReflex moment(SafetyReflexConfig{});
  Vector6 wrench = Vector6::Zero();
  wrench[4] = 26.0;
  EXPECT_TRUE(moment.check(JointVector::Zero(), wrench, kRest));
  EXPECT_EQ(moment.last_cause(), ReflexCause::kTorque);

  SafetyReflex speed(SafetyReflexConfig{});
  JointVector dq = JointVector::Zero();
  dq[5] = -2.7;  // the wrist's limit is 2.61 rad/s
  EXPECT_TRUE(speed.check(JointVector::Zero(), Vector6::Zero(), dq));
  EXPECT_EQ(speed.last_cause(), ReflexCause::kJointVelocity);
  EXPECT_EQ(speed.fault_code(), msg::FAULT_SPEED_REFLEX);

  SafetyReflex nan(SafetyReflexConfig{});
  JointVector tau = JointVector::Zero();
  tau[3] = std::nan("");
  EXPECT_TRUE(nan.check(tau, Vector6::Zero(), kRest));
  EXPECT_EQ(nan.last_cause(), ReflexCause::kJointTorque);
}

TEST(SafetyReflex, NeverTripsWhenOff) {
  SafetyReflexConfig config;
  config.enabled = false;
  SafetyReflex reflex(config);
  EXPECT_FALSE(reflex.check(JointVector::Constant(1e4), Vector6::Constant(1e4), JointVector::Constant(1e4)));
  EXPECT_FALSE(reflex.latched());
}

TEST(SafetyReflex, ChecksWithoutAllocating) {
  SafetyReflex reflex(SafetyReflexConfig{});
  const JointVector tau = JointVector::Constant(30.0);
  const Vector6 wrench = Vector6::Constant(1.0);
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 100; ++i) {
    (void)reflex.check(tau, wrench, kRest);
    reflex.reset();
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::follower

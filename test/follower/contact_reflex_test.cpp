#include "teleop/follower/contact_reflex.h"

#include <gtest/gtest.h>

#include <cmath>

#include "allocation_counter.h"

namespace teleop::follower {
namespace {

using control::JointVector;
using control::Vector6;

TEST(ContactReflex, StaysQuietBelowEveryThreshold) {
  ContactReflex reflex(ContactReflexConfig{});
  JointVector tau = JointVector::Constant(11.9);  // under the smallest (joint 7: 12 Nm)
  Vector6 wrench;
  wrench << 19.9, -19.9, 19.9, 24.9, -24.9, 24.9;
  EXPECT_FALSE(reflex.check(tau, wrench));
  EXPECT_FALSE(reflex.latched());
  EXPECT_EQ(reflex.trips(), 0u);
}

TEST(ContactReflex, TripsOnAJointTorqueAndLatchesUntilReset) {
  ContactReflex reflex(ContactReflexConfig{});
  JointVector tau = JointVector::Zero();
  tau[6] = -12.5;  // joint 7's threshold is 12 Nm, either sign
  EXPECT_TRUE(reflex.check(tau, Vector6::Zero()));
  EXPECT_EQ(reflex.last_cause(), ReflexCause::kJointTorque);
  EXPECT_NEAR(reflex.last_trip_ratio(), 12.5 / 12.0, 1e-12);
  // latched: the load going away does not clear it, nor does it trip again
  EXPECT_FALSE(reflex.check(JointVector::Zero(), Vector6::Zero()));
  EXPECT_TRUE(reflex.latched());
  reflex.reset();
  EXPECT_FALSE(reflex.latched());
  EXPECT_EQ(reflex.trips(), 1u);
}

TEST(ContactReflex, NamesTheLargestExcessAsTheCause) {
  ContactReflex reflex(ContactReflexConfig{});
  JointVector tau = JointVector::Zero();
  tau[0] = 21.0;  // 1.05 of its threshold
  Vector6 wrench = Vector6::Zero();
  wrench[2] = -30.0;  // 1.5 of the force threshold along z
  EXPECT_TRUE(reflex.check(tau, wrench));
  EXPECT_EQ(reflex.last_cause(), ReflexCause::kForce);
  EXPECT_NEAR(reflex.last_trip_ratio(), 1.5, 1e-12);
}

TEST(ContactReflex, TripsOnAMomentAndOnANonFiniteEstimate) {
  ContactReflex moment(ContactReflexConfig{});
  Vector6 wrench = Vector6::Zero();
  wrench[4] = 26.0;
  EXPECT_TRUE(moment.check(JointVector::Zero(), wrench));
  EXPECT_EQ(moment.last_cause(), ReflexCause::kTorque);

  ContactReflex nan(ContactReflexConfig{});
  JointVector tau = JointVector::Zero();
  tau[3] = std::nan("");
  EXPECT_TRUE(nan.check(tau, Vector6::Zero()));
  EXPECT_EQ(nan.last_cause(), ReflexCause::kJointTorque);
}

TEST(ContactReflex, NeverTripsWhenOff) {
  ContactReflexConfig config;
  config.enabled = false;
  ContactReflex reflex(config);
  EXPECT_FALSE(reflex.check(JointVector::Constant(1e4), Vector6::Constant(1e4)));
  EXPECT_FALSE(reflex.latched());
}

TEST(ContactReflex, ChecksWithoutAllocating) {
  ContactReflex reflex(ContactReflexConfig{});
  const JointVector tau = JointVector::Constant(30.0);
  const Vector6 wrench = Vector6::Constant(1.0);
  test::ScopedAllocationCounter counter;
  for (int i = 0; i < 100; ++i) {
    (void)reflex.check(tau, wrench);
    reflex.reset();
  }
  EXPECT_EQ(counter.count(), 0u);
}

}  // namespace
}  // namespace teleop::follower

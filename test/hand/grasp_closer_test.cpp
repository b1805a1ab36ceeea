// GraspCloser: shaping motors straight to their angle, the others closing until they stop
// following, then a fixed squeeze past the contact.
#include "teleop/hand/grasp_closer.h"

#include <gtest/gtest.h>

namespace teleop::hand {
namespace {

TEST(GraspCloser, ClosesUntilAFingerStopsFollowingThenSqueezesPastTheContact) {
  HandMotorVector closed{};
  closed.fill(1.0);
  GraspCloserConfig c = power_grasp(closed);
  GraspCloser closer(c);
  closer.start(HandMotorVector{});
  HandMotorVector measured{};
  const size_t k = hand_motor::kIndexProximal;
  // the shaping phase: the opposition moves, the fingers wait
  closer.update(0.5, measured);
  EXPECT_NEAR(closer.targets()[hand_motor::kThumbOpposition], 0.25, 1e-9);
  EXPECT_EQ(closer.targets()[k], 0.0);
  // then every finger closes at 0.5 rad/s while it follows (measured = target)
  double t = 0.5;
  for (; t < 1.0; t += 0.01) measured = closer.update(t, measured);
  EXPECT_GT(closer.targets()[k], 0.15);
  EXPECT_FALSE(closer.in_contact(k));
  // the finger is held at 0.2: once it lags by more than 0.08 it is in contact
  HandMotorVector held = measured;
  held[k] = 0.2;
  for (; t < 1.5 && !closer.in_contact(k); t += 0.01) {
    measured = closer.update(t, held);
    held = measured;
    held[k] = 0.2;
  }
  ASSERT_TRUE(closer.in_contact(k));
  EXPECT_EQ(closer.contact_rad(k), 0.2);
  EXPECT_NEAR(closer.targets()[k], 0.2 + c.squeeze_rad, 1e-12);
  // and stays there while the others close on
  for (; t < 4.0; t += 0.01) {
    measured = closer.update(t, held);
    held = measured;
    held[k] = 0.22;
  }
  EXPECT_NEAR(closer.targets()[k], 0.2 + c.squeeze_rad, 1e-12);
  // a finger that meets nothing ends at its closed angle; the spread at 0
  EXPECT_NEAR(closer.targets()[hand_motor::kRing], 1.0, 1e-9);
  EXPECT_EQ(closer.targets()[hand_motor::kFingerSpread], 0.0);
  EXPECT_NEAR(closer.targets()[hand_motor::kThumbOpposition], 0.9, 1e-9);
  EXPECT_EQ(c.current_limit_a[k], 1.0);
  EXPECT_EQ(c.current_limit_a[hand_motor::kThumbFlexion], 1.5);
}

}  // namespace
}  // namespace teleop::hand

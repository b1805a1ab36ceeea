// MMT's object update, pure arithmetic: the pull of the twin's object towards the remote site's
// measurement (twin/object_correction.h).
#include "object_correction.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace teleop::twin {
namespace {

ObjectCorrectionConfig config() {
  ObjectCorrectionConfig c;
  c.bodies = {"box"};
  c.stiffness_n_per_m = 200.0;
  c.damping_ns_per_m = 30.0;
  c.stiffness_nm_per_rad = 2.0;
  c.damping_nms_per_rad = 0.3;
  c.max_force_n = 8.0;
  c.max_torque_nm = 1.0;
  c.timeout_s = 0.1;
  return c;
}

sim::BodyState at(double x, double y, double z) {
  sim::BodyState s;
  s.position_m = {x, y, z};
  return s;
}

TEST(ObjectCorrection, PullsNothingBeforeAMeasurement) {
  ObjectCorrection c(config());
  const CorrectionWrench w = c.wrench(at(0.3, 0, 0.8), 1.0);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(w.force_n[k], 0.0);
    EXPECT_EQ(w.torque_nm[k], 0.0);
  }
  EXPECT_TRUE(std::isnan(c.position_error_m()));
}

TEST(ObjectCorrection, SpringTowardsTheMeasuredPositionAndDamperOnTheVelocityDifference) {
  ObjectCorrection c(config());
  sim::BodyState measured = at(0.30, 0.0, 0.82);  // 2 cm above the twin's box
  ASSERT_EQ(c.measure(measured, 0.0, 1.0), ObjectCorrection::Outcome::kAccepted);
  sim::BodyState twin = at(0.30, 0.0, 0.80);
  twin.linear_mps = {0.0, 0.01, 0.0};  // drifting sideways where the remote box is still
  const CorrectionWrench w = c.wrench(twin, 1.0);
  EXPECT_NEAR(w.force_n[2], 200.0 * 0.02, 1e-9);
  EXPECT_NEAR(w.force_n[1], -30.0 * 0.01, 1e-9);
  EXPECT_NEAR(w.force_n[0], 0.0, 1e-12);
  EXPECT_NEAR(c.position_error_m(), 0.02, 1e-12);
  EXPECT_NEAR(c.force_n(), std::hypot(4.0, 0.3), 1e-9);
  EXPECT_EQ(c.clamped(), 0u);
}

TEST(ObjectCorrection, CarriesTheMeasurementForwardOverItsAge) {
  ObjectCorrection c(config());
  sim::BodyState measured = at(0.30, 0.0, 0.80);
  measured.linear_mps = {0.2, 0.0, 0.0};
  // 17 ms old on arrival at t = 5 s; the twin asks 3 ms later: 20 ms of motion at 0.2 m/s
  ASSERT_EQ(c.measure(measured, 0.017, 5.0), ObjectCorrection::Outcome::kAccepted);
  EXPECT_NEAR(c.predicted_position_m(5.003)[0], 0.304, 1e-12);
  sim::BodyState twin = at(0.304, 0.0, 0.80);
  twin.linear_mps = measured.linear_mps;
  const CorrectionWrench w = c.wrench(twin, 5.003);
  EXPECT_NEAR(w.force_n[0], 0.0, 1e-9) << "a box carried in step with the remote one is not pulled back";
}

TEST(ObjectCorrection, TurnsTheShortWayTowardsTheMeasuredOrientation) {
  ObjectCorrection c(config());
  sim::BodyState measured = at(0.3, 0.0, 0.8);
  const double angle = 0.1;  // about z
  measured.orientation_wxyz = {std::cos(angle / 2), 0.0, 0.0, std::sin(angle / 2)};
  ASSERT_EQ(c.measure(measured, 0.0, 0.0), ObjectCorrection::Outcome::kAccepted);
  const CorrectionWrench w = c.wrench(at(0.3, 0.0, 0.8), 0.0);
  EXPECT_NEAR(w.torque_nm[2], 2.0 * angle, 1e-9);
  EXPECT_NEAR(w.torque_nm[0], 0.0, 1e-12);
  // the same orientation as the negated quaternion: the same pull, not the long way round
  measured.orientation_wxyz = {-std::cos(angle / 2), 0.0, 0.0, -std::sin(angle / 2)};
  ASSERT_EQ(c.measure(measured, 0.0, 0.0), ObjectCorrection::Outcome::kAccepted);
  EXPECT_NEAR(c.wrench(at(0.3, 0.0, 0.8), 0.0).torque_nm[2], 2.0 * angle, 1e-9);
}

TEST(ObjectCorrection, CutsForceAndMomentAtTheirBoundsAndCountsIt) {
  ObjectCorrection c(config());
  sim::BodyState measured = at(0.3, 0.3, 0.4);  // half a metre away: 100 N of spring
  measured.orientation_wxyz = {0.0, 1.0, 0.0, 0.0};  // half a turn: 6.3 N m of spring
  ASSERT_EQ(c.measure(measured, 0.0, 0.0), ObjectCorrection::Outcome::kAccepted);
  const CorrectionWrench w = c.wrench(at(0.3, 0.0, 0.8), 0.0);
  EXPECT_NEAR(std::hypot(w.force_n[0], w.force_n[1], w.force_n[2]), 8.0, 1e-9);
  EXPECT_NEAR(std::hypot(w.torque_nm[0], w.torque_nm[1], w.torque_nm[2]), 1.0, 1e-9);
  EXPECT_GT(w.force_n[1], 0.0) << "cut, still towards the measurement";
  EXPECT_LT(w.force_n[2], 0.0);
  EXPECT_EQ(c.clamped(), 1u);
}

TEST(ObjectCorrection, IgnoresAndCountsStaleAndNonFiniteMeasurementsKeepingTheLastGoodOne) {
  ObjectCorrection c(config());
  ASSERT_EQ(c.measure(at(0.3, 0.0, 0.81), 0.0, 0.0), ObjectCorrection::Outcome::kAccepted);
  EXPECT_EQ(c.measure(at(0.3, 0.0, 0.9), 0.5, 0.01), ObjectCorrection::Outcome::kStale);
  EXPECT_EQ(c.measure(at(std::nan(""), 0.0, 0.9), 0.0, 0.01), ObjectCorrection::Outcome::kNonFinite);
  sim::BodyState unnormalised = at(0.3, 0.0, 0.9);
  unnormalised.orientation_wxyz = {2.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(c.measure(unnormalised, 0.0, 0.01), ObjectCorrection::Outcome::kNonFinite);
  sim::BodyState infinite_speed = at(0.3, 0.0, 0.9);
  infinite_speed.angular_radps[1] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(c.measure(infinite_speed, 0.0, 0.01), ObjectCorrection::Outcome::kNonFinite);
  EXPECT_EQ(c.stale(), 1u);
  EXPECT_EQ(c.non_finite(), 3u);
  EXPECT_EQ(c.accepted(), 1u);
  EXPECT_NEAR(c.wrench(at(0.3, 0.0, 0.8), 0.01).force_n[2], 200.0 * 0.01, 1e-9) << "still the first measurement";
}

TEST(ObjectCorrection, LetsGoOnceTheMeasurementIsOlderThanTheTimeout) {
  ObjectCorrection c(config());
  ASSERT_EQ(c.measure(at(0.3, 0.0, 0.81), 0.02, 10.0), ObjectCorrection::Outcome::kAccepted);
  EXPECT_GT(c.wrench(at(0.3, 0.0, 0.8), 10.07).force_n[2], 0.0) << "90 ms old: still pulls";
  EXPECT_EQ(c.wrench(at(0.3, 0.0, 0.8), 10.09).force_n[2], 0.0) << "110 ms old: the remote site went quiet";
  EXPECT_TRUE(std::isnan(c.position_error_m()));
}

}  // namespace
}  // namespace teleop::twin

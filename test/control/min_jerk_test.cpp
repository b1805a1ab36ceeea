// The minimum-jerk motion and path (control/include/teleop/control/min_jerk.h): at rest at the
// ends, 15/8 of the mean speed at half time, the velocity the position's derivative, waypoints
// passed at rest, the last held.
#include "teleop/control/min_jerk.h"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace teleop::control {
namespace {

TEST(MinJerkProfile, RisesFromZeroToOneAtRestAtBothEnds) {
  EXPECT_EQ(min_jerk_progress(0.0), 0.0);
  EXPECT_DOUBLE_EQ(min_jerk_progress(0.5), 0.5);
  EXPECT_DOUBLE_EQ(min_jerk_progress(1.0), 1.0);
  EXPECT_EQ(min_jerk_rate(0.0), 0.0);
  EXPECT_DOUBLE_EQ(min_jerk_rate(0.5), 1.875);
  EXPECT_EQ(min_jerk_rate(1.0), 0.0);
}

TEST(MinJerkMotion, StartsAndEndsAtRestAndPeaksAtHalfTimeWithFifteenEighthsTheMeanSpeed) {
  const MinJerkMotion motion({0.0, 1.0}, {2.0, 1.0}, 4.0);
  std::vector<double> q(2);
  std::vector<double> dq(2);
  motion.sample(-1.0, q, dq);
  EXPECT_EQ(q[0], 0.0);
  EXPECT_EQ(dq[0], 0.0);
  motion.sample(2.0, q, dq);
  EXPECT_DOUBLE_EQ(q[0], 1.0);
  EXPECT_DOUBLE_EQ(dq[0], 1.875 * 2.0 / 4.0);
  EXPECT_DOUBLE_EQ(q[1], 1.0);
  EXPECT_EQ(dq[1], 0.0);
  motion.sample(4.0, q, dq);
  EXPECT_DOUBLE_EQ(q[0], 2.0);
  EXPECT_EQ(dq[0], 0.0);
  // the velocity is the derivative of the position
  std::vector<double> q2(2);
  motion.sample(1.0, q, dq);
  motion.sample(1.0 + 1e-6, q2, dq);
  EXPECT_NEAR((q2[0] - q[0]) / 1e-6, dq[0], 1e-5);
  EXPECT_THROW(MinJerkMotion({0.0}, {1.0, 2.0}, 1.0), std::invalid_argument);
  EXPECT_THROW(MinJerkMotion({0.0}, {1.0}, 0.0), std::invalid_argument);
}

TEST(MinJerkPath, PassesEachWaypointAtRestAndHoldsTheLast) {
  MinJerkPath path({0.0});
  std::vector<double> q(1);
  std::vector<double> dq(1);
  path.sample(5.0, q, dq);  // no motion yet: the start
  EXPECT_EQ(q[0], 0.0);
  path.then({1.0}, 2.0);
  path.then({3.0}, 1.0);
  EXPECT_DOUBLE_EQ(path.duration_s(), 3.0);
  path.sample(1.0, q, dq);
  EXPECT_DOUBLE_EQ(q[0], 0.5);
  path.sample(2.0, q, dq);
  EXPECT_DOUBLE_EQ(q[0], 1.0);
  EXPECT_EQ(dq[0], 0.0);
  path.sample(2.5, q, dq);
  EXPECT_DOUBLE_EQ(q[0], 2.0);
  EXPECT_DOUBLE_EQ(dq[0], 1.875 * 2.0 / 1.0);
  path.sample(10.0, q, dq);
  EXPECT_DOUBLE_EQ(q[0], 3.0);
  EXPECT_EQ(dq[0], 0.0);
  EXPECT_THROW(MinJerkPath({}), std::invalid_argument);
}

}  // namespace
}  // namespace teleop::control

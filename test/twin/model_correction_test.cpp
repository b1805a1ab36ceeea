// MMT's model update in the twin node, over DDS: the follower's joint state and wrench move the
// twin's wall (ModelCorrection), malformed samples are ignored and counted, and the cycle with the
// correction does not allocate.
#include <gtest/gtest.h>

#include <limits>
#include <thread>

#include "node_harness.h"
#include "report_counter.h"
#include "teleop/transport/joint_fields.h"
#include "twin_node.h"
#include "twin_node_test_util.h"
#include "twin_test_util.h"

namespace teleop::twin {
namespace {

constexpr size_t kJoints = 7;
constexpr double kRateMPerS = 0.02;

TwinConfig config() {
  TwinConfig c;
  c.model = test::wall_model();
  c.mmt.enabled = true;
  CorrectionConfig correction;
  correction.probe = "geom:link7_flange";  // the simulation's distance pair: the same gap
  correction.max_offset_m = 0.1;
  correction.rate_m_per_s = kRateMPerS;
  c.mmt.correction = correction;
  return c;
}

// the follower's side: its measured joint state and estimated wrench
struct FollowerPeer {
  transport::Publication<msg::JointState> state;
  transport::Publication<msg::WrenchStamped> wrench;
  explicit FollowerPeer(transport::Participant& p)
      : state(p, transport::topics::kFollowerState, "follower"), wrench(p, transport::topics::kFollowerWrench, "follower") {
    transport::presize_joint_state(state.sample(), kJoints);
  }
  void publish(const JointVector& q, double force_x_n) {
    transport::copy_joints(q, kJoints, state.sample().q_rad());
    const double force[3] = {force_x_n, 0.0, 0.0};
    const double torque[3] = {0.0, 0.0, 0.0};
    transport::set_wrench(wrench.sample(), force, torque);
    EXPECT_TRUE(state.publish());
    EXPECT_TRUE(wrench.publish());
  }
};

class ModelCorrectionTest : public ::testing::Test {
 protected:
  teleop::test::NodeHarness harness{"twin"};
  TwinNode node{config(), harness.context};
  FollowerPeer follower{harness.peer};
  JointVector home = node.simulation().q_rad();

  void SetUp() override {
    ASSERT_TRUE(teleop::test::eventually([&] { return follower.state.matched() > 0 && follower.wrench.matched() > 0; }));
  }

  // the follower at `q` pushed with `force_x_n` along x, for `cycles` of the twin
  void follower_at(const JointVector& q, double force_x_n, int cycles) {
    (void)test::drive_cycles(node, harness, cycles, [&](int) { follower.publish(q, force_x_n); });
  }

  double counter(const std::string& name) const {
    runtime::NodeReport report;
    node.fill_report(report);
    return teleop::test::counter(report, name);
  }
};

TEST_F(ModelCorrectionTest, AFollowerInContactWhereTheTwinIsFreeBringsTheWallToIt) {
  // the follower at the start pose, 5 cm in front of the twin's wall, feels the real wall (the
  // wall pushes it back along -x = along n): the real wall is 5 cm nearer than the twin's
  const double gap_m = node.simulation().distance_m(0);
  ASSERT_GT(gap_m, 0.03);
  follower_at(home, -15.0, 300);
  ASSERT_GT(counter("correction_contact_updates"), 0);
  EXPECT_NEAR(counter("env_estimate_m"), gap_m, 1e-6);
  const double applied = counter("env_offset_m");
  EXPECT_GT(applied, 0.0);
  EXPECT_LE(applied, kRateMPerS * 300 * 1e-3 + 1e-12) << "no faster than the rate limit";
  // and the twin's own wall has moved by that much towards its arm
  EXPECT_NEAR(node.simulation().distance_m(0), gap_m - applied, 1e-4);
}

TEST_F(ModelCorrectionTest, AFreeFollowerInFrontOfTheWallTeachesNothing) {
  follower_at(home, 0.0, 100);
  EXPECT_EQ(counter("env_estimate_m"), 0.0);
  EXPECT_EQ(counter("env_offset_m"), 0.0);
}

TEST_F(ModelCorrectionTest, IgnoresAndCountsNonFiniteAndMalformedSamples) {
  JointVector q = home;
  q[0] = std::numeric_limits<double>::quiet_NaN();
  follower_at(q, -15.0, 20);
  // three angles for a seven-joint arm (published as is, not through follower_at, which resizes)
  follower.state.sample().q_rad().resize(3);
  (void)test::drive_cycles(node, harness, 20, [&](int) {
    EXPECT_TRUE(follower.state.publish());
    EXPECT_TRUE(follower.wrench.publish());
  });
  EXPECT_GT(counter("correction_rejected"), 0);
  EXPECT_GT(counter("correction_malformed"), 0);
  EXPECT_EQ(counter("correction_contact_updates"), 0);
  EXPECT_EQ(counter("env_estimate_m"), 0.0);
}

TEST_F(ModelCorrectionTest, CycleWithTheCorrectionDoesNotAllocate) {
  follower_at(home, -15.0, 100);
  const uint64_t allocations =
      test::drive_cycles(node, harness, 300, [&](int) { follower.publish(home, -15.0); });
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(counter("correction_contact_updates"), 100);
}

}  // namespace
}  // namespace teleop::twin

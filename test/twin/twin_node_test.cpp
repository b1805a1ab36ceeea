#include "teleop/twin/twin_node.h"

#include <gtest/gtest.h>

#include <thread>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::twin {
namespace {

constexpr size_t kJoints = 3;
constexpr double kWall = 0.2;

TwinConfig config() {
  TwinConfig c;
  c.model.joints = kJoints;
  c.model.wall_q_rad = kWall;
  c.feedback_cutoff_hz = 0;  // unfiltered, so a test sees the torque of this very cycle
  c.feedback_gain = 0.5;
  return c;
}

// the leader's side: publishes its device state, reads the rendered feedback
struct LeaderPeer {
  transport::Publication<msg::JointState> state;
  transport::Subscription<msg::JointTorque> feedback;
  explicit LeaderPeer(transport::Participant& p)
      : state(p, transport::topics::kLeaderState, "leader"), feedback(p, transport::topics::kTwinFeedback) {
    transport::presize_joint_state(state.sample(), kJoints);
  }
};

class TwinNodeTest : public ::testing::Test {
 protected:
  test::NodeHarness harness{"twin"};
  TwinNode node{config(), harness.context};
  LeaderPeer leader{harness.peer};

  void SetUp() override {
    ASSERT_TRUE(test::eventually([&] { return leader.state.matched() > 0 && leader.feedback.reader().matched() > 0; }));
  }

  // holds the leader at q0 for `cycles` and returns the last feedback torque on joint 0
  double hold_leader_at(double q0, int cycles) {
    for (int i = 0; i < cycles; ++i) {
      leader.state.sample().q_rad()[0] = q0;
      EXPECT_TRUE(leader.state.publish());
      std::this_thread::sleep_for(std::chrono::microseconds(500));
      node.cycle(harness.tick());
    }
    double tau = 0;
    test::eventually([&] {
      leader.feedback.poll();
      if (!leader.feedback.has_sample()) return false;
      tau = leader.feedback.latest().tau_nm()[0];
      return true;
    });
    return tau;
  }
};

TEST_F(TwinNodeTest, RendersNoFeedbackInFreeSpace) {
  EXPECT_NEAR(hold_leader_at(0.1, 800), 0.0, 1e-9);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
}

TEST_F(TwinNodeTest, FeedbackPointsOutOfTheWallAndGrowsWithPenetration) {
  const double shallow = hold_leader_at(kWall + 0.05, 1500);
  const double deep = hold_leader_at(kWall + 0.15, 1500);
  EXPECT_LT(shallow, 0.0) << "pushes the leader back, out of the wall (towards lower q)";
  EXPECT_LT(deep, shallow) << "deeper into the wall: larger feedback";
}

TEST_F(TwinNodeTest, StopsRenderingWhenTheLeaderGoesSilent) {
  hold_leader_at(kWall + 0.1, 500);
  for (int i = 0; i < 300; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(1000));
    node.cycle(harness.tick());
  }
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  ASSERT_TRUE(test::eventually([&] {
    leader.feedback.poll();
    return leader.feedback.latest().tau_nm()[0] == 0.0;
  }));
}

TEST_F(TwinNodeTest, CycleDoesNotAllocate) {
  hold_leader_at(0.3, 200);
  uint64_t allocations = 0;
  for (int i = 0; i < 1000; ++i) {
    leader.state.sample().q_rad()[0] = 0.3 + 1e-4 * i;
    ASSERT_TRUE(leader.state.publish());
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    const CycleTick tick = harness.tick();
    test::ScopedAllocationCounter counter;
    node.cycle(tick);
    allocations += counter.count();
  }
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace teleop::twin

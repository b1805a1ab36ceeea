// The twin node in real-time mode, coupled to a leader over DDS.
#include "twin_node.h"

#include <gtest/gtest.h>

#include <thread>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/transport/joint_fields.h"
#include "twin_node_test_util.h"
#include "twin_test_util.h"

namespace teleop::twin {
namespace {

using test::kShoulder;
constexpr size_t kJoints = 7;

TwinConfig config() {
  TwinConfig c;
  c.model = test::wall_model();
  c.feedback_cutoff_hz = 0;  // unfiltered, so a test sees the torque of this very cycle
  c.feedback_gain = 0.5;
  return c;
}

// the leader's side: publishes its device state, reads the rendered feedback and the observations
struct LeaderPeer {
  transport::Publication<msg::JointState> state;
  transport::Subscription<msg::JointTorque> feedback;
  transport::Subscription<msg::GeomDistances> distances;
  transport::Subscription<msg::WrenchStamped> wrench;
  explicit LeaderPeer(transport::Participant& p)
      : state(p, transport::topics::kLeaderState, "leader"),
        feedback(p, transport::topics::kTwinFeedback),
        distances(p, transport::topics::kTwinDistances),
        wrench(p, transport::TopicSpec<msg::WrenchStamped>{"teleop/twin/contact_wrench/flange_wall",
                                                           transport::QosPreset::kStream}) {
    transport::presize_joint_state(state.sample(), kJoints);
  }
};

class TwinNodeTest : public ::testing::Test {
 protected:
  teleop::test::NodeHarness harness{"twin"};
  TwinNode node{config(), harness.context};
  LeaderPeer leader{harness.peer};
  JointVector home = node.simulation().q_rad();

  void SetUp() override {
    ASSERT_TRUE(teleop::test::eventually([&] {
      return leader.state.matched() > 0 && leader.feedback.reader().matched() > 0 && leader.wrench.reader().matched() > 0;
    }));
  }

  // holds the leader at home + offset on the shoulder for `cycles`; returns the last shoulder feedback
  double hold_leader_at(double offset, int cycles) {
    for (int i = 0; i < cycles; ++i) {
      transport::copy_joints(home, kJoints, leader.state.sample().q_rad());
      leader.state.sample().q_rad()[kShoulder] += offset;
      EXPECT_TRUE(leader.state.publish());
      std::this_thread::sleep_for(std::chrono::microseconds(300));
      node.cycle(harness.tick());
    }
    double tau = 0;
    teleop::test::eventually([&] {
      leader.feedback.poll();
      if (!leader.feedback.has_sample()) return false;
      tau = leader.feedback.latest().tau_nm()[kShoulder];
      return true;
    });
    return tau;
  }
};

TEST_F(TwinNodeTest, RendersNoFeedbackInFreeSpace) {
  EXPECT_NEAR(hold_leader_at(0.0, 300), 0.0, 1e-9);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
}

TEST_F(TwinNodeTest, FeedbackPointsOutOfTheWallAndGrowsWithPenetration) {
  const double shallow = hold_leader_at(0.15, 800);
  const double deep = hold_leader_at(0.25, 800);
  EXPECT_LT(shallow, 0.0) << "pushes the leader back, out of the wall (towards lower q)";
  EXPECT_LT(deep, shallow) << "deeper into the wall: larger feedback";
}

TEST_F(TwinNodeTest, PublishesContactWrenchAndDistanceOfTheConfiguredPairs) {
  hold_leader_at(0.2, 800);
  ASSERT_TRUE(teleop::test::eventually([&] {
    leader.wrench.poll();
    leader.distances.poll();
    return leader.wrench.has_sample() && leader.distances.has_sample();
  }));
  EXPECT_LT(leader.wrench.latest().force_n().x(), -1.0) << "the wall pushes the flange back (-x)";
  ASSERT_EQ(leader.distances.latest().pair().size(), 1u);
  EXPECT_EQ(leader.distances.latest().pair()[0], "flange_wall");
  EXPECT_LT(leader.distances.latest().distance_m()[0], 1e-3);
}

TEST_F(TwinNodeTest, StopsRenderingWhenTheLeaderGoesSilent) {
  hold_leader_at(0.2, 500);
  for (int i = 0; i < 300; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(1000));
    node.cycle(harness.tick());
  }
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_EQ(faults, std::vector<uint32_t>{msg::FAULT_PEER_LOST});
  ASSERT_TRUE(teleop::test::eventually([&] {
    leader.feedback.poll();
    return leader.feedback.has_sample() && leader.feedback.latest().tau_nm()[kShoulder] == 0.0;
  }));
}

TEST_F(TwinNodeTest, CountsMalformedLeaderSamples) {
  leader.state.sample().q_rad().resize(3);
  for (int i = 0; i < 20; ++i) {
    ASSERT_TRUE(leader.state.publish());
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    node.cycle(harness.tick());
  }
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_NE(std::find(faults.begin(), faults.end(), msg::FAULT_COMMAND_REJECTED), faults.end());
  leader.state.sample().q_rad().resize(kJoints);
}

TEST_F(TwinNodeTest, CycleDoesNotAllocate) {
  hold_leader_at(0.2, 200);
  const uint64_t allocations = test::drive_cycles(node, harness, 500, [&](int i) {
    transport::copy_joints(home, kJoints, leader.state.sample().q_rad());
    leader.state.sample().q_rad()[kShoulder] += 0.2 + 1e-4 * i;
    EXPECT_TRUE(leader.state.publish());
  });
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace teleop::twin

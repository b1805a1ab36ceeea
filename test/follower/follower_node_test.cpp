#include "teleop/follower/follower_node.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <thread>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::follower {
namespace {

constexpr size_t kJoints = 7;

FollowerConfig config() {
  FollowerConfig c;
  c.joints = kJoints;
  c.model.joints = kJoints;
  c.limits.q_min_rad.fill(-2.8);
  c.limits.q_max_rad.fill(2.8);
  c.command_timeout_s = 0.05;
  return c;
}

// the leader's side of the follower's topics
struct LeaderPeer {
  transport::Publication<msg::JointCommand> command;
  transport::Subscription<msg::JointState> state;
  explicit LeaderPeer(transport::Participant& p)
      : command(p, transport::topics::kLeaderCommand, "leader"), state(p, transport::topics::kFollowerState) {
    auto& c = command.sample();
    c.mode().assign(kJoints, msg::CONTROL_JOINT_IMPEDANCE);
    transport::presize(kJoints, c.q_des_rad(), c.dq_des_radps(), c.tau_ff_nm());
    c.stiffness_nm_per_rad().assign(kJoints, 300.0);
    c.damping_nms_per_rad().assign(kJoints, 20.0);
  }
  void command_position(double q) {
    std::fill(command.sample().q_des_rad().begin(), command.sample().q_des_rad().end(), q);
    ASSERT_TRUE(command.publish());
  }
};

class FollowerNodeTest : public ::testing::Test {
 protected:
  test::NodeHarness harness{"follower"};
  FollowerNode node{config(), harness.context};
  LeaderPeer leader{harness.peer};

  void SetUp() override {
    ASSERT_TRUE(test::eventually([&] { return leader.command.matched() > 0 && leader.state.reader().matched() > 0; }));
  }

  // one leader command and one follower cycle, about 1 ms apart
  void step(double q_cmd, bool send = true) {
    if (send) leader.command_position(q_cmd);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
  }

  double counter(const std::string& name) const {
    runtime::NodeReport r;
    node.fill_report(r);
    for (const auto& [n, v] : r.counters) {
      if (n == name) return v;
    }
    return -1;
  }
};

TEST_F(FollowerNodeTest, TracksACommandedPositionAndReportsRunning) {
  for (int i = 0; i < 1500; ++i) step(0.3);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
  ASSERT_TRUE(test::eventually([&] {
    leader.state.poll();
    return leader.state.has_sample();
  }));
  for (size_t j = 0; j < kJoints; ++j) EXPECT_NEAR(leader.state.latest().q_rad()[j], 0.3, 0.01) << "joint " << j;
}

TEST_F(FollowerNodeTest, HoldsItsPoseWhenCommandsStop) {
  for (int i = 0; i < 300; ++i) step(0.2);
  ASSERT_EQ(node.state(), msg::STATE_RUNNING);
  for (int i = 0; i < 300; ++i) step(0.0, /*send=*/false);
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  EXPECT_EQ(counter("watchdog_trips"), 1.0);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_NE(std::find(faults.begin(), faults.end(), msg::FAULT_STALE_INPUT), faults.end());
  // commands come back: running again
  for (int i = 0; i < 50; ++i) step(0.2);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
}

TEST_F(FollowerNodeTest, IgnoresAndCountsANonFiniteCommand) {
  for (int i = 0; i < 100; ++i) step(0.1);
  leader.command.sample().q_des_rad()[3] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(leader.command.publish());
  ASSERT_TRUE(test::eventually([&] {
    node.cycle(harness.tick());
    return counter("rejected_non_finite") >= 1.0;
  }));
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_NE(std::find(faults.begin(), faults.end(), msg::FAULT_COMMAND_REJECTED), faults.end());
}

TEST_F(FollowerNodeTest, CycleDoesNotAllocate) {
  for (int i = 0; i < 200; ++i) step(0.1);  // warm-up: buffers reach their working size
  uint64_t allocations = 0;
  for (int i = 0; i < 1000; ++i) {
    leader.command_position(0.1 + 1e-4 * i);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    const CycleTick tick = harness.tick();
    test::ScopedAllocationCounter counter;
    node.cycle(tick);
    allocations += counter.count();
  }
  EXPECT_EQ(allocations, 0u);
  runtime::NodeReport r;
  node.fill_report(r);
  EXPECT_GT(r.received.at(0).received, 1000u) << "the cycles processed real commands";
}

}  // namespace
}  // namespace teleop::follower

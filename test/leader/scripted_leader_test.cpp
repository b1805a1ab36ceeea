#include "teleop/leader/scripted_leader.h"

#include <gtest/gtest.h>

#include <cmath>
#include <thread>

#include "allocation_counter.h"
#include "node_harness.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::leader {
namespace {

constexpr size_t kJoints = 7;

ScriptedLeaderConfig config() {
  ScriptedLeaderConfig c;
  c.joints = kJoints;
  c.amplitude_rad.fill(0.3);
  c.frequency_hz = 0.5;
  c.peer_timeout_s = 0.05;
  return c;
}

// the follower's side: reads commands, publishes state
struct FollowerPeer {
  transport::Subscription<msg::JointCommand> command;
  transport::Publication<msg::JointState> state;
  explicit FollowerPeer(transport::Participant& p)
      : command(p, transport::topics::kLeaderCommand), state(p, transport::topics::kFollowerState, "follower") {
    transport::presize_joint_state(state.sample(), kJoints);
  }
};

class ScriptedLeaderTest : public ::testing::Test {
 protected:
  test::NodeHarness harness{"leader"};
  ScriptedLeader node{config(), harness.context};
  FollowerPeer follower{harness.peer};

  void SetUp() override {
    ASSERT_TRUE(test::eventually([&] { return follower.state.matched() > 0 && follower.command.reader().matched() > 0; }));
  }

  void step(bool follower_alive) {
    if (follower_alive) {
      ASSERT_TRUE(follower.state.publish());
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
  }
};

TEST_F(ScriptedLeaderTest, StreamsTheScriptedMotionAsJointImpedanceCommands) {
  for (int i = 0; i < 300; ++i) step(true);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
  ASSERT_TRUE(test::eventually([&] {
    follower.command.poll();
    return follower.command.has_sample() && follower.command.latest().header().seq() >= 300;
  }));
  const auto& cmd = follower.command.latest();
  const double t = static_cast<double>(cmd.header().seq() - 1) * 1e-3;  // cycle index of that sample
  // the amplitude fades in over ramp_s = 1 s (smoothstep)
  const double envelope = t * t * (3 - 2 * t);
  for (size_t j = 0; j < kJoints; ++j) {
    EXPECT_EQ(cmd.mode()[j], msg::CONTROL_JOINT_IMPEDANCE);
    EXPECT_NEAR(cmd.q_des_rad()[j], envelope * 0.3 * std::sin(2 * M_PI * 0.5 * t + 0.4 * static_cast<double>(j)), 1e-9);
  }
}

TEST_F(ScriptedLeaderTest, StartsAtHomeWithoutAStep) {
  step(true);
  ASSERT_TRUE(test::eventually([&] {
    follower.command.poll();
    return follower.command.has_sample();
  }));
  ASSERT_EQ(follower.command.latest().header().seq(), 1u);
  for (double q : follower.command.latest().q_des_rad()) EXPECT_EQ(q, 0.0) << "home, although joints start out of phase";
}

TEST_F(ScriptedLeaderTest, FreezesTheCommandWhenTheFollowerGoesSilent) {
  for (int i = 0; i < 200; ++i) step(true);
  for (int i = 0; i < 200; ++i) step(false);
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_EQ(faults, std::vector<uint32_t>{msg::FAULT_PEER_LOST});
  // the last commands all carry the same, frozen pose with zero velocity
  ASSERT_TRUE(test::eventually([&] {
    follower.command.poll();
    return follower.command.latest().header().seq() >= 400;
  }));
  for (double dq : follower.command.latest().dq_des_radps()) EXPECT_EQ(dq, 0.0);
}

TEST_F(ScriptedLeaderTest, CycleDoesNotAllocate) {
  for (int i = 0; i < 200; ++i) step(true);
  uint64_t allocations = 0;
  for (int i = 0; i < 1000; ++i) {
    ASSERT_TRUE(follower.state.publish());
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    const CycleTick tick = harness.tick();
    test::ScopedAllocationCounter counter;
    node.cycle(tick);
    allocations += counter.count();
  }
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace teleop::leader

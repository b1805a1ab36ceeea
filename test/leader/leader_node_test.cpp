#include "leader_node.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <thread>

#include "allocation_counter.h"
#include "following_peer.h"
#include "node_harness.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::leader {
namespace {

constexpr size_t kJoints = 7;

LeaderConfig config() {
  LeaderConfig c;
  c.joints = kJoints;
  c.motion.joints = kJoints;
  c.motion.amplitude_rad.fill(0.3);
  c.motion.frequency_hz = 0.5;
  c.peer_timeout_s = 0.05;
  return c;
}

// the follower's side of the joint commands
struct FollowerPeer : test::FollowingPeer<msg::JointCommand> {
  explicit FollowerPeer(transport::Participant& p) : FollowingPeer(p, transport::topics::kLeaderCommand, kJoints) {}
};

class LeaderNodeTest : public ::testing::Test {
 protected:
  test::NodeHarness harness{"leader"};
  LeaderNode node{config(), harness.context};
  FollowerPeer follower{harness.peer};

  void SetUp() override {
    ASSERT_TRUE(test::eventually([&] { return follower.state.matched() > 0 && follower.command.reader().matched() > 0; }));
  }

  void step(bool follower_alive) {
    if (follower_alive) {
      ASSERT_TRUE(follower.publish());
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
  }
};

TEST_F(LeaderNodeTest, StreamsTheScriptedMotionAsJointImpedanceCommands) {
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

TEST_F(LeaderNodeTest, StartsAtHomeWithoutAStep) {
  // cycle until the follower hears a command: the first one, unless this loaded machine's
  // discovery let the node's writer match a few cycles after the follower's reader did
  ASSERT_TRUE(test::eventually([&] {
    step(true);
    follower.command.poll();
    return follower.command.has_sample();
  }));
  const auto& cmd = follower.command.latest();
  ASSERT_LE(cmd.header().seq(), 100u) << "the commands flow from the start";
  // home (0) at the first cycle, then fading in over ramp_s = 1 s: never a step, although the
  // joints' sines start out of phase
  const double t = static_cast<double>(cmd.header().seq() - 1) * 1e-3;
  const double envelope = t * t * (3 - 2 * t);
  for (double q : cmd.q_des_rad()) EXPECT_LE(std::abs(q), 0.3 * envelope + 1e-12) << "at cycle " << cmd.header().seq();
}

TEST_F(LeaderNodeTest, FreezesTheCommandWhenTheFollowerGoesSilent) {
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

TEST_F(LeaderNodeTest, IsNotInCommandWhileTheFollowerFollowsAnotherWriterAndRendersNothing) {
  for (int i = 0; i < 200; ++i) step(true);
  ASSERT_EQ(node.state(), msg::STATE_RUNNING);
  // the follower now follows someone else
  auto& flow = follower.status.sample().flows().back();
  for (int i = 0; i < 100; ++i) {
    flow.following("rogue");
    flow.following_writer("");
    ASSERT_TRUE(follower.status.publish());
    ASSERT_TRUE(follower.state.publish());
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
  }
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
  std::vector<uint32_t> faults;
  node.active_faults(faults);
  EXPECT_EQ(faults, std::vector<uint32_t>{msg::FAULT_NOT_IN_COMMAND});
  runtime::NodeReport report;
  node.fill_report(report);
  const auto in_command = std::find_if(report.counters.begin(), report.counters.end(),
                                       [](const auto& c) { return c.first == "in_command"; });
  ASSERT_NE(in_command, report.counters.end());
  EXPECT_EQ(in_command->second, 0.0);
  // the follower follows the leader again: running again
  for (int i = 0; i < 100; ++i) step(true);
  EXPECT_EQ(node.state(), msg::STATE_RUNNING);
}

TEST_F(LeaderNodeTest, CycleDoesNotAllocate) {
  for (int i = 0; i < 200; ++i) step(true);
  uint64_t allocations = 0;
  for (int i = 0; i < 1000; ++i) {
    ASSERT_TRUE(follower.publish());
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

namespace teleop::leader {
namespace {

// Position-position feedback (the follower's joint impedance felt back): the safety case of a
// follower dying in contact.
class FeedbackFadeTest : public ::testing::Test {
 protected:
  static LeaderConfig haptic_config() {
    LeaderConfig c = config();
    c.motion.amplitude_rad.fill(0.0);
    c.teleoperation.architecture = runtime::find_architecture("position_position");
    c.stiffness_nm_per_rad = 200;
    c.feedback.fade_s = 0.1;
    c.feedback.max_rate_nm_per_s = 500;  // 0.5 Nm per cycle
    return c;
  }
  test::NodeHarness harness{"leader"};
  LeaderNode node{haptic_config(), harness.context};
  FollowerPeer follower{harness.peer};

  void SetUp() override {
    ASSERT_TRUE(test::eventually([&] { return follower.state.matched() > 0; }));
  }
  // one cycle; returns the torque the device rendered on joint 1
  double step(bool follower_alive) {
    if (follower_alive) {
      EXPECT_TRUE(follower.publish());
    }
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
    return rendered();
  }
  // what the device rendered this cycle, read from the node: the device's state goes out best-effort, and a
  // sample lost under load would leave a cycle unmeasured
  double rendered() const { return node.rendered_torque()[1]; }
};

TEST_F(FeedbackFadeTest, FadesTheFeedbackToZeroWithoutAStepWhenTheFollowerDiesInContact) {
  // the follower is held 0.04 rad off the command on joint 2 (pushing against something):
  // its joint impedance of 200 Nm/rad, felt back, is 8 Nm
  follower.state.sample().q_rad()[1] = 0.04;
  for (int i = 0; i < 400; ++i) step(true);
  ASSERT_EQ(node.state(), msg::STATE_RUNNING);
  ASSERT_NEAR(rendered(), 8.0, 1e-9) << "the operator feels the contact";
  // the follower dies: no more samples
  double previous = rendered();
  double largest_step = 0.0;
  int cycles_to_zero = -1;
  for (int i = 0; i < 400; ++i) {
    const double now = step(false);
    largest_step = std::max(largest_step, std::abs(now - previous));
    previous = now;
    if (now == 0.0 && cycles_to_zero < 0) cycles_to_zero = i + 1;
  }
  RecordProperty("cycles_to_zero", cycles_to_zero);
  ASSERT_GT(cycles_to_zero, 0) << "faded out";
  // peer_timeout 50 ms (wall time: test cycles are >= 0.5 ms apart, so at most 100 cycles)
  // + fade 100 ms (100 cycles)
  EXPECT_LE(cycles_to_zero, 100 + 100 + 5);
  EXPECT_LE(largest_step, 0.5 + 1e-9) << "never a step above the rate limit";
  EXPECT_EQ(node.state(), msg::STATE_SAFE_HOLD);
}

}  // namespace
}  // namespace teleop::leader

namespace teleop::leader {
namespace {

TEST(LeaderNodeHand, StreamsTheOperatorsHandPlanAsHandCommand) {
  test::NodeHarness harness{"leader"};
  LeaderConfig c = config();
  HandMotors closed{};
  closed.fill(0.6);
  HandMotors limit{};
  limit.fill(1.0);
  c.hand = HandPlan({{0.0, HandMotors{}, HandMotors{}}, {0.2, closed, limit}});
  LeaderNode node{c, harness.context};
  transport::Subscription<msg::HandCommand> hand{harness.peer, transport::topics::kHandCommand};
  ASSERT_TRUE(test::eventually([&] { return hand.reader().matched() > 0; }));
  for (int i = 0; i < 300; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node.cycle(harness.tick());
  }
  // best effort, newest only: the node keeps streaming until a sample from after the plan's end
  // (cycle 200) arrives, so a lost last sample only costs a cycle
  ASSERT_TRUE(test::eventually([&] {
    hand.poll();
    if (hand.has_sample() && hand.latest().header().seq() >= 250) return true;
    node.cycle(harness.tick());
    return false;
  }));
  for (size_t m = 0; m < 9; ++m) {
    EXPECT_NEAR(hand.latest().target_position_rad()[m], 0.6, 1e-12) << m;  // the plan's end, held
    EXPECT_EQ(hand.latest().current_limit_a()[m], 1.0);
  }
  EXPECT_TRUE(hand.latest().enable());
  EXPECT_FALSE(hand.latest().fault_reset());
}

}  // namespace
}  // namespace teleop::leader

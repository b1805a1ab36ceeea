#include "teleop/follower/follower_node.h"
#include "teleop/robot/mujoco_backend.h"

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

// the shipped configuration: the MuJoCo arm in front of the wall, Panda limits
FollowerConfig shipped_config() {
  auto root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/follower.yaml");
  FollowerConfig c = FollowerNode::parse_config(root);
  c.command_timeout_s = 0.05;
  return c;
}

// the hardware, built here so the tests can reach into the simulation (forces, friction)
std::unique_ptr<robot::MujocoHardware> hardware(const FollowerConfig& c, bool friction = true) {
  auto hw = std::make_unique<robot::MujocoHardware>(robot::mujoco_config(*c.hardware));
  if (!friction) {
    mjModel* m = hw->simulation().model();
    for (int i = 0; i < m->nv; ++i) m->dof_frictionloss[i] = 0;
  }
  return hw;
}

// the facing_wall keyframe of scene_wall.xml
const std::array<double, kJoints> kHome{0.0, -0.2438, 0.0, -2.1400, 0.0, 3.4638, 0.78539816339744831};

// the leader's side of the follower's topics
struct LeaderPeer {
  transport::Publication<msg::JointCommand> command;
  transport::Publication<msg::CartesianCommand> cartesian;
  transport::Subscription<msg::JointState> state;
  transport::Subscription<msg::WrenchStamped> wrench;
  explicit LeaderPeer(transport::Participant& p)
      : command(p, transport::topics::kLeaderCommand, "leader"),
        cartesian(p, transport::topics::kLeaderCartesian, "leader"),
        state(p, transport::topics::kFollowerState),
        wrench(p, transport::topics::kFollowerWrench) {
    auto& c = command.sample();
    c.mode().assign(kJoints, msg::CONTROL_JOINT_IMPEDANCE);
    transport::presize(kJoints, c.q_des_rad(), c.dq_des_radps(), c.tau_ff_nm());
    c.stiffness_nm_per_rad().assign(kJoints, 300.0);
    c.damping_nms_per_rad().assign(kJoints, 20.0);
    std::copy(kHome.begin(), kHome.end(), c.q_des_rad().begin());
  }
  // home plus `offset` on every joint but the shoulder (which would push into the wall)
  void command_offset(double offset) {
    auto& q = command.sample().q_des_rad();
    for (size_t j = 0; j < kJoints; ++j) q[j] = kHome[j] + (j == 1 ? 0.0 : offset);
    ASSERT_TRUE(command.publish());
  }
};

class FollowerNodeTest : public ::testing::Test {
 protected:
  FollowerConfig config = shipped_config();
  test::NodeHarness harness{"follower"};
  robot::MujocoHardware* sim = nullptr;  // owned by the node
  std::unique_ptr<FollowerNode> node;
  std::unique_ptr<LeaderPeer> leader;

  void start(bool friction = true) {
    auto hw = hardware(config, friction);
    sim = hw.get();
    node = std::make_unique<FollowerNode>(config, std::move(hw), harness.context);
    leader = std::make_unique<LeaderPeer>(harness.peer);
    ASSERT_TRUE(test::eventually([&] { return leader->command.matched() > 0 && leader->state.reader().matched() > 0; }));
  }
  void SetUp() override { start(); }

  // one leader command and one follower cycle, about 1 ms apart
  void step(double offset, bool send = true) {
    if (send) leader->command_offset(offset);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node->cycle(harness.tick());
  }
  // one follower cycle, the commands taken as they are
  void cycle() {
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node->cycle(harness.tick());
  }

  double counter(const std::string& name) const {
    runtime::NodeReport r;
    node->fill_report(r);
    for (const auto& [n, v] : r.counters) {
      if (n == name) return v;
    }
    ADD_FAILURE() << "no counter " << name;
    return -1;
  }
  bool has_fault(uint32_t code) const {
    std::vector<uint32_t> faults;
    node->active_faults(faults);
    return std::find(faults.begin(), faults.end(), code) != faults.end();
  }
};

TEST_F(FollowerNodeTest, TracksAJointImpedanceCommandAndPublishesItsState) {
  for (int i = 0; i < 1500; ++i) step(0.1);
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
  // gravity is compensated, so only joint friction over K = 300 Nm/rad is left as error
  for (size_t j = 0; j < kJoints; ++j) {
    EXPECT_NEAR(node->arm().q_rad[j], kHome[j] + (j == 1 ? 0.0 : 0.1), 0.01) << "joint " << j;
  }
  ASSERT_TRUE(test::eventually([&] {
    leader->state.poll();
    return leader->state.has_sample() && leader->state.latest().tau_ext_nm().size() == kJoints;
  }));
  EXPECT_LT(counter("tracking_rmse_rad"), 0.05);
  EXPECT_EQ(counter("torque_saturations"), 0.0);
}

TEST_F(FollowerNodeTest, HoldsItsPoseWhenCommandsStopAndResumesWhenTheyReturn) {
  for (int i = 0; i < 500; ++i) step(0.05);
  ASSERT_EQ(node->state(), msg::STATE_RUNNING);
  const robot::ArmState before = node->arm();
  for (int i = 0; i < 300; ++i) step(0.0, /*send=*/false);
  EXPECT_EQ(node->state(), msg::STATE_SAFE_HOLD);
  EXPECT_EQ(counter("watchdog_trips"), 1.0);
  EXPECT_TRUE(has_fault(msg::FAULT_STALE_INPUT));
  // the hold is gravity-compensated joint impedance at the pose where the commands stopped
  for (size_t j = 0; j < kJoints; ++j) EXPECT_NEAR(node->arm().q_rad[j], before.q_rad[j], 0.01) << "joint " << j;
  const double latency_ms = counter("watchdog_latency_max_ms");
  EXPECT_GE(latency_ms, 50.0);
  EXPECT_LT(latency_ms, 50.0 + 20.0) << "trips at the first cycle after the timeout (test cycles are ~1 ms)";
  for (int i = 0; i < 50; ++i) step(0.05);
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
}

// an emergency stop while the arm moves: it comes to rest where its damping stops it (no spring
// pulls it back), follows no command while stopped, however they stream, and joins them after the
// enable without a step
TEST_F(FollowerNodeTest, AnEmergencyStopBringsTheArmToRestAndOnlyAnEnableResumes) {
  for (int i = 0; i < 400; ++i) step(0.3 * i / 400.0);
  ASSERT_EQ(node->state(), msg::STATE_RUNNING);
  node->emergency_stop(true);
  EXPECT_NE(node->state(), msg::STATE_RUNNING);
  EXPECT_TRUE(has_fault(msg::FAULT_EMERGENCY_STOP));
  for (int i = 0; i < 600; ++i) step(0.3);
  const robot::ArmState rest = node->arm();
  for (int i = 0; i < 400; ++i) step(0.3 - 0.3 * i / 400.0);
  EXPECT_NE(node->state(), msg::STATE_RUNNING);
  for (size_t j = 0; j < kJoints; ++j) {
    EXPECT_NEAR(node->arm().q_rad[j], rest.q_rad[j], 2e-3) << "joint " << j << ": stays where it came to rest";
  }
  EXPECT_GT(std::abs(node->arm().q_rad[0] - kHome[0]), 0.1) << "the commands went home, the arm did not follow";
  node->emergency_stop(false);
  for (int i = 0; i < 1500; ++i) step(0.0);
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
  EXPECT_EQ(counter("reflex_trips"), 0.0) << "joined, not stepped to";
  for (size_t j = 0; j < kJoints; ++j) EXPECT_NEAR(node->arm().q_rad[j], kHome[j], 0.01) << "joint " << j;
}

// follower.after_hold: enable: the commands return after a lost link, the arm stays held until a
// deliberate enable, then joins them from the held pose
TEST_F(FollowerNodeTest, WithAfterHoldEnableOnlyAnEnableEndsAHold) {
  config.enable_after_hold = true;
  node.reset();
  start();
  for (int i = 0; i < 500; ++i) step(0.05);
  ASSERT_EQ(node->state(), msg::STATE_RUNNING);
  EXPECT_FALSE(node->enable_requested()) << "nothing to end while running";
  for (int i = 0; i < 300; ++i) step(0.0, /*send=*/false);
  ASSERT_EQ(node->state(), msg::STATE_SAFE_HOLD);
  const robot::ArmState held = node->arm();
  for (int i = 0; i < 500; ++i) step(-0.1);
  EXPECT_EQ(node->state(), msg::STATE_SAFE_HOLD) << "the commands are back, the hold waits for an enable";
  for (size_t j = 0; j < kJoints; ++j) EXPECT_NEAR(node->arm().q_rad[j], held.q_rad[j], 0.01) << "joint " << j;
  EXPECT_TRUE(node->enable_requested());
  EXPECT_FALSE(node->enable_requested()) << "one enable ends one hold";
  for (int i = 0; i < 1500; ++i) step(-0.1);
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
  for (size_t j = 0; j < kJoints; ++j) {
    EXPECT_NEAR(node->arm().q_rad[j], kHome[j] + (j == 1 ? 0.0 : -0.1), 0.01) << "joint " << j << ": joined, then tracked";
  }
  EXPECT_EQ(counter("holds_awaiting_enable"), 1.0);
  EXPECT_EQ(counter("reflex_trips"), 0.0);
}

// the loop stopped for longer than the command timeout (a stopped or starved process): the
// backlog's newest command is far from where the arm is, and is joined, not stepped to
TEST_F(FollowerNodeTest, AStallOfItsOwnLoopIsAHoldAndTheNewestCommandIsJoinedNotSteppedTo) {
  // the loop's deadlines are the test's (1 ms apart, then a 200 ms gap): a loaded test machine
  // that stops this thread adds no stall of its own
  int64_t deadline = monotonic_now_ns();
  const auto cycle_at = [&](int64_t advance_ns, bool send, double offset) {
    if (send) leader->command_offset(offset);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    deadline += advance_ns;
    node->cycle(CycleTick{harness.index++, deadline, deadline});
  };
  for (int i = 0; i < 500; ++i) cycle_at(1'000'000, true, 0.0);
  ASSERT_EQ(node->state(), msg::STATE_RUNNING);
  const robot::ArmState before = node->arm();
  // while the loop stood still for 200 ms, the leader moved on by 0.2 rad on every joint but the shoulder
  cycle_at(200'000'000, true, 0.2);
  EXPECT_EQ(node->state(), msg::STATE_SAFE_HOLD) << "a stall is a hold";
  EXPECT_TRUE(has_fault(msg::FAULT_LOOP_OVERRUN));
  EXPECT_EQ(counter("stall_holds"), 1.0);
  EXPECT_EQ(counter("watchdog_trips"), 0.0);
  // the commands flow again: the arm joins them at the rejoin speed (0.5 rad/s), no step
  double largest_step = 0.0;
  robot::ArmState last = node->arm();
  for (int i = 0; i < 100; ++i) {
    cycle_at(1'000'000, true, 0.2);
    for (size_t j = 0; j < kJoints; ++j) largest_step = std::max(largest_step, std::abs(node->arm().q_rad[j] - last.q_rad[j]));
    last = node->arm();
  }
  EXPECT_EQ(node->state(), msg::STATE_RUNNING);
  EXPECT_LT(largest_step, 0.002) << "0.5 rad/s is 0.5 mrad per cycle; a step would be 0.2 rad";
  EXPECT_LT(std::abs(node->arm().q_rad[0] - before.q_rad[0]), 0.08) << "still on its way after 100 cycles";
}

TEST_F(FollowerNodeTest, ACommandOfTheWrongSizeIsNotInForceAndTheFlowSaysWhy) {
  for (int i = 0; i < 50; ++i) step(0.0);
  leader->command.sample().q_des_rad().resize(6);
  ASSERT_TRUE(leader->command.publish());
  ASSERT_TRUE(test::eventually([&] {
    cycle();
    return counter("rejected_wrong_size") > 0;
  }));
  const auto flows = harness.node_participant.reader_flows();
  const auto flow = std::find_if(flows.begin(), flows.end(), [](const auto& f) { return f.topic == "teleop/leader/joint_command"; });
  ASSERT_NE(flow, flows.end());
  EXPECT_FALSE(flow->status->authority.in_force);
  EXPECT_EQ(flow->status->authority.following.view(), "leader");
  EXPECT_EQ(flow->status->authority.refusal, msg::REFUSAL_INVALID);
  EXPECT_EQ(flow->status->authority.refusal_detail.view(), "rejected_wrong_size");
}

TEST_F(FollowerNodeTest, RejectsAndCountsNonFiniteAndMixedModeCommands) {
  for (int i = 0; i < 100; ++i) step(0.0);
  auto& c = leader->command.sample();
  const auto expect_counted = [&](const char* reason) {
    ASSERT_TRUE(test::eventually([&] {
      node->cycle(harness.tick());
      return counter(reason) >= 1.0;
    })) << reason;
  };
  c.q_des_rad()[3] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(leader->command.publish());
  expect_counted("rejected_non_finite");
  c.q_des_rad()[3] = kHome[3];
  c.mode()[2] = msg::CONTROL_POSITION_PD;
  ASSERT_TRUE(leader->command.publish());
  expect_counted("rejected_mixed_modes");
  EXPECT_TRUE(has_fault(msg::FAULT_COMMAND_REJECTED));
}

TEST_F(FollowerNodeTest, RejectsACommandStampedLongAgo) {
  for (int i = 0; i < 100; ++i) step(0.0);
  // what a replayed or long-delayed command looks like: a newer sequence number, an old stamp
  auto writer = harness.peer.make_writer(transport::topics::kLeaderCommand);
  ASSERT_TRUE(test::eventually([&] { return writer.matched() > 0; }));
  msg::JointCommand old = leader->command.sample();
  uint64_t seq = 1'000'000;
  ASSERT_TRUE(test::eventually([&] {
    // best effort: until the follower's reader has matched this writer too, samples may be lost
    old.header().seq(++seq);
    old.header().stamp_ns(system_now_ns() - 10'000'000'000);
    EXPECT_TRUE(writer.write(old));
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    node->cycle(harness.tick());
    return counter("rejected_stale") >= 1.0;
  }));
  EXPECT_TRUE(has_fault(msg::FAULT_COMMAND_REJECTED));
}

TEST_F(FollowerNodeTest, ClampsAndSaturatesAFarTargetWithoutExceedingAnyJointTorqueLimit) {
  // the limits alone: the reflexes would stop this arm first (ReflexProcess), and the rejoin
  // would approach the far target at its calm speed
  config.reflex.enabled = false;
  config.rejoin_speed_radps = 10.0;
  start();
  auto& c = leader->command.sample();
  c.stiffness_nm_per_rad().assign(kJoints, 1e6);  // above max_stiffness: clamped
  for (int i = 0; i < 300; ++i) step(5.0);         // beyond the joint ranges: clamped
  EXPECT_GT(counter("clamped_gain"), 0.0);
  EXPECT_GT(counter("clamped_position"), 0.0);
  EXPECT_GT(counter("torque_saturations"), 0.0);
  EXPECT_LE(counter("peak_torque_ratio"), 1.0);
  // the rate limit: no commanded torque step above 1000 Nm/s x 1 ms
  EXPECT_GT(counter("torque_rate_limited"), 0.0);
}

TEST_F(FollowerNodeTest, ASpeedTripBrakesTheArmToAStopAndItStaysThere) {
  // a stiff far command swings the arm past its speed limits; the rejoin would keep it calm
  config.rejoin_speed_radps = 10.0;
  start();
  leader->command.sample().stiffness_nm_per_rad().assign(kJoints, 1e6);
  const mjData* d = sim->simulation().data();
  int cycles = 0;
  for (; cycles < 2000 && counter("reflex_trips") == 0.0; ++cycles) step(1.5);
  ASSERT_EQ(counter("reflex_cause"), 4.0) << "a joint speed tripped the reflex";
  // the brake: within 0.3 s every joint is at rest (the compliant hold alone coasts for seconds)
  for (int i = 0; i < 300; ++i) step(1.5);
  double fastest = 0.0;
  for (size_t j = 0; j < kJoints; ++j) fastest = std::max(fastest, std::abs(d->qvel[j]));
  EXPECT_LT(fastest, 0.02);
  // and it stays where it stopped: no wandering along the null space, no saturated chatter
  std::array<double, kJoints> stopped{};
  std::copy_n(d->qpos, kJoints, stopped.begin());
  for (int i = 0; i < 1000; ++i) step(1.5);
  for (size_t j = 0; j < kJoints; ++j) EXPECT_NEAR(d->qpos[j], stopped[j], 0.01) << "joint " << j;
  EXPECT_EQ(counter("reflex_latched"), 1.0);
}

TEST_F(FollowerNodeTest, SwitchesToCartesianImpedanceWithoutATorqueStepAndReachesTheTarget) {
  for (int i = 0; i < 300; ++i) step(0.0);
  const double rate_limited = counter("torque_rate_limited");
  const Eigen::Vector3d start = node->control().ee_position();
  auto& c = leader->cartesian.sample();
  // 4 cm sideways, along the wall; the flange keeps its orientation
  const mjData* d = sim->simulation().data();
  const int site = mj_name2id(sim->simulation().model(), mjOBJ_SITE, "ee_site");
  Eigen::Matrix3d r;
  for (int i = 0; i < 9; ++i) r(i / 3, i % 3) = d->site_xmat[9 * site + i];
  const Eigen::Quaterniond q(r);
  c.target_pose().position_m().x(start.x());
  c.target_pose().position_m().y(start.y() + 0.04);
  c.target_pose().position_m().z(start.z());
  c.target_pose().orientation().w(q.w());
  c.target_pose().orientation().x(q.x());
  c.target_pose().orientation().y(q.y());
  c.target_pose().orientation().z(q.z());
  c.stiffness_translational_n_per_m().x(2000);
  c.stiffness_translational_n_per_m().y(2000);
  c.stiffness_translational_n_per_m().z(2000);
  c.stiffness_rotational_nm_per_rad().x(50);
  c.stiffness_rotational_nm_per_rad().y(50);
  c.stiffness_rotational_nm_per_rad().z(50);
  c.damping_ratio(1.0);
  c.nullspace_stiffness_nm_per_rad(10);
  for (int i = 0; i < 2000; ++i) {
    ASSERT_TRUE(leader->cartesian.publish());
    cycle();
  }
  EXPECT_EQ(node->control().mode(), msg::CONTROL_CARTESIAN_IMPEDANCE);
  EXPECT_EQ(counter("mode_changes"), 1.0);
  EXPECT_EQ(counter("torque_rate_limited"), rate_limited) << "the blend alone keeps the torque continuous";
  const Eigen::Vector3d target(start.x(), start.y() + 0.04, start.z());
  EXPECT_LT((node->control().ee_position() - target).norm(), 0.005) << "joint friction over K = 2000 N/m leaves millimetres";
}

TEST_F(FollowerNodeTest, PublishesTheObservedFlangeForceAsWrench) {
  node.reset();
  leader.reset();
  start(/*friction=*/false);  // friction would be external torque to the observer, rightly
  for (int i = 0; i < 200; ++i) step(0.0);
  // 15 N pressing down (-z) on the flange, applied in the simulation only
  mjData* d = sim->simulation().data();
  const int body = mj_name2id(sim->simulation().model(), mjOBJ_BODY, "link7");
  ASSERT_GE(body, 0);
  d->xfrc_applied[6 * body + 2] = -15.0;
  for (int i = 0; i < 1500; ++i) step(0.0);
  ASSERT_TRUE(test::eventually([&] {
    leader->wrench.poll();
    return leader->wrench.has_sample() && leader->wrench.latest().header().seq() > 1000;
  }));
  // a pure force at the body's CoM; the wrench is at the site, so compare the force only
  const auto& f = leader->wrench.latest().force_n();
  EXPECT_NEAR(f.z(), -15.0, 0.75) << "within 5 %";
  EXPECT_NEAR(f.x(), 0.0, 0.75);
  EXPECT_NEAR(f.y(), 0.0, 0.75);
}

TEST_F(FollowerNodeTest, CycleDoesNotAllocate) {
  for (int i = 0; i < 200; ++i) step(0.01);  // warm-up: buffers reach their working size
  runtime::NodeReport before;
  node->fill_report(before);
  uint64_t allocations = 0;
  for (int i = 0; i < 1000; ++i) {
    leader->command_offset(0.01 + 1e-5 * i);
    std::this_thread::sleep_for(std::chrono::microseconds(500));
    const CycleTick tick = harness.tick();
    test::ScopedAllocationCounter counter;
    node->cycle(tick);
    allocations += counter.count();
  }
  EXPECT_EQ(allocations, 0u);
  runtime::NodeReport r;
  node->fill_report(r);
  // the measured cycles took commands (how many of the 1000 arrive by then depends on the host's load)
  EXPECT_GT(r.received.at(0).received, before.received.at(0).received) << "the cycles processed real commands";
}

}  // namespace
}  // namespace teleop::follower

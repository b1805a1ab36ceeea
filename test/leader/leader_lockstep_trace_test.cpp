// The leader's side of each architecture, run in lock-step (test/support/lockstep.h): the shipped
// leader.yaml on the simulated haptic arm (it feels the feedback, so the feedback law moves the
// device and shows in the trace) against a scripted follower and twin whose inputs are a function
// of the cycle only. The hashes below were taken before the architectures moved behind their
// registry (issue 29), on the enum-based leader (the nodes of authority 3952579; commit d15c1dc), with
//   build/default/bin/leader_lockstep_trace_test   (or: ctest --test-dir build/default -R LeaderLockstepTrace -V)
// (each run prints its hash): a refactoring that changes one bit of a trace fails here.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "leader_node.h"
#include "lockstep.h"
#include "teleop/common/clock.h"
#include "teleop/runtime/command_authority.h"
#include "teleop/transport/joint_fields.h"

namespace teleop::leader {
namespace {

constexpr size_t kJoints = 7;
constexpr int kCycles = 1500;      // the operator's ramp and half a motion period: contact and release
constexpr size_t kGrantCycle = 4;  // the follower says it follows the leader after this cycle

LeaderConfig config(const std::string& architecture) {
  auto root = ConfigNode::load_file(std::string(TELEOP_SOURCE_DIR) + "/config/nodes/leader.yaml");
  root.apply_override("teleoperation.architecture=" + architecture);
  root.apply_override("leader.device=haptic_arm");
  // a slow cycle on a loaded machine must not count as a lost peer: the trace is the law's alone
  root.apply_override("leader.peer_timeout_ms=10000");
  return parse_leader_config(root);
}

// the follower's and the twin's side, scripted: what they send in cycle k depends on k alone
struct ScriptedPeers {
  test::ScriptedStream<msg::JointState> state;
  test::ScriptedStream<msg::WrenchStamped> wrench;
  test::ScriptedStream<msg::JointTorque> twin_feedback;
  test::ScriptedStream<msg::TdpaEnergy> tdpa;
  transport::Publication<msg::NodeStatus> status;
  test::DeliveryFence fence;

  ScriptedPeers(transport::Participant& peer, transport::Participant& node)
      : state(peer, node, transport::topics::kFollowerState, "follower"),
        wrench(peer, node, transport::topics::kFollowerWrench, "follower"),
        twin_feedback(peer, node, transport::topics::kTwinFeedback, "twin"),
        tdpa(peer, node, transport::topics::kTdpaFollowerToLeader, "follower"),
        status(peer, transport::topics::kNodeStatus, "follower"),
        fence(peer, node) {
    transport::presize_joint_state(state.sample(), kJoints);
    twin_feedback.sample().tau_nm().resize(kJoints);
    tdpa.sample().session(1);
    tdpa.sample().energy_in_j().resize(6);
    tdpa.sample().energy_out_j().resize(6);
  }

  // each stream reaches two readers in the node's participant, the node's and the probe (the TDPA
  // packets: the probe's alone where the architecture has no channel), and the status the node's
  // authority: all matched before the first cycle, or the node might miss one
  bool matched(bool tdpa_channel) const {
    return state.matched() && wrench.matched() && twin_feedback.matched() && tdpa.matched(tdpa_channel ? 2 : 1) &&
           status.matched() >= 1 && fence.matched();
  }

  // a follower swaying about the home pose, pushed on by a varying wall, and a twin's torque
  void publish(size_t k, const JointVector& home) {
    const double t = static_cast<double>(k) * 1e-3;
    auto& st = state.sample();
    for (size_t j = 0; j < kJoints; ++j) {
      st.q_rad()[j] = home[j] + 0.1 * std::sin(2.0 * t + static_cast<double>(j));
      st.dq_radps()[j] = 0.2 * std::cos(2.0 * t + static_cast<double>(j));
    }
    const double f[3] = {6.0 + 4.0 * std::sin(3.0 * t), -1.0 + std::cos(5.0 * t), 0.5 * std::sin(7.0 * t)};
    const double m[3] = {0.1 * std::sin(t), 0.05, -0.02 * std::cos(2.0 * t)};
    transport::set_wrench(wrench.sample(), f, m);
    for (size_t j = 0; j < kJoints; ++j)
      twin_feedback.sample().tau_nm()[j] = 3.0 * std::sin(4.0 * t + static_cast<double>(j));
    for (size_t c = 0; c < 6; ++c) {
      tdpa.sample().energy_in_j()[c] = 2e-4 * static_cast<double>(k) * (1.0 + 0.1 * static_cast<double>(c));
      tdpa.sample().energy_out_j()[c] = 1e-4 * static_cast<double>(k);
    }
    ASSERT_TRUE(state.deliver());
    ASSERT_TRUE(wrench.deliver());
    ASSERT_TRUE(twin_feedback.deliver());
    ASSERT_TRUE(tdpa.deliver());
    ASSERT_TRUE(fence.pass());
  }

  // the taker's word that this writer's commands are in force (runtime/command_authority.h), and
  // the wait until an authority of our own in the node's participant has heard it: the node's
  // has too, before its next cycle (lockstep.h), so the cycle the leader runs from is the same in
  // every run. Another taker on the domain that refuses fails here, not in the hash.
  void grant(const std::string& topic, const WriterId& writer, transport::Participant& node) {
    const std::string writer_hex = writer.hex().data();
    auto& s = status.sample();
    s.role(msg::ROLE_FOLLOWER);
    s.state(msg::STATE_RUNNING);
    s.flows().resize(1);
    s.flows()[0].topic(topic);
    s.flows()[0].awaited(true);
    s.flows()[0].following("leader");
    s.flows()[0].following_writer(writer_hex);
    s.flows()[0].in_force(true);
    ASSERT_TRUE(status.publish());
    ASSERT_TRUE(status.wait_for_acknowledgments(5'000'000'000));
    if (!authority) authority.emplace(node, writer, "leader", topic);
    const bool granted = test::eventually([&] {
      authority->poll(monotonic_now_ns());
      return authority->in_command();
    });
    ASSERT_TRUE(granted) << "not in command: " << runtime::to_string(authority->refusal()) << " from "
                         << authority->taker().view();
    ASSERT_TRUE(fence.pass());
    granted_ns = monotonic_now_ns();
  }
  std::optional<runtime::CommandAuthority> authority;
  int64_t granted_ns = 0;
};

// the hash of the leader's trace over kCycles lock-step cycles of `architecture`
template <typename Command>
uint64_t run(const std::string& architecture, const transport::TopicSpec<Command>& authority_topic) {
  const LeaderConfig c = config(architecture);
  test::NodeHarness harness{"leader"};
  LeaderNode node{c, harness.context};
  ScriptedPeers peers{harness.peer, harness.node_participant};
  transport::Subscription<Command> commands{harness.peer, authority_topic};
  EXPECT_TRUE(test::eventually([&] {
    return peers.matched(architecture == "pfc" || architecture == "pfc_tdpa") && commands.reader().matched() > 0;
  }));
  std::vector<std::string> columns;
  node.trace_columns(columns);
  std::vector<double> row(columns.size());
  // the columns traced since the hashes were taken (issue 34: the operator's clock, the passivity
  // controller's work) are left out, so that the law's columns still compare bit for bit
  test::HashedColumns hashed(columns, {"operator_s", "tdpa_dissipated_j", "tdpa_acting"});
  if (hashed.missing() != 0) {
    ADD_FAILURE() << "the leader no longer traces a column this test leaves out";
    return 0;
  }
  test::TraceHash hash{"leader_" + architecture};
  for (size_t k = 0; k < kCycles; ++k) {
    peers.publish(k, c.home_rad);
    node.cycle(harness.tick());
    node.trace_row(row.data());
    hash.add(hashed.of(row));
    (void)commands.poll();  // the writer, from any of its first samples (best effort: one may be lost)
    if (k == kGrantCycle) {
      // from the cycle after this one the follower follows the leader (said again every half second
      // of the run, long before the authority forgets a silent taker: 3 s)
      if (!commands.has_sample() && !test::eventually([&] { return commands.poll() > 0; })) {
        ADD_FAILURE() << "none of the leader's first " << kGrantCycle + 1 << " commands arrived";
        return 0;
      }
      peers.grant(commands.topic_name(), commands.session().writer(), harness.node_participant);
    } else if (k > kGrantCycle && monotonic_now_ns() - peers.granted_ns > 500'000'000) {
      peers.grant(commands.topic_name(), commands.session().writer(), harness.node_participant);
    }
  }
  EXPECT_EQ(node.state(), msg::STATE_RUNNING) << architecture;
  std::printf("%s: %llu rows, trace hash 0x%016llx\n", architecture.c_str(),
              static_cast<unsigned long long>(hash.rows()), static_cast<unsigned long long>(hash.value()));
  return hash.value();
}

TEST(LeaderLockstepTrace, PositionPosition) {
  EXPECT_EQ(run("position_position", transport::topics::kLeaderCommand), 0x98a5e0f32b12d27full);
}

TEST(LeaderLockstepTrace, Pfc) { EXPECT_EQ(run("pfc", transport::topics::kLeaderCartesian), 0xa8d1c6d00731c227ull); }

TEST(LeaderLockstepTrace, PfcTdpa) {
  EXPECT_EQ(run("pfc_tdpa", transport::topics::kLeaderCartesian), 0x2beb7d3d7ad1d0acull);
}

TEST(LeaderLockstepTrace, Mmt) { EXPECT_EQ(run("mmt", transport::topics::kLeaderState), 0xadb8fdd02397c90aull); }

}  // namespace
}  // namespace teleop::leader

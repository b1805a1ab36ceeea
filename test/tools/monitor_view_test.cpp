// What `teleop monitor` makes of the nodes' statuses.
#include <gtest/gtest.h>

#include <cmath>

#include "teleop/tools/monitor_view.h"

namespace teleop::tools {
namespace {

constexpr int64_t kMs = 1'000'000;

msg::NodeStatus status(const char* node, msg::NodeState state, int64_t mono_ns, uint64_t cycles) {
  msg::NodeStatus s;
  s.header().source(node);
  s.header().stamp_mono_ns(mono_ns);
  s.role(msg::ROLE_FOLLOWER);
  s.state(state);
  s.loop().cycles(cycles);
  s.tdpa_energy_j(std::nan(""));
  return s;
}

TEST(MonitorView, ShowsStateFaultsAndTheLoopRateMeasuredBetweenStatuses) {
  MonitorView view;
  view.update(status("follower", msg::STATE_RUNNING, 0, 1000), 0);
  msg::NodeStatus s = status("follower", msg::STATE_SAFE_HOLD, 1000 * kMs, 1998);
  s.fault_codes({msg::FAULT_STALE_INPUT, msg::FAULT_PEER_LOST});
  view.update(s, 1000 * kMs);
  const std::string line = view.lines(1000 * kMs);
  EXPECT_NE(line.find("node=follower role=follower state=safe_hold faults=stale_input,peer_lost rate_hz=998.0"),
            std::string::npos)
      << line;
  const std::string table = view.table(1000 * kMs, 60);
  EXPECT_NE(table.find("domain 60"), std::string::npos) << table;
  EXPECT_NE(table.find("safe_hold"), std::string::npos) << table;
}

TEST(MonitorView, SaysWhichFlowWaitsForAWriterAndHowMuchAnotherLost) {
  MonitorView view;
  msg::NodeStatus a = status("leader", msg::STATE_STARTING, 0, 0);
  a.flows().resize(3);
  a.flows()[0].topic("teleop/follower/joint_state");
  a.flows()[0].awaited(true);
  a.flows()[0].writers(0);
  a.flows()[0].age_ns(-1);
  a.flows()[1].topic("teleop/twin/feedback_torque");
  a.flows()[1].writers(1);
  a.flows()[1].received(900);
  a.flows()[1].lost(100);
  a.flows()[2].topic("teleop/leader/cartesian_command");  // the node does not need it
  a.flows()[2].awaited(false);
  view.update(a, 0);
  msg::NodeStatus b = a;
  b.header().stamp_mono_ns(1000 * kMs);
  b.flows()[1].received(1890);  // +990 received, +10 lost since the last status: 1 %
  b.flows()[1].lost(110);
  b.flows()[1].age_ns(2 * kMs);
  b.flows()[1].latency_ns(17 * kMs + 500'000);
  view.update(b, 1000 * kMs);
  const std::string table = view.table(1000 * kMs, 0);
  EXPECT_NE(table.find("teleop/follower/joint_state"), std::string::npos) << table;
  EXPECT_NE(table.find("WAITING FOR A WRITER  age never"), std::string::npos) << table;
  EXPECT_NE(table.find("1 writer  age 2.00 ms  latency 17.50 ms  loss 1.0 %"), std::string::npos) << table;
  EXPECT_NE(table.find("teleop/leader/cartesian_command    no writer (optional)"), std::string::npos) << table;
}

TEST(MonitorView, ANodeWhoseStatusStopsIsShownSilent) {
  MonitorView view(2000 * kMs);
  view.update(status("twin", msg::STATE_RUNNING, 0, 0), 0);
  EXPECT_NE(view.lines(1000 * kMs).find("state=running"), std::string::npos);
  EXPECT_NE(view.lines(3500 * kMs).find("state=SILENT 3.5 s (was running)"), std::string::npos)
      << view.lines(3500 * kMs);
  // a node that said it stops is not silent, it is gone on purpose
  view.update(status("twin", msg::STATE_STOPPING, 10, 0), 4000 * kMs);
  EXPECT_NE(view.lines(9000 * kMs).find("state=stopping"), std::string::npos);
}

WriterId writer(uint8_t id) {
  WriterId w;
  w.bytes.fill(id);
  return w;
}

TEST(MonitorView, TwoNodesOfOneNameAreShownAsSuchNotMerged) {
  MonitorView view;
  // two setups on one domain, both with a node called follower: their statuses alternate
  for (int i = 0; i < 4; ++i) {
    view.update(status("follower", msg::STATE_RUNNING, i * 100 * kMs, 100 * i), i * 100 * kMs, writer(i % 2 ? 2 : 1));
  }
  EXPECT_NE(view.lines(400 * kMs).find("state=DUPLICATE NAME (2 nodes)"), std::string::npos) << view.lines(400 * kMs);
}

TEST(MonitorView, ARestartedNodeIsNotADuplicate) {
  MonitorView view;
  view.update(status("follower", msg::STATE_RUNNING, 0, 0), 0, writer(1));
  view.update(status("follower", msg::STATE_RUNNING, 100 * kMs, 100), 100 * kMs, writer(1));
  // killed and started again: a new status writer from now on
  view.update(status("follower", msg::STATE_STARTING, 300 * kMs, 0), 300 * kMs, writer(2));
  view.update(status("follower", msg::STATE_RUNNING, 400 * kMs, 100), 400 * kMs, writer(2));
  EXPECT_NE(view.lines(400 * kMs).find("state=running"), std::string::npos) << view.lines(400 * kMs);
}

TEST(MonitorView, ShowsWhomAFlowFollowsAndWhatItRefuses) {
  MonitorView view;
  msg::NodeStatus s = status("follower", msg::STATE_RUNNING, 0, 0);
  s.flows().resize(1);
  auto& f = s.flows()[0];
  f.topic("teleop/leader/joint_command");
  f.awaited(true);
  f.writers(2);
  f.following("leader");
  f.in_force(true);
  f.refused_other_writer(5123);
  f.refused_source("rogue");
  f.refusal(msg::REFUSAL_OTHER_WRITER);
  view.update(s, 0);
  const std::string table = view.table(0, 1);
  EXPECT_NE(table.find("following leader, refused 5123 (last: rogue other_writer)"), std::string::npos) << table;
  f.in_force(false);
  f.refused_invalid(3);
  f.refused_source("leader");
  f.refusal(msg::REFUSAL_INVALID);
  f.refusal_detail("rejected_wrong_size");
  view.update(s, kMs);
  EXPECT_NE(view.lines(kMs).find("following leader (NOT IN FORCE), refused 5126 (last: leader invalid rejected_wrong_size)"),
            std::string::npos)
      << view.lines(kMs);
}

}  // namespace
}  // namespace teleop::tools

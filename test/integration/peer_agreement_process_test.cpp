// Nodes that disagree on one domain. Of different releases (issue 33): a node hears a status of
// another protocol or message version, stops (its samples would decode as garbage) naming both
// versions, takes no enable while it talks, and resumes on `teleop enable` once it is gone. Of
// different teleoperation architectures (issue 34: a pfc_tdpa leader beside a position_position
// follower ran "fine" with passivity on one side only): both stop, naming both architectures.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <string>
#include <thread>
#include <vector>

#include "process_helpers.h"
#include "report_counter.h"
#include "teleop/common/version.h"
#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/publication.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

// what a node of another release says in its status, every 100 ms while it talks
class OtherRelease {
 public:
  explicit OtherRelease(int domain)
      : participant_(bus_participant(domain, "old_leader")), status_(participant_, transport::topics::kNodeStatus, "old_leader") {
    auto& s = status_.sample();
    s.role(msg::ROLE_LEADER);
    s.state(msg::STATE_RUNNING);
    s.protocol_version(kProtocolVersion + 1);
    s.message_version("0123456789ab");
    s.software_version("9.9.9 (git cafe123)");
  }
  void talk_for(std::chrono::milliseconds duration) {
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
      (void)status_.publish();
      std::this_thread::sleep_for(100ms);
    }
  }
  void talk_until(const std::atomic<bool>& done) {
    while (!done) {
      (void)status_.publish();
      std::this_thread::sleep_for(100ms);
    }
  }

 private:
  transport::Participant participant_;
  transport::Publication<msg::NodeStatus> status_;
};

int enable(int domain) {
  const ProcessResult r = run_process({bin("teleop"), "enable", "--domain", std::to_string(domain), "--timeout", "20"}, 60s);
  return r.exit_status.value_or(-1);
}

TEST(Versions, ANodeOfAnotherReleaseStopsThePairNamingBothVersionsUntilItIsGoneAndAnEnable) {
  ProcessSite site;
  RunningProcess follower(site.args("follower", source("config/nodes/follower.yaml"), "follower"));
  ASSERT_TRUE(follower.wait_for_output("starting", 20s)) << follower.output();
  // the shipped operator, slowly and clear of the wall: where the shipped sine presses the wall,
  // resuming after the stop in another phase of it tripped the follower's contact reflex (a
  // loaded host), and versions are the subject here
  RunningProcess leader(site.args("leader",
                                  config_copy(site.dir, "leader.yaml",
                                              {{"amplitudes_rad: [0.0, 0.2, 0.0, 0.2, 0.0, 0.0, 0.0]",
                                                "amplitudes_rad: [0.0, 0.0, 0.0, 0.0, 0.3, 0.0, 0.3]"},
                                               {"frequency_hz: 0.5", "frequency_hz: 0.1"}}),
                                  "leader"));
  ASSERT_TRUE(leader.wait_for_output("in command (its commands", 60s)) << leader.output() << follower.output();
  OtherRelease other(site.domain);
  other.talk_for(1500ms);
  const std::string ours = "this node protocol " + std::to_string(kProtocolVersion) + ", messages " + message_version();
  const std::string theirs = "'old_leader' speaks protocol " + std::to_string(kProtocolVersion + 1) +
                             ", messages 0123456789ab (teleop 9.9.9 (git cafe123))";
  for (RunningProcess* node : {&follower, &leader}) {
    ASSERT_TRUE(node->wait_for_output("VERSION MISMATCH", 10s)) << node->output();
    EXPECT_NE(node->output().find(theirs), std::string::npos) << node->output();
    EXPECT_NE(node->output().find(ours), std::string::npos) << node->output();
  }
  // while it talks an enable changes nothing (it talks until the enable was acknowledged)
  std::atomic<bool> acknowledged{false};
  std::thread talking([&] { other.talk_until(acknowledged); });
  EXPECT_EQ(enable(site.domain), 0);
  acknowledged = true;
  talking.join();
  // gone (its status older than 3 s), the nodes wait for the deliberate enable
  ASSERT_TRUE(follower.wait_for_output("the node of another version is gone", 10s)) << follower.output();
  follower.run_for(500ms);
  EXPECT_EQ(follower.output().find("enabled after the emergency stop"), std::string::npos) << "not resumed by itself";
  ASSERT_EQ(enable(site.domain), 0);
  ASSERT_TRUE(follower.wait_for_output("enabled after the emergency stop", 10s)) << follower.output();
  ASSERT_TRUE(leader.wait_for_output("enabled after the emergency stop", 10s)) << leader.output();
  leader.run_for(1500ms);
  ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();
  ASSERT_EQ(follower.stop(SIGTERM, 10s), 0) << follower.output();

  const auto f = runtime::read_report(site.report_path("follower"));
  const auto l = runtime::read_report(site.report_path("leader"));
  for (const auto* r : {&f, &l}) {
    EXPECT_EQ(counter(*r, "version_mismatch_stops"), 1.0) << r->name;
    EXPECT_GE(counter(*r, "enables_refused"), 1.0) << r->name;
    EXPECT_EQ(counter(*r, "emergency_stop_enables"), 1.0) << r->name;
    EXPECT_EQ(counter(*r, "emergency_stop_engaged"), 0.0) << r->name;
  }
  EXPECT_EQ(counter(l, "in_command"), 1.0) << "the pair runs again\n" << leader.output() << follower.output();
}

TEST(Architectures, ALeaderAndAFollowerOfDifferentArchitecturesBothStopNamingBoth) {
  ProcessSite site;
  RunningProcess follower(site.args("follower", source("config/nodes/follower.yaml"), "follower"));
  ASSERT_TRUE(follower.wait_for_output("starting", 20s)) << follower.output();
  std::vector<std::string> leader_args = site.args("leader", source("config/nodes/leader.yaml"), "leader");
  leader_args.insert(leader_args.end(), {"--set", "teleoperation.architecture=pfc_tdpa"});
  RunningProcess leader(leader_args);
  ASSERT_TRUE(follower.wait_for_output("ARCHITECTURE MISMATCH", 30s)) << follower.output() << leader.output();
  ASSERT_TRUE(leader.wait_for_output("ARCHITECTURE MISMATCH", 10s)) << leader.output();
  EXPECT_NE(follower.output().find("'leader' plays pfc_tdpa, this node plays position_position"), std::string::npos)
      << follower.output();
  EXPECT_NE(leader.output().find("'follower' plays position_position, this node plays pfc_tdpa"), std::string::npos)
      << leader.output();
  // the leader gone, the follower says so and stays stopped until an enable
  ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();
  ASSERT_TRUE(follower.wait_for_output("the node of another architecture is gone", 10s)) << follower.output();
  ASSERT_EQ(follower.stop(SIGTERM, 10s), 0) << follower.output();

  const auto f = runtime::read_report(site.report_path("follower"));
  const auto l = runtime::read_report(site.report_path("leader"));
  for (const auto* r : {&f, &l}) {
    EXPECT_EQ(counter(*r, "architecture_mismatch_stops"), 1.0) << r->name;
    EXPECT_EQ(counter(*r, "version_mismatch_stops"), 0.0) << r->name;
    EXPECT_EQ(counter(*r, "emergency_stop_engaged"), 1.0) << r->name << ": stopped until an enable";
  }
  EXPECT_EQ(counter(l, "in_command"), 0.0) << leader.output();
}

}  // namespace
}  // namespace teleop::test

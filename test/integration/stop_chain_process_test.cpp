// The stop chain between processes (docs/stop_chain.md): the emergency stop button of the leader's
// device stops the follower, which brakes its robot to a standstill and follows no command, not
// even those of a new leader, until `teleop enable`; the stopped leader renders no force.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <thread>

#include "process_helpers.h"
#include "report_counter.h"
#include "teleop/experiment/trace.h"
#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/subscription.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

constexpr double kPressAtS = 3.0;

struct Site : ProcessSite {
  // the shipped leader, swinging the flange along the wall, not into it
  std::string leader_config = config_copy(dir, "leader.yaml",
                                          {{"amplitudes_rad: [0.0, 0.2, 0.0, 0.2, 0.0, 0.0, 0.0]",
                                            "amplitudes_rad: [0.3, 0.0, 0.0, 0.0, 0.3, 0.0, 0.3]"}});

  // a leader whose operator presses the device's emergency stop (button 0) at kPressAtS
  std::vector<std::string> pressing_leader(const std::string& tag) const {
    std::vector<std::string> argv = args("leader", leader_config, tag);
    argv.insert(argv.end(), {"--set", "leader.buttons={emergency_stop: 0, enable: 1}", "--set",
                             "leader.button_presses=[{button: 0, at_s: " + std::to_string(kPressAtS) + "}]"});
    return argv;
  }
};

// waits until the leader's commands have had their `session`-th writer
bool wait_for_session(transport::Subscription<msg::JointCommand>& commands, uint64_t session, std::chrono::seconds timeout) {
  const auto until = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < until) {
    commands.poll();
    if (commands.session().session() >= session) return true;
    std::this_thread::sleep_for(2ms);
  }
  return false;
}

size_t first_row(const std::vector<double>& column, double value, size_t from = 0) {
  for (size_t i = from; i < column.size(); ++i) {
    if (column[i] == value) return i;
  }
  return column.size();
}

// the flange's largest displacement [m] over the rows [from, to)
double flange_travel(const experiment::Trace& trace, size_t from, size_t to) {
  const auto& x = trace.column("x_x");
  const auto& y = trace.column("x_y");
  const auto& z = trace.column("x_z");
  double travel = 0.0;
  for (size_t i = from; i < to; ++i) {
    travel = std::max(travel, std::hypot(x[i] - x[from], y[i] - y[from], z[i] - z[from]));
  }
  return travel;
}

TEST(StopChain, TheDevicesEmergencyStopHoldsTheFollowerThroughANewLeaderUntilAnEnable) {
  Site site;
  transport::Participant observer(bus_participant(site.domain, "observer"));
  transport::Subscription<msg::JointCommand> commands(observer, transport::topics::kLeaderCommand);
  RunningProcess follower(site.args("follower", source("config/nodes/follower.yaml"), "follower"));
  ASSERT_TRUE(follower.wait_for_output("starting", 20s)) << follower.output();
  {
    RunningProcess leader(site.pressing_leader("leader_a"));
    ASSERT_TRUE(follower.wait_for_output("EMERGENCY STOP from 'leader'", 60s)) << follower.output() << leader.output();
    leader.run_for(1500ms);  // the leader stopped itself too
    ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();
  }
  // a new leader, which never saw the stop, streams: the follower stays stopped
  RunningProcess leader(site.args("leader", site.leader_config, "leader_b"));
  ASSERT_TRUE(wait_for_session(commands, 2, 30s)) << leader.output();
  follower.run_for(1500ms);
  const ProcessResult enable =
      run_process({bin("teleop"), "enable", "--domain", std::to_string(site.domain), "--timeout", "20"}, 60s);
  ASSERT_EQ(enable.exit_status, 0) << enable.output;
  EXPECT_NE(enable.output.find("enable sent to every node and acknowledged"), std::string::npos) << enable.output;
  ASSERT_TRUE(follower.wait_for_output("enabled after the emergency stop by 'teleop_enable'", 20s)) << follower.output();
  follower.run_for(1500ms);
  ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();
  ASSERT_EQ(follower.stop(SIGTERM, 10s), 0) << follower.output();

  const auto report = runtime::read_report(site.report_path("follower"));
  EXPECT_EQ(counter(report, "emergency_stops"), 1.0);
  EXPECT_EQ(counter(report, "emergency_stop_enables"), 1.0);
  EXPECT_EQ(counter(report, "emergency_stop_engaged"), 0.0);
  ::testing::Test::RecordProperty("follower_reaction_max_ms",
                                  std::to_string(counter(report, "emergency_stop_reaction_max_ms")));
  const auto leader_a = runtime::read_report(site.report_path("leader_a"));
  EXPECT_GE(counter(leader_a, "emergency_stops_sent"), 1.0);
  EXPECT_EQ(counter(leader_a, "emergency_stops"), 1.0) << "the leader honours its own button";
  EXPECT_EQ(leader_a.final_state, "fault");
  EXPECT_EQ(runtime::read_report(site.report_path("leader_b")).final_state, "running");

  const experiment::Trace trace = experiment::read_trace(site.trace_path("follower"));
  const auto& stopped = trace.column("emergency_stop");
  const auto& state = trace.column("state");
  const auto& seq = trace.column("cmd_seq");
  const size_t engaged = first_row(stopped, 1.0);
  ASSERT_LT(engaged, stopped.size());
  const size_t enabled = first_row(stopped, 0.0, engaged);
  ASSERT_LT(enabled, stopped.size());
  // stopped: never running, and not one command taken (the sequence in force stays the one before)
  for (size_t i = engaged; i < enabled; ++i) {
    ASSERT_NE(state[i], static_cast<double>(msg::STATE_RUNNING)) << "row " << i;
    ASSERT_EQ(seq[i], seq[engaged - 1]) << "row " << i;
  }
  // braked to a standstill within 0.5 s, where it stays (a drift of the hold under gravity: < 1 mm)
  size_t at_rest = engaged;
  while (at_rest < enabled && trace.t_s[at_rest] < trace.t_s[engaged] + 0.5) ++at_rest;
  ASSERT_LT(at_rest, enabled);
  ::testing::Test::RecordProperty("stopping_distance_mm", std::to_string(flange_travel(trace, engaged, at_rest) * 1e3));
  const double travel = flange_travel(trace, at_rest, enabled);
  EXPECT_LT(travel, 1e-3);
  ::testing::Test::RecordProperty("flange_travel_while_stopped_mm", std::to_string(travel * 1e3));
  // after the enable the new leader's commands are followed
  const auto& session = trace.column("cmd_session");
  const size_t running = first_row(state, static_cast<double>(msg::STATE_RUNNING), enabled);
  ASSERT_LT(running, state.size()) << "the follower runs again after the enable";
  EXPECT_EQ(session[running], 2.0) << "under the new leader";

  // the stopped leader rendered no force once its fade was over (leader.yaml: 200 ms)
  const experiment::Trace a = experiment::read_trace(site.trace_path("leader_a"));
  const size_t a_engaged = first_row(a.column("emergency_stop"), 1.0);
  ASSERT_LT(a_engaged, a.t_s.size());
  double rendered = 0.0;
  for (const auto* tau : a.numbered("tau_fb_")) {
    for (size_t i = a_engaged; i < a.t_s.size(); ++i) {
      if (a.t_s[i] - a.t_s[a_engaged] > 0.3) rendered = std::max(rendered, std::abs((*tau)[i]));
    }
  }
  EXPECT_EQ(rendered, 0.0);
}

// follower.after_hold: enable: a leader killed mid-motion leaves the follower holding, and a new
// leader's commands do not move it until `teleop enable follower`
TEST(StopChain, WithAfterHoldEnableANewLeaderWaitsForAnEnable) {
  Site site;
  transport::Participant observer(bus_participant(site.domain, "observer"));
  transport::Subscription<msg::JointCommand> commands(observer, transport::topics::kLeaderCommand);
  std::vector<std::string> follower_argv = site.args("follower", source("config/nodes/follower.yaml"), "follower");
  follower_argv.insert(follower_argv.end(), {"--set", "follower.after_hold=enable"});
  RunningProcess follower(follower_argv);
  ASSERT_TRUE(follower.wait_for_output("starting", 20s)) << follower.output();
  {
    RunningProcess leader(site.args("leader", site.leader_config, "leader_a"));
    ASSERT_TRUE(follower.wait_for_output("starting -> running", 60s)) << follower.output() << leader.output();
    leader.run_for(1s);
    leader.stop(SIGKILL, 10s);
  }
  ASSERT_TRUE(follower.wait_for_output("running -> safe_hold", 10s)) << follower.output();
  RunningProcess leader(site.args("leader", site.leader_config, "leader_b"));
  ASSERT_TRUE(wait_for_session(commands, 2, 30s)) << leader.output();
  follower.run_for(1500ms);
  EXPECT_EQ(follower.output().find("safe_hold -> running"), std::string::npos) << "the hold waits for an enable";
  const ProcessResult enable = run_process(
      {bin("teleop"), "enable", "follower", "--domain", std::to_string(site.domain), "--timeout", "20"}, 60s);
  ASSERT_EQ(enable.exit_status, 0) << enable.output;
  ASSERT_TRUE(follower.wait_for_output("enabled after its hold by 'teleop_enable'", 20s)) << follower.output();
  ASSERT_TRUE(follower.wait_for_output("safe_hold -> running", 20s)) << follower.output();
  ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();
  ASSERT_EQ(follower.stop(SIGTERM, 10s), 0) << follower.output();
  const auto report = runtime::read_report(site.report_path("follower"));
  EXPECT_EQ(counter(report, "holds_awaiting_enable"), 2.0) << "the killed leader's, and the second's at the end";
  EXPECT_EQ(counter(report, "hold_enables"), 1.0);
  EXPECT_EQ(counter(report, "emergency_stops"), 0.0);
}

TEST(StopChain, AnEstopNobodyHearsFailsWithAMessage) {
  const ProcessResult r = run_process({bin("teleop"), "estop", "--domain", std::to_string(unique_domain()), "--timeout", "0.5"}, 30s);
  EXPECT_EQ(r.exit_status, 1) << r.output;
  EXPECT_NE(r.output.find("no reader of teleop/emergency_stop acknowledged the emergency stop"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace teleop::test

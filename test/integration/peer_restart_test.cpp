// Peers that die and come back, as a lab meets them (issue 16): a leader killed with SIGKILL and
// started again is followed from its first command, five times in one run; the leader sees a
// restarted follower the same way; a forged command with the largest sequence number, from a
// writer of its own, changes nothing for the leader the follower follows.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <limits>
#include <thread>

#include "process_helpers.h"
#include "report_counter.h"
#include "teleop/common/clock.h"
#include "teleop/experiment/trace.h"
#include "teleop/runtime/node_report.h"
#include "teleop/transport/participant.h"
#include "teleop/transport/subscription.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

constexpr int kRestarts = 5;

struct Site : ProcessSite {
  // the shipped leader, swinging the flange along the wall, not into it
  std::string leader_clear_of_the_wall() const {
    return config_copy(dir, "leader.yaml",
                       {{"amplitudes_rad: [0.0, 0.2, 0.0, 0.2, 0.0, 0.0, 0.0]",
                         "amplitudes_rad: [0.3, 0.0, 0.0, 0.0, 0.3, 0.0, 0.3]"}});
  }
};

// Watches one stream on the bus and tells when a new writer of it has been heard.
template <typename T>
class StreamWatch {
 public:
  StreamWatch(transport::Participant& participant, const transport::TopicSpec<T>& topic) : sub_(participant, topic) {}
  /// Waits until the stream's `session`-th writer has been heard (true) or `timeout` passed.
  bool wait_for_session(uint64_t session, std::chrono::seconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < until) {
      sub_.poll();
      if (sub_.session().session() >= session) return true;
      std::this_thread::sleep_for(2ms);
    }
    return false;
  }

 private:
  transport::Subscription<T> sub_;
};

// What one node says in its NodeStatus of one of its flows: how many samples it has taken.
class FlowReceived {
 public:
  FlowReceived(transport::Participant& participant, std::string node, std::string topic)
      : reader_(participant.make_reader(transport::topics::kNodeStatus)),
        node_(std::move(node)),
        topic_(std::move(topic)) {}
  /// The newest count the node reported (0 before its first status).
  uint64_t poll() {
    while (reader_.take_next(status_)) {
      if (node_ != status_.header().source().c_str()) continue;
      for (const auto& f : status_.flows()) {
        if (topic_ == f.topic().c_str()) received_ = f.received();
      }
    }
    return received_;
  }
  /// Waits until the node has taken more than `count` samples (true) or `timeout` passed.
  bool wait_beyond(uint64_t count, std::chrono::seconds timeout) {
    const auto until = std::chrono::steady_clock::now() + timeout;
    while (poll() <= count) {
      if (std::chrono::steady_clock::now() > until) return false;
      std::this_thread::sleep_for(10ms);
    }
    return true;
  }

 private:
  transport::Reader<msg::NodeStatus> reader_;
  msg::NodeStatus status_;
  std::string node_, topic_;
  uint64_t received_ = 0;
};

// Per session of a peer seen in a node's trace: how long from the first cycle the node had the
// new peer's sample (the session column changes) to the first cycle it ran again (state RUNNING).
struct Rejoin {
  double session = 0;
  double resume_s = INFINITY;
};

std::vector<Rejoin> rejoins(const experiment::Trace& trace, const std::string& session_column) {
  const auto& t = trace.t_s;
  const auto& session = trace.column(session_column);
  const auto& state = trace.column("state");
  std::vector<Rejoin> out;
  for (size_t i = 0; i < t.size(); ++i) {
    if (session[i] < 1 || (i > 0 && session[i] == session[i - 1])) continue;
    Rejoin r{session[i], INFINITY};
    for (size_t k = i; k < t.size() && session[k] == session[i]; ++k) {
      if (state[k] == static_cast<double>(msg::STATE_RUNNING)) {
        r.resume_s = t[k] - t[i];
        break;
      }
    }
    out.push_back(r);
  }
  return out;
}

// Resumed within the peer timeout (100 ms, leader.yaml's): by the new peer's samples, not by any
// timeout. Measured 0-8 ms in both builds; 53.8 ms once in an ASan run on a loaded host (the bound
// was 50 ms then), so the bound is the one that means something, not a rate.
void expect_each_session_resumed(const std::vector<Rejoin>& seen, int sessions, const std::string& who) {
  ASSERT_EQ(static_cast<int>(seen.size()), sessions) << who << ": one session per peer started";
  for (size_t k = 0; k < seen.size(); ++k) {
    EXPECT_EQ(seen[k].session, static_cast<double>(k + 1)) << who << ": sessions count up, none comes back";
    EXPECT_LE(seen[k].resume_s, 0.100) << who << ": session " << seen[k].session;
    ::testing::Test::RecordProperty(who + "_resume_ms_" + std::to_string(k + 1),
                                    std::to_string(seen[k].resume_s * 1e3));
  }
}

TEST(PeerRestart, TheFollowerFollowsEachRestartedLeaderFromItsFirstCommandAndAppliesNoStaleOne) {
  Site site;
  transport::Participant observer(bus_participant(site.domain, "observer"));
  StreamWatch<msg::JointCommand> commands(observer, transport::topics::kLeaderCommand);
  FlowReceived follower_commands(observer, "follower", transport::topics::kLeaderCommand.name);
  RunningProcess follower(site.args("follower", source("config/nodes/follower.yaml"), "follower"));
  ASSERT_TRUE(follower.wait_for_output("starting", 20s)) << follower.output();
  const std::string leader_config = site.leader_clear_of_the_wall();
  for (int run = 1; run <= kRestarts + 1; ++run) {
    const uint64_t taken_before = follower_commands.poll();
    RunningProcess leader(site.args("leader", leader_config, "leader_" + std::to_string(run)));
    ASSERT_TRUE(commands.wait_for_session(static_cast<uint64_t>(run), 30s)) << "leader " << run << leader.output();
    // the follower has this leader's commands too (discovery between the two can take longer than
    // between the leader and this test on a loaded host)
    ASSERT_TRUE(follower_commands.wait_beyond(taken_before + 100, 30s)) << "leader " << run << follower.output();
    follower.run_for(800ms);  // followed for a while, then killed mid-motion
    (void)leader.stop(SIGKILL, 10s);
    follower.run_for(200ms);
  }
  ASSERT_EQ(follower.stop(SIGTERM, 10s), 0) << follower.output();

  const auto report = runtime::read_report(site.report_path("follower"));
  EXPECT_EQ(counter(report, "command_sessions"), kRestarts + 1.0);
  EXPECT_EQ(counter(report, "rejected_old_sequence"), 0.0) << "no leader's commands were measured against another's";
  EXPECT_EQ(report.final_state, "safe_hold") << "the last leader was killed";
  const auto received = std::find_if(report.received.begin(), report.received.end(),
                                     [](const auto& r) { return r.topic == transport::topics::kLeaderCommand.name; });
  ASSERT_NE(received, report.received.end());
  EXPECT_EQ(received->sessions, kRestarts + 1u);
  EXPECT_LE(received->lost, received->expected) << "statistics stay truthful over the sessions";

  const experiment::Trace trace = experiment::read_trace(site.trace_path("follower"));
  expect_each_session_resumed(rejoins(trace, "cmd_session"), kRestarts + 1, "follower");
  // a stale command: one of an earlier leader (a lower session), or an older one of the same
  // leader, in force while running
  const auto& session = trace.column("cmd_session");
  const auto& seq = trace.column("cmd_seq");
  const auto& state = trace.column("state");
  int stale = 0;
  for (size_t i = 1; i < session.size(); ++i) {
    const bool running = state[i] == static_cast<double>(msg::STATE_RUNNING);
    if (running && (session[i] < session[i - 1] || (session[i] == session[i - 1] && seq[i] < seq[i - 1]))) ++stale;
  }
  EXPECT_EQ(stale, 0);
}

TEST(PeerRestart, TheLeaderFollowsEachRestartedFollowerFromItsFirstState) {
  Site site;
  transport::Participant observer(bus_participant(site.domain, "observer"));
  StreamWatch<msg::JointState> states(observer, transport::topics::kFollowerState);
  FlowReceived leader_states(observer, "leader", transport::topics::kFollowerState.name);
  RunningProcess leader(site.args("leader", site.leader_clear_of_the_wall(), "leader"));
  ASSERT_TRUE(leader.wait_for_output("starting", 20s)) << leader.output();
  const std::string follower_config = source("config/nodes/follower.yaml");
  for (int run = 1; run <= kRestarts + 1; ++run) {
    const uint64_t taken_before = leader_states.poll();
    RunningProcess follower(site.args("follower", follower_config, "follower_" + std::to_string(run)));
    ASSERT_TRUE(states.wait_for_session(static_cast<uint64_t>(run), 30s)) << "follower " << run << follower.output();
    ASSERT_TRUE(leader_states.wait_beyond(taken_before + 100, 30s)) << "follower " << run << leader.output();
    leader.run_for(800ms);
    (void)follower.stop(SIGKILL, 10s);
    leader.run_for(300ms);  // beyond the leader's 100 ms peer timeout: it holds
  }
  ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();

  const auto report = runtime::read_report(site.report_path("leader"));
  EXPECT_EQ(report.final_state, "safe_hold") << "the last follower was killed";
  const experiment::Trace trace = experiment::read_trace(site.trace_path("leader"));
  expect_each_session_resumed(rejoins(trace, "peer_session"), kRestarts + 1, "leader");
}

TEST(PeerRestart, AForgedMaximalSequenceNumberChangesNothingForTheLeaderFollowed) {
  Site site;
  transport::Participant observer(bus_participant(site.domain, "observer"));
  StreamWatch<msg::JointCommand> commands(observer, transport::topics::kLeaderCommand);
  RunningProcess follower(site.args("follower", source("config/nodes/follower.yaml"), "follower"));
  RunningProcess leader(site.args("leader", site.leader_clear_of_the_wall(), "leader"));
  ASSERT_TRUE(commands.wait_for_session(1, 30s)) << leader.output();
  follower.run_for(500ms);

  // a writer of its own, on an unsecured domain: a well-formed command to somewhere else, with
  // the largest sequence number, sent for 50 cycles
  transport::Writer<msg::JointCommand> forger = observer.make_writer(transport::topics::kLeaderCommand);
  // matched by the follower (and the watch beside it) before it writes: a sample written before
  // discovery reaches nobody (a slow follower, as under ASan, matched after all 50)
  for (const auto until = std::chrono::steady_clock::now() + 30s;
       forger.matched() < 2 && std::chrono::steady_clock::now() < until;) {
    follower.run_for(10ms);
  }
  ASSERT_GE(forger.matched(), 2) << follower.output();
  msg::JointCommand forged;
  forged.robot("follower");
  forged.mode().assign(7, msg::CONTROL_JOINT_IMPEDANCE);
  forged.q_des_rad({1.0, 0.5, 0.0, -1.5, 0.0, 2.0, 0.0});
  forged.dq_des_radps().assign(7, 0.0);
  forged.tau_ff_nm().assign(7, 0.0);
  forged.stiffness_nm_per_rad().assign(7, 200.0);
  forged.damping_nms_per_rad().assign(7, 10.0);
  forged.header().seq(std::numeric_limits<uint64_t>::max() - 1);
  // a name costs nothing to forge: the session, not the accept list, must refuse it
  forged.header().source("leader");
  for (int i = 0; i < 50; ++i) {
    forged.header().stamp_ns(system_now_ns());
    forged.header().stamp_mono_ns(monotonic_now_ns());
    ASSERT_TRUE(forger.write(forged));
    std::this_thread::sleep_for(1ms);
  }
  follower.run_for(1000ms);
  ASSERT_EQ(follower.stop(SIGTERM, 10s), 0) << follower.output();
  ASSERT_EQ(leader.stop(SIGTERM, 10s), 0) << leader.output();

  const auto report = runtime::read_report(site.report_path("follower"));
  EXPECT_EQ(report.final_state, "running");
  EXPECT_EQ(counter(report, "watchdog_trips"), 0.0) << "the leader's commands were taken throughout";
  EXPECT_EQ(counter(report, "command_sessions"), 1.0);
  EXPECT_EQ(counter(report, "rejected_old_sequence"), 0.0);
  const auto received = std::find_if(report.received.begin(), report.received.end(),
                                     [](const auto& r) { return r.topic == transport::topics::kLeaderCommand.name; });
  ASSERT_NE(received, report.received.end());
  EXPECT_GT(received->refused_other_writer, 0u) << "the forged samples arrived and were refused";
  EXPECT_LE(received->refused_other_writer, 50u);
  EXPECT_LT(received->expected, 1'000'000u) << "statistics stay truthful";
  const experiment::Trace trace = experiment::read_trace(site.trace_path("follower"));
  const auto& session = trace.column("cmd_session");
  EXPECT_EQ(*std::max_element(session.begin(), session.end()), 1.0) << "the forger never took over";
}

}  // namespace
}  // namespace teleop::test

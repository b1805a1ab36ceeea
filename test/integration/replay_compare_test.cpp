// The replay's regression (issue 19): a stiff-wall run of leader and follower is recorded; the
// leader's commands alone, replayed to a fresh follower, move it as the recorded one moved.
#include <gtest/gtest.h>

#include <regex>

#include "teleop/bag/bag_reader.h"
#include "tool_processes.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

// The shipped leader swings shoulder and elbow by 0.2 rad at 0.5 Hz into the wall: at most
// 0.63 rad/s. A replay shifts each command by its timing error (p99 below 6 ms on this loaded VM)
// and the two recordings' receive jitter: 0.63 rad/s x 6 ms = 4 mrad at the fastest point, much
// less on average (0.4 mrad RMSE measured). The bound leaves a loaded host five times that at
// every point; a replay that dropped, reordered or misplaced commands in time would be off by up
// to the swing's 0.2 rad.
constexpr double kRmseBoundRad = 0.02;

TEST(RecordReplay, TheLeadersCommandsReplayedMoveAFreshFollowerAsTheRecordedOneMoved) {
  const std::string dir = make_temp_dir();
  const std::string bag = dir + "/run";
  const int recorded_domain = unique_domain();
  RunningProcess recorder(tool(
      {"record", "-o", bag, "--duration", "9", "--topics", "teleop/leader/joint_command,teleop/follower/joint_state"},
      recorded_domain));
  recorder.run_for(1000ms);  // the recorder is on the bus before the nodes start
  {
    RunningProcess follower(node(dir, "follower", recorded_domain, 7));
    RunningProcess leader(node(dir, "leader", recorded_domain, 6));
    EXPECT_EQ(leader.stop(0, 20s), 0) << leader.output();
    EXPECT_EQ(follower.stop(0, 20s), 0) << follower.output();
  }
  ASSERT_EQ(recorder.stop(0, 20s), 0) << recorder.output();
  EXPECT_NE(recorder.output().find("dropped 0 (queue full)"), std::string::npos) << recorder.output();

  const int replay_domain = unique_domain();
  RunningProcess fresh(node(dir, "follower", replay_domain, 15));
  const ProcessResult replay = run_process(
      tool({"replay", bag, "--topics", "teleop/leader/joint_command", "--compare", "teleop/follower/joint_state"},
           replay_domain),
      40s);
  ASSERT_EQ(replay.exit_status, 0) << replay.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(replay.output, m, std::regex(R"(replayed ([0-9]+) samples)"))) << replay.output;
  uint64_t commands = 0;
  {
    bag::BagReader counting(bag);
    counting.select({counting.topic_id("teleop/leader/joint_command")});
    bag::BagMessage msg;
    while (counting.next(msg)) ++commands;
  }
  EXPECT_GT(commands, 1000u);
  EXPECT_EQ(std::stoull(m[1]), commands) << "every recorded command is published once";
  ASSERT_TRUE(std::regex_search(
      replay.output, m,
      std::regex(R"(compare teleop/follower/joint_state: ([0-9]+) live samples, RMSE ([0-9.]+) rad)")))
      << replay.output;
  EXPECT_GT(std::stoull(m[1]), 1000u) << replay.output;
  EXPECT_LT(std::stod(m[2]), kRmseBoundRad) << replay.output;
}

}  // namespace
}  // namespace teleop::test

// Record and replay (issue 19), with real nodes: a stiff-wall run of leader and follower is
// recorded; the leader's commands alone, replayed to a fresh follower, move it as the recorded one
// moved; a recorder killed with SIGKILL leaves a readable recording that lacks at most its last
// second; a damaged recording is refused with an error that names it.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>

#include "process_helpers.h"
#include "teleop/bag/bag_reader.h"
#include "teleop/common/clock.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

std::vector<std::string> node(const std::string& dir, const std::string& role, int domain, double seconds) {
  return {bin("teleop_" + role), "--config", config_copy(dir, role + ".yaml", {}), "--domain", std::to_string(domain),
          "--duration", std::to_string(seconds)};
}

std::vector<std::string> tool(std::vector<std::string> args, int domain) {
  args.insert(args.begin(), bin("teleop"));
  args.insert(args.end(), {"--domain", std::to_string(domain)});
  return args;
}

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
  RunningProcess recorder(tool({"record", "-o", bag, "--duration", "9", "--topics",
                                "teleop/leader/joint_command,teleop/follower/joint_state"},
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
  const ProcessResult replay = run_process(tool({"replay", bag, "--topics", "teleop/leader/joint_command", "--compare",
                                                 "teleop/follower/joint_state"},
                                                replay_domain),
                                           40s);
  ASSERT_EQ(replay.exit_status, 0) << replay.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(replay.output, m, std::regex(R"(replayed ([0-9]+) samples)"))) << replay.output;
  const bag::BagReader reader(bag);
  uint64_t commands = 0;
  {
    bag::BagReader counting(bag);
    counting.select({counting.topic_id("teleop/leader/joint_command")});
    bag::BagMessage msg;
    while (counting.next(msg)) ++commands;
  }
  EXPECT_GT(commands, 1000u);
  EXPECT_EQ(std::stoull(m[1]), commands) << "every recorded command is published once";
  ASSERT_TRUE(std::regex_search(replay.output, m,
                                std::regex(R"(compare teleop/follower/joint_state: ([0-9]+) live samples, RMSE ([0-9.]+) rad)")))
      << replay.output;
  EXPECT_GT(std::stoull(m[1]), 1000u) << replay.output;
  EXPECT_LT(std::stod(m[2]), kRmseBoundRad) << replay.output;
}

TEST(RecordReplay, ARecorderKilledWithSigkillLeavesAReadableRecordingShortOfAtMostASecond) {
  const std::string dir = make_temp_dir();
  const std::string bag = dir + "/killed";
  const int domain = unique_domain();
  RunningProcess leader(node(dir, "leader", domain, 20));
  RunningProcess recorder(tool({"record", "-o", bag}, domain));
  ASSERT_TRUE(recorder.wait_for_output("recording teleop/leader/joint_command", 15s)) << recorder.output();
  recorder.run_for(3000ms);
  const int64_t killed_ns = system_now_ns();
  recorder.stop(SIGKILL, 5s);
  const bag::BagReader reader(bag);
  ASSERT_GT(reader.message_count(), 1000u);
  EXPECT_GE(reader.end_ns(), killed_ns - 1'000'000'000) << "more than the last second lost";

  // a damaged copy: cut in half
  const std::string cut = dir + "/cut";
  std::filesystem::create_directory(cut);
  std::filesystem::copy_file(bag + "/metadata.yaml", cut + "/metadata.yaml");
  const std::string db = bag + "/killed_0.db3";
  std::filesystem::copy_file(db, cut + "/killed_0.db3");
  std::filesystem::resize_file(cut + "/killed_0.db3", std::filesystem::file_size(db) / 2);
  const ProcessResult replay = run_process(tool({"replay", cut, "--wait-for-readers", "0"}, domain), 20s);
  EXPECT_EQ(replay.exit_status, 1) << replay.output;
  EXPECT_NE(replay.output.find(cut + "/killed_0.db3"), std::string::npos) << replay.output;
}

}  // namespace
}  // namespace teleop::test

// Record and replay (issue 19), with real nodes: a recorder killed with SIGKILL leaves a readable
// recording that lacks at most its last second; a damaged recording is refused with an error that
// names it. The replay's regression is in replay_compare_test.cpp.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <regex>

#include "teleop/bag/bag_reader.h"
#include "teleop/common/clock.h"
#include "tool_processes.h"

namespace teleop::test {
namespace {

using namespace std::chrono_literals;

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

TEST(RecordReplay, AFullDiskEndsTheRecordingWithAClearErrorAndKeepsWhatItHad) {
  const std::string dir = make_temp_dir();
  const std::string bag = dir + "/capped";
  const int domain = unique_domain();
  RunningProcess leader(node(dir, "leader", domain, 30));
  // SQLite reports the cap as it reports a full disk (SQLITE_FULL)
  const ProcessResult record =
      run_process(tool({"record", "-o", bag, "--max-mb", "0.5", "--duration", "25"}, domain), 40s);
  EXPECT_EQ(record.exit_status, 1) << record.output;
  EXPECT_NE(record.output.find("disk full"), std::string::npos) << record.output;
  EXPECT_NE(record.output.find("what was recorded before stays readable in " + bag), std::string::npos)
      << record.output;
  const bag::BagReader reader(bag);
  EXPECT_GT(reader.message_count(), 100u);
}

}  // namespace
}  // namespace teleop::test

// Record and replay (issues 19, 30), with real nodes: a recorder killed with SIGKILL leaves a
// readable recording that lacks at most its last second (a sqlite3 bag; an MCAP file that the
// streaming readers read, ours and the MCAP project's @mcap/core, and after `teleop bag repair`
// the indexed ones); a damaged recording is refused with an error that names it. The replay's
// regression is in replay_compare_test.cpp.
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
  RunningProcess recorder(tool({"record", "-o", bag, "--storage", "sqlite3"}, domain));
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

// the MCAP project's own reader on a file: its JSON line, or its error (exit status != 0)
ProcessResult read_with_mcap_core(const std::string& file, const std::string& mode) {
  // through env: the spawn takes a path, env finds node on PATH
  return run_process({"/usr/bin/env", "TELEOP_NPM_DIR=" TELEOP_NPM_DIR, "node", TELEOP_MCAP_READ_SCRIPT, file, mode,
                      "--min-messages", "1000"},
                     60s);
}

TEST(RecordReplay, AKilledMcapRecordingStreamsAndAfterRepairReadsIndexed) {
  const std::string dir = make_temp_dir();
  const std::string file = dir + "/killed.mcap";
  const int domain = unique_domain();
  RunningProcess leader(node(dir, "leader", domain, 20));
  RunningProcess recorder(tool({"record", "-o", file}, domain));
  ASSERT_TRUE(recorder.wait_for_output("recording teleop/leader/joint_command", 15s)) << recorder.output();
  recorder.run_for(3000ms);
  const int64_t killed_ns = system_now_ns();
  recorder.stop(SIGKILL, 5s);

  uint64_t streamed = 0;
  {
    const bag::BagReader reader(file);
    EXPECT_NE(reader.warning().find("teleop bag repair"), std::string::npos) << reader.warning();
    EXPECT_NE(reader.format().find("streamed"), std::string::npos) << reader.format();
    streamed = reader.message_count();
    ASSERT_GT(streamed, 1000u);
    EXPECT_GE(reader.end_ns(), killed_ns - 1'000'000'000) << "more than the last second lost";
  }
  const ProcessResult core_streamed = read_with_mcap_core(file, "streamed");
  EXPECT_EQ(core_streamed.exit_status, 0) << core_streamed.output;
  const ProcessResult unrepaired = read_with_mcap_core(file, "indexed");
  EXPECT_NE(unrepaired.exit_status, 0) << "an indexed reader needs the summary: " << unrepaired.output;

  const ProcessResult repair = run_process({bin("teleop"), "bag", "repair", file}, 60s);
  ASSERT_EQ(repair.exit_status, 0) << repair.output;
  const bag::BagReader repaired(file);
  EXPECT_EQ(repaired.warning(), "");
  EXPECT_EQ(repaired.format(), "mcap (zstd)");
  EXPECT_EQ(repaired.message_count(), streamed);
  const ProcessResult core_indexed = read_with_mcap_core(file, "indexed");
  EXPECT_EQ(core_indexed.exit_status, 0) << core_indexed.output;
  EXPECT_NE(core_indexed.output.find("\"messages\":" + std::to_string(streamed)), std::string::npos)
      << core_indexed.output;
  const ProcessResult info = run_process({bin("teleop"), "bag", "info", file}, 60s);
  EXPECT_EQ(info.exit_status, 0) << info.output;
  EXPECT_NE(info.output.find("teleop/leader/joint_command (teleop_msgs/msg/JointCommand)"), std::string::npos)
      << info.output;
}

TEST(RecordReplay, AFullDiskEndsTheRecordingWithAClearErrorAndKeepsWhatItHad) {
  const std::string dir = make_temp_dir();
  const std::string bag = dir + "/capped.mcap";
  const int domain = unique_domain();
  RunningProcess leader(node(dir, "leader", domain, 30));
  // the MCAP writer reports the cap as it reports a full disk (ENOSPC), and still writes the summary
  const ProcessResult record =
      run_process(tool({"record", "-o", bag, "--max-mb", "0.5", "--duration", "25"}, domain), 40s);
  EXPECT_EQ(record.exit_status, 1) << record.output;
  EXPECT_NE(record.output.find("disk full"), std::string::npos) << record.output;
  EXPECT_NE(record.output.find("what was recorded before stays readable in " + bag), std::string::npos)
      << record.output;
  const bag::BagReader reader(bag);
  EXPECT_GT(reader.message_count(), 100u);
  EXPECT_EQ(reader.warning(), "");
}

}  // namespace
}  // namespace teleop::test

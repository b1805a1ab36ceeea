#include "teleop/runtime/node_report.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace teleop::runtime {
namespace {

// a fresh temporary directory per test, removed with it
class NodeReportFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("teleop_node_report_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

NodeReport full_report() {
  NodeReport r;
  r.name = "follower_left";
  r.role = "follower";
  r.final_state = "safe_hold";
  r.rate_hz = 1000.0;
  r.run_time_s = 12.345678901234567;
  r.cycles = 12'345'678'901ull;
  r.overruns = 17;
  r.skipped = 3;
  r.lateness_p50_ns = 12'345;
  r.lateness_p99_ns = 98'765;
  r.lateness_max_ns = 1'234'567'890'123ll;
  r.shutdown_ms = 3.0625;
  r.published.push_back({"teleop/follower/joint_state", 12'345'678, 2});
  r.published.push_back({"teleop/follower/wrench", 0, 0});
  ReceivedTopic t;
  t.topic = "teleop/leader/joint_command";
  t.received = 999'000;
  t.expected = 1'000'000;
  t.lost = 1000;
  t.duplicates = 4;
  t.reordered = 5;
  t.first_seq = 7;
  t.last_seq = 1'000'006;
  t.rate_hz = 999.87654321098;
  t.latency_p50_ns = 45'000;
  t.latency_p99_ns = 250'000;
  t.latency_max_ns = 3'000'000;
  t.deadline_missed = 11;
  t.liveliness_lost = 1;
  r.received.push_back(t);
  ReceivedTopic empty;
  empty.topic = "teleop/twin/feedback_torque";
  r.received.push_back(empty);
  r.counters = {{"rejected_non_finite", 3.0}, {"clamped_position", 12.0}, {"watchdog_trips", 0.0},
                {"mean_torque_nm", -0.1234567890123}};
  return r;
}

void expect_equal(const ReceivedTopic& a, const ReceivedTopic& b) {
  EXPECT_EQ(a.topic, b.topic);
  EXPECT_EQ(a.received, b.received) << a.topic;
  EXPECT_EQ(a.expected, b.expected) << a.topic;
  EXPECT_EQ(a.lost, b.lost) << a.topic;
  EXPECT_EQ(a.duplicates, b.duplicates) << a.topic;
  EXPECT_EQ(a.reordered, b.reordered) << a.topic;
  EXPECT_EQ(a.first_seq, b.first_seq) << a.topic;
  EXPECT_EQ(a.last_seq, b.last_seq) << a.topic;
  EXPECT_EQ(a.rate_hz, b.rate_hz) << a.topic;
  EXPECT_EQ(a.latency_p50_ns, b.latency_p50_ns) << a.topic;
  EXPECT_EQ(a.latency_p99_ns, b.latency_p99_ns) << a.topic;
  EXPECT_EQ(a.latency_max_ns, b.latency_max_ns) << a.topic;
  EXPECT_EQ(a.deadline_missed, b.deadline_missed) << a.topic;
  EXPECT_EQ(a.liveliness_lost, b.liveliness_lost) << a.topic;
}

void expect_equal(const NodeReport& a, const NodeReport& b) {
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(a.role, b.role);
  EXPECT_EQ(a.final_state, b.final_state);
  EXPECT_EQ(a.rate_hz, b.rate_hz);
  EXPECT_EQ(a.run_time_s, b.run_time_s);
  EXPECT_EQ(a.cycles, b.cycles);
  EXPECT_EQ(a.overruns, b.overruns);
  EXPECT_EQ(a.skipped, b.skipped);
  EXPECT_EQ(a.lateness_p50_ns, b.lateness_p50_ns);
  EXPECT_EQ(a.lateness_p99_ns, b.lateness_p99_ns);
  EXPECT_EQ(a.lateness_max_ns, b.lateness_max_ns);
  EXPECT_EQ(a.shutdown_ms, b.shutdown_ms);
  ASSERT_EQ(a.published.size(), b.published.size());
  for (size_t i = 0; i < a.published.size(); ++i) {
    EXPECT_EQ(a.published[i].topic, b.published[i].topic);
    EXPECT_EQ(a.published[i].sent, b.published[i].sent);
    EXPECT_EQ(a.published[i].failed, b.published[i].failed);
  }
  ASSERT_EQ(a.received.size(), b.received.size());
  for (size_t i = 0; i < a.received.size(); ++i) expect_equal(a.received[i], b.received[i]);
  EXPECT_EQ(a.counters, b.counters);  // names, values and order
}

TEST_F(NodeReportFile, ReadsBackEveryFieldWhenWrittenAndRead) {
  const NodeReport written = full_report();
  write_report(written, path("report.yaml"));
  const NodeReport read = read_report(path("report.yaml"));
  expect_equal(written, read);
}

TEST_F(NodeReportFile, ReadsBackEmptyListsAndCountersAndUnsignalledShutdown) {
  NodeReport written;
  written.name = "leader";
  written.role = "leader";
  written.final_state = "stopping";
  written.rate_hz = 250.0;
  // shutdown_ms keeps its -1: not signalled
  write_report(written, path("empty.yaml"));
  const NodeReport read = read_report(path("empty.yaml"));
  expect_equal(written, read);
  EXPECT_EQ(read.shutdown_ms, -1.0);
  EXPECT_TRUE(read.published.empty());
  EXPECT_TRUE(read.received.empty());
  EXPECT_TRUE(read.counters.empty());
}

TEST_F(NodeReportFile, ReadsBackNamesThatNeedQuotingInYaml) {
  NodeReport written = full_report();
  written.name = "node: #1";
  written.final_state = "- weird";
  written.counters = {{"with space: and colon", 1.5}, {"true", 2.0}};
  write_report(written, path("quoted.yaml"));
  expect_equal(written, read_report(path("quoted.yaml")));
}

TEST_F(NodeReportFile, ThrowsRuntimeErrorWhenFileCannotBeWritten) {
  EXPECT_THROW(write_report(full_report(), path("no_such_dir/report.yaml")), std::runtime_error);
}

TEST_F(NodeReportFile, ThrowsConfigErrorNamingFileWhenReadingMissingOrBrokenFile) {
  try {
    read_report(path("missing.yaml"));
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), path("missing.yaml") + ": cannot open the file");
  }
  std::ofstream(path("broken.yaml")) << "name: x\nrole: leader\n";  // truncated
  try {
    read_report(path("broken.yaml"));
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), path("broken.yaml") + ":1: final_state: missing required key");
  }
}

TEST(NodeReport, TakesLoopFiguresFromPacerStats) {
  PacerStats stats;
  stats.cycles = 1000;
  stats.overruns = 4;
  stats.skipped = 2;
  for (int i = 1; i <= 100; ++i) stats.lateness.record(i);
  NodeReport r;
  r.add_loop(stats);
  EXPECT_EQ(r.cycles, 1000u);
  EXPECT_EQ(r.overruns, 4u);
  EXPECT_EQ(r.skipped, 2u);
  EXPECT_EQ(r.lateness_p50_ns, stats.lateness.percentile_ns(0.5));
  EXPECT_EQ(r.lateness_p99_ns, stats.lateness.percentile_ns(0.99));
  EXPECT_EQ(r.lateness_max_ns, 100);
}

TEST(NodeReport, TakesStreamFiguresFromSequenceTracker) {
  SequenceTracker t;
  int64_t rx = 1'000'000'000;
  for (uint64_t seq : {5, 6, 8, 8, 7, 10}) {
    t.on_sample(seq, rx - 20'000, rx);
    rx += 1'000'000;
  }
  const ReceivedTopic r = NodeReport::received_from("topic/x", t, DurationHistogram{}, 9, 2);
  EXPECT_EQ(r.topic, "topic/x");
  EXPECT_EQ(r.received, t.received());
  EXPECT_EQ(r.expected, 6u);
  EXPECT_EQ(r.lost, 1u);  // 9
  EXPECT_EQ(r.duplicates, 1u);
  EXPECT_EQ(r.reordered, 1u);
  EXPECT_EQ(r.first_seq, 5u);
  EXPECT_EQ(r.last_seq, 10u);
  EXPECT_EQ(r.rate_hz, t.rate_hz());
  EXPECT_EQ(r.latency_p50_ns, t.latency().percentile_ns(0.5));
  EXPECT_EQ(r.latency_p99_ns, t.latency().percentile_ns(0.99));
  EXPECT_EQ(r.latency_max_ns, 20'000);
  EXPECT_EQ(r.deadline_missed, 9u);
  EXPECT_EQ(r.liveliness_lost, 2u);
}

}  // namespace
}  // namespace teleop::runtime

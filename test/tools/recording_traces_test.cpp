// A recording's joint states as a run's traces (`teleop render` of a recording): one arm's
// columns plain, two arms' prefixed and joined once both were seen, the twin's beside, and a
// recording without the follower's joint states refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "serialized_sample.h"
#include "teleop/bag/mcap_writer.h"
#include "teleop/tools/message_schemas.h"
#include "teleop/tools/recording_traces.h"

namespace teleop::tools {
namespace {

namespace fs = std::filesystem;

constexpr int64_t kStartNs = 1'700'000'000'000'000'000;

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class RecordingTraces : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("teleop_recording_traces_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    writer_ = std::make_unique<bag::McapWriter>(bag::McapWriterOptions{path()});
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path() const { return (dir_ / "r.mcap").string(); }
  int topic(const std::string& name) {
    return writer_->add_topic(recorded_topic(name, type_of<msg::JointState>(), "", RecordingFormat::kMcap));
  }
  void joint_state(int topic, int64_t after_ns, const std::string& arm, std::vector<double> q) {
    msg::JointState s;
    s.arm(arm);
    s.q_rad(std::move(q));
    const std::vector<uint8_t> bytes = serialize(s);
    writer_->write({topic, kStartNs + after_ns, 0, 0, {}, bytes.data(), bytes.size()});
  }

  fs::path dir_;
  std::unique_ptr<bag::McapWriter> writer_;
};

TEST_F(RecordingTraces, OneArmsJointsArePlainColumnsAndTheTwinIsBeside) {
  const int follower = topic("teleop/follower/joint_state");
  const int twin = topic("teleop/twin/joint_state");
  joint_state(follower, 0, "single", {0.5, -1.0});
  joint_state(twin, 1'000'000, "single", {0.25, -0.5});
  joint_state(follower, 2'000'000, "single", {0.75, -1.0});
  writer_->close();
  const auto files = write_recording_traces(path(), (dir_ / "traces").string());
  ASSERT_EQ(files.size(), 2u);
  const auto rows = lines_of(files[0]);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0], "t_s,wall_s,q_0,q_1");
  EXPECT_EQ(rows[1], "0.000000,1700000000.000000,0.5,-1");
  EXPECT_EQ(rows[2], "0.002000,1700000000.002000,0.75,-1");
  EXPECT_EQ(fs::path(files[1]).filename(), "twin.csv");
  EXPECT_EQ(lines_of(files[1])[1], "0.001000,1700000000.001000,0.25,-0.5");
}

TEST_F(RecordingTraces, TwoArmsArePrefixedAndARowWaitsForBoth) {
  const int follower = topic("teleop/follower/joint_state");
  joint_state(follower, 0, "left", {0.1});
  joint_state(follower, 1'000'000, "left", {0.2});
  joint_state(follower, 2'000'000, "right", {-0.1});
  joint_state(follower, 3'000'000, "left", {0.3});
  writer_->close();
  const auto rows = lines_of(write_recording_traces(path(), (dir_ / "traces").string()).at(0));
  ASSERT_EQ(rows.size(), 3u) << "no row before the right arm's first sample";
  EXPECT_EQ(rows[0], "t_s,wall_s,left_q_0,right_q_0");
  EXPECT_EQ(rows[1], "0.002000,1700000000.002000,0.2,-0.1");
  EXPECT_EQ(rows[2], "0.003000,1700000000.003000,0.3,-0.1");
}

TEST_F(RecordingTraces, ARecordingWithoutTheFollowersJointStatesIsRefusedNamingIt) {
  joint_state(topic("teleop/twin/joint_state"), 0, "single", {0.5});
  writer_->close();
  try {
    write_recording_traces(path(), (dir_ / "traces").string());
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path() + ": no teleop/follower/joint_state"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace teleop::tools

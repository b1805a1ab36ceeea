// A recording's topics as CSV files (`teleop bag export`): from MCAP and from sqlite3, fields as
// columns, a sequence that grows, a type without decoder, bytes that decode to nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <memory>

#include "serialized_sample.h"
#include "teleop/bag/bag_writer.h"
#include "teleop/bag/mcap_writer.h"
#include "teleop/tools/message_schemas.h"
#include "teleop/tools/recording_csv.h"

namespace teleop::tools {
namespace {

namespace fs = std::filesystem;

constexpr int64_t kStartNs = 1'700'000'000'000'000'000;

msg::JointState joint_state(uint64_t seq, std::vector<double> q) {
  msg::JointState s;
  s.header().seq(seq);
  s.header().stamp_ns(kStartNs + static_cast<int64_t>(seq) * 1'000'000);
  s.header().source("follower, sim");  // a comma: the cell is quoted
  s.robot("panda");
  s.q_rad(std::move(q));
  return s;
}

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

class RecordingCsv : public ::testing::TestWithParam<RecordingFormat> {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("teleop_recording_csv_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // three joint states (the third with a joint more than the first), a wrench, a topic of a
  // type that is not teleop's, and a joint state whose bytes are cut short
  std::string record() {
    const RecordingFormat format = GetParam();
    const std::string path = (dir_ / (format == RecordingFormat::kMcap ? "run.mcap" : "run")).string();
    std::unique_ptr<bag::RecordingWriter> writer;
    if (format == RecordingFormat::kMcap) {
      writer = std::make_unique<bag::McapWriter>(bag::McapWriterOptions{path});
    } else {
      writer = std::make_unique<bag::BagWriter>(bag::BagWriterOptions{path});
    }
    const int state = writer->add_topic(recorded_topic("teleop/follower/joint_state", type_of<msg::JointState>(), "", format));
    const int wrench = writer->add_topic(recorded_topic("teleop/follower/wrench", type_of<msg::WrenchStamped>(), "", format));
    const int other = writer->add_topic({"/chatter", "std_msgs/msg/String", "", "", ""});
    const auto put = [&](int topic, int64_t recv_ns, const std::vector<uint8_t>& bytes) {
      writer->write({topic, recv_ns, 0, recv_ns - 100, {}, bytes.data(), bytes.size()});
    };
    put(state, kStartNs, serialize(joint_state(1, {0.5, -1.25})));
    put(state, kStartNs + 1'000'000, serialize(joint_state(2, {0.5, -1.0})));
    put(state, kStartNs + 2'000'000, serialize(joint_state(3, {0.25, -1.0, 2.0})));
    msg::WrenchStamped w;
    w.force_n().z(-12.5);
    put(wrench, kStartNs + 1'500'000, serialize(w));
    put(other, kStartNs + 1'600'000, {0, 1, 0, 0, 3, 0, 0, 0, 'h', 'i', 0});
    std::vector<uint8_t> cut = serialize(joint_state(4, {0.0, 0.0}));
    cut.resize(20);
    put(state, kStartNs + 3'000'000, cut);
    writer->close();
    return path;
  }

  fs::path dir_;
};

TEST_P(RecordingCsv, EachTopicIsAFileWithItsFieldsAsColumns) {
  const CsvExport result = export_csv(record(), (dir_ / "csv").string(), {});
  ASSERT_EQ(result.files.size(), 2u);
  const CsvTopicFile& state = result.files[0];
  EXPECT_EQ(state.topic, "teleop/follower/joint_state");
  EXPECT_EQ(fs::path(state.path).filename(), "teleop.follower.joint_state.csv");
  EXPECT_EQ(state.rows, 3u);
  EXPECT_EQ(state.undecodable, 1u) << "the bytes cut short";
  EXPECT_EQ(state.values_left_out, 1u) << "q_rad[2] of the third message";
  const auto lines = lines_of(state.path);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].rfind("t_s,recv_ns,publish_ns,header.seq,header.stamp_ns,header.stamp_mono_ns,header.source,"
                           "robot,arm,q_rad[0],q_rad[1]",
                           0),
            0u)
      << lines[0];
  // MCAP keeps the publish time, sqlite3 has no column for it
  const std::string publish = GetParam() == RecordingFormat::kMcap ? "1699999999999999900" : "0";
  EXPECT_EQ(lines[1].rfind("0.000000000,1700000000000000000," + publish +
                               ",1,1700000000001000000,0,\"follower, sim\",panda,,0.5,-1.25",
                           0),
            0u)
      << lines[1];
  EXPECT_EQ(lines[3].rfind("0.002000000,", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find(",panda,,0.25,-1"), std::string::npos) << lines[3];
  const auto wrench = lines_of(result.files[1].path);
  ASSERT_EQ(wrench.size(), 2u);
  EXPECT_NE(wrench[0].find("force_n.x,force_n.y,force_n.z,torque_nm.x"), std::string::npos) << wrench[0];
  EXPECT_NE(wrench[1].find(",0,0,-12.5,0,0,0"), std::string::npos) << wrench[1];
  ASSERT_EQ(result.skipped.size(), 1u);
  EXPECT_NE(result.skipped[0].find("/chatter: type 'std_msgs/msg/String' is not a teleop type"), std::string::npos)
      << result.skipped[0];
}

TEST_P(RecordingCsv, OnlyTheTopicsAskedFor) {
  const CsvExport result = export_csv(record(), (dir_ / "csv").string(), {"teleop/follower/wrench"});
  ASSERT_EQ(result.files.size(), 1u);
  EXPECT_EQ(result.files[0].rows, 1u);
  EXPECT_FALSE(fs::exists(dir_ / "csv" / "teleop.follower.joint_state.csv"));
}

TEST_P(RecordingCsv, ATopicTheRecordingLacksIsAnErrorNamingThoseItHas) {
  try {
    export_csv(record(), (dir_ / "csv").string(), {"teleop/follower/wrench_typo"});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("no topic 'teleop/follower/wrench_typo'"), std::string::npos) << what;
    EXPECT_NE(what.find("teleop/follower/wrench,"), std::string::npos) << what;
  }
}

INSTANTIATE_TEST_SUITE_P(BothFormats, RecordingCsv, ::testing::Values(RecordingFormat::kMcap, RecordingFormat::kSqlite3),
                         [](const auto& p) { return p.param == RecordingFormat::kMcap ? "Mcap" : "Sqlite3"; });

}  // namespace
}  // namespace teleop::tools

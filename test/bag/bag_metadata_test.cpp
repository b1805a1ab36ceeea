// The bag as rosbag2 (ROS 2 Humble) and the sqlite3 shell see it: metadata.yaml version 5 and
// rosbag2's tables, columns and queries; our extra columns and tables beside them.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>

#include "bag_test_support.h"

namespace teleop::bag {
namespace {

using test::BagDir;
using test::guid;
using test::payload;
using test::query_text;
using test::topic;

constexpr int64_t kT0 = 1'700'000'000'123'456'789LL;
const char* const kQos = "- history: 3\n  depth: 0\n  reliability: 1\n";

// 3 messages on "teleop/a" (with a QoS profile), 1 on "teleop/b", 1 topic without messages
void record_three_topics(const std::string& dir) {
  BagWriter writer({dir});
  writer.add_topic({"teleop/a", "teleop/msg/A", kQos, "", ""});
  writer.add_topic(topic("teleop/b"));
  writer.add_topic(topic("teleop/quiet"));
  const auto data = payload(300, 3);
  for (int64_t dt : {0LL, 5'000'000LL, 2'000'000'000LL})
    writer.write(1, kT0 + dt, dt, guid(1), data.data(), data.size());
  writer.write(2, kT0 + 1'000, 1, guid(2), data.data(), data.size());
  writer.close();
}

YAML::Node bag_info(const std::string& metadata) { return YAML::LoadFile(metadata)["rosbag2_bagfile_information"]; }

TEST(BagMetadata, DescribesTheBagAsRosbag2HumbleReadsIt) {
  BagDir bag;
  record_three_topics(bag.dir());
  const YAML::Node info = bag_info(bag.metadata());
  ASSERT_TRUE(info.IsMap());
  EXPECT_EQ(info["version"].as<int>(), 5);
  EXPECT_EQ(info["storage_identifier"].as<std::string>(), "sqlite3");
  EXPECT_EQ(info["relative_file_paths"].size(), 1u);
  EXPECT_EQ(info["relative_file_paths"][0].as<std::string>(), "run1_0.db3");
  EXPECT_EQ(info["message_count"].as<uint64_t>(), 4u);
  EXPECT_EQ(info["starting_time"]["nanoseconds_since_epoch"].as<int64_t>(), kT0);
  EXPECT_EQ(info["duration"]["nanoseconds"].as<int64_t>(), 2'000'000'000LL);
  EXPECT_EQ(info["compression_format"].as<std::string>(), "");
  EXPECT_EQ(info["compression_mode"].as<std::string>(), "");

  const YAML::Node topics = info["topics_with_message_count"];
  ASSERT_EQ(topics.size(), 3u);
  EXPECT_EQ(topics[0]["topic_metadata"]["name"].as<std::string>(), "teleop/a");
  EXPECT_EQ(topics[0]["topic_metadata"]["type"].as<std::string>(), "teleop/msg/A");
  EXPECT_EQ(topics[0]["topic_metadata"]["serialization_format"].as<std::string>(), "cdr");
  EXPECT_EQ(topics[0]["topic_metadata"]["offered_qos_profiles"].as<std::string>(), kQos);
  EXPECT_EQ(topics[0]["message_count"].as<uint64_t>(), 3u);
  EXPECT_EQ(topics[1]["message_count"].as<uint64_t>(), 1u);
  EXPECT_EQ(topics[2]["topic_metadata"]["offered_qos_profiles"].as<std::string>(), "");
  EXPECT_EQ(topics[2]["message_count"].as<uint64_t>(), 0u);

  // version 5 also lists the files, each with its own times and count
  const YAML::Node files = info["files"];
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0]["path"].as<std::string>(), "run1_0.db3");
  EXPECT_EQ(files[0]["starting_time"]["nanoseconds_since_epoch"].as<int64_t>(), kT0);
  EXPECT_EQ(files[0]["duration"]["nanoseconds"].as<int64_t>(), 2'000'000'000LL);
  EXPECT_EQ(files[0]["message_count"].as<uint64_t>(), 4u);
  EXPECT_FALSE(std::filesystem::exists(bag.metadata() + ".tmp"));
}

TEST(BagMetadata, ExistsFromTheStartAndFollowsItsPeriod) {
  BagDir bag;
  BagWriterOptions options{bag.dir()};
  options.commit_period_ns = 0;
  options.metadata_period_ns = 3'600'000'000'000;  // only flush() rewrites it
  BagWriter writer(options);
  EXPECT_EQ(bag_info(bag.metadata())["message_count"].as<uint64_t>(), 0u);
  writer.add_topic(topic("a"));
  const auto data = payload(10, 1);
  writer.write(1, kT0, 0, guid(1), data.data(), data.size());
  EXPECT_EQ(bag_info(bag.metadata())["message_count"].as<uint64_t>(), 0u);
  writer.flush();
  EXPECT_EQ(bag_info(bag.metadata())["message_count"].as<uint64_t>(), 1u);
}

TEST(BagMetadata, IsRewrittenWithEveryMessageWhenItsPeriodIsZero) {
  BagDir bag;
  BagWriterOptions options{bag.dir()};
  options.commit_period_ns = 3'600'000'000'000;
  options.metadata_period_ns = 0;
  BagWriter writer(options);
  writer.add_topic(topic("a"));
  const auto data = payload(10, 1);
  for (uint64_t i = 1; i <= 3; ++i) {
    writer.write(1, kT0, 0, guid(1), data.data(), data.size());
    EXPECT_EQ(bag_info(bag.metadata())["message_count"].as<uint64_t>(), i);  // committed with it
  }
}

TEST(BagDatabase, HasRosbag2sTablesColumnsAndIndex) {
  BagDir bag;
  record_three_topics(bag.dir());
  const std::string db = bag.db();
  // name, type, NOT NULL and primary key of every column rosbag2 reads
  const auto columns = [&](const std::string& table) {
    return query_text(db,
                      "SELECT group_concat(name || ' ' || type || ' ' || \"notnull\" || ' ' || pk, ', ') "
                      "FROM pragma_table_info('" +
                          table + "')");
  };
  EXPECT_EQ(columns("topics"),
            "id INTEGER 0 1, name TEXT 1 0, type TEXT 1 0, serialization_format TEXT 1 0, "
            "offered_qos_profiles TEXT 1 0");
  EXPECT_EQ(columns("messages"),
            "id INTEGER 0 1, topic_id INTEGER 1 0, timestamp INTEGER 1 0, data BLOB 1 0, "
            "recv_mono_ns INTEGER 0 0, writer_id INTEGER 0 0");
  EXPECT_EQ(columns("writers"), "id INTEGER 0 1, guid BLOB 1 0");
  EXPECT_EQ(columns("teleop_bag"), "format_version INTEGER 1 0");
  EXPECT_EQ(query_text(db,
                       "SELECT tbl_name || '(' || (SELECT group_concat(name) FROM pragma_index_info('timestamp_idx')) "
                       "|| ')' FROM sqlite_master WHERE type = 'index' AND name = 'timestamp_idx'"),
            "messages(timestamp)");
  EXPECT_EQ(query_text(db, "SELECT format_version FROM teleop_bag"), "1");
  EXPECT_EQ(query_text(db, "PRAGMA journal_mode"), "delete");  // closed: one self-contained file
}

TEST(BagDatabase, AnswersRosbag2sOwnQueries) {
  BagDir bag;
  record_three_topics(bag.dir());
  const std::string db = bag.db();
  // its reader: the messages joined with their topic names in time order
  EXPECT_EQ(query_text(db, "SELECT group_concat(name || '@' || (timestamp - " + std::to_string(kT0) +
                               ") || ':' || length(data)) FROM (SELECT data, timestamp, topics.name, messages.id "
                               "FROM messages JOIN topics ON messages.topic_id = topics.id "
                               "ORDER BY messages.timestamp, messages.id)"),
            "teleop/a@0:300,teleop/b@1000:300,teleop/a@5000000:300,teleop/a@2000000000:300");
  // its metadata from the database alone (what `ros2 bag reindex` does)
  EXPECT_EQ(query_text(db,
                       "SELECT group_concat(name || '=' || c) FROM (SELECT name, COUNT(messages.id) AS c, "
                       "MIN(messages.timestamp), MAX(messages.timestamp), offered_qos_profiles FROM messages "
                       "JOIN topics ON topics.id = messages.topic_id GROUP BY topics.name)"),
            "teleop/a=3,teleop/b=1");
  // the sqlite3 shell's `select count(*) from messages`
  EXPECT_EQ(query_text(db, "select count(*) from messages"), "4");
}

TEST(BagDatabase, TakesRosbag2sInsertLeavingOurColumnsEmpty) {
  BagDir bag;
  record_three_topics(bag.dir());
  test::run_sql(bag.db(), "INSERT INTO messages (timestamp, topic_id, data) VALUES (" + std::to_string(kT0 + 1) +
                              ", 2, x'00010000')");
  BagReader reader(bag.dir());
  EXPECT_EQ(reader.message_count(), 5u);
  reader.select({2});
  const auto read = test::read_all(reader);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].recv_ns, kT0 + 1);  // before b's message at kT0 + 1000
  EXPECT_EQ(read[0].recv_mono_ns, 0);
  EXPECT_EQ(read[0].writer, WriterGuid{});
  EXPECT_EQ(read[0].data, (std::vector<uint8_t>{0, 1, 0, 0}));
}

TEST(BagDatabase, KeepsOneWriterRowPerGuid) {
  BagDir bag;
  record_three_topics(bag.dir());
  EXPECT_EQ(query_text(bag.db(), "SELECT COUNT(*) FROM writers"), "2");
  EXPECT_EQ(query_text(bag.db(), "SELECT hex(guid) FROM writers WHERE id = 1"), "0102030405060708090A0B0C0D0E0F10");
}

TEST(BagDatabase, APlainRosbag2BagIsReadWithoutOurColumns) {
  BagDir bag;
  std::filesystem::create_directories(bag.dir());
  // what rosbag2 (Humble) creates, without metadata.yaml
  test::run_sql(bag.db(),
                "CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL, "
                "serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);"
                "CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, "
                "timestamp INTEGER NOT NULL, data BLOB NOT NULL);"
                "CREATE INDEX timestamp_idx ON messages (timestamp ASC);"
                "INSERT INTO topics VALUES (1, '/chatter', 'std_msgs/msg/String', 'cdr', '');"
                "INSERT INTO messages (topic_id, timestamp, data) VALUES (1, 20, x'0001000003000000686900'),"
                "(1, 10, x'00010000')");
  BagReader reader(bag.dir());
  EXPECT_NE(reader.warning().find("not recorded by teleop"), std::string::npos) << reader.warning();
  EXPECT_EQ(reader.topics()[0].type, "std_msgs/msg/String");
  const auto read = test::read_all(reader);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_EQ(read[0].recv_ns, 10);
  EXPECT_EQ(read[1].data.size(), 11u);
  EXPECT_EQ(read[1].recv_mono_ns, 0);
  EXPECT_EQ(read[1].writer, WriterGuid{});
}

}  // namespace
}  // namespace teleop::bag

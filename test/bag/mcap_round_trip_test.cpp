// McapWriter and the MCAP reader behind BagReader: what is written reads back, in time order,
// with its topics, schemas and times, in every compression; the summary's numbers are the file's.
#include <gtest/gtest.h>

#include "mcap_test_support.h"
#include "teleop/bag/bag_reader.h"
#include "teleop/bag/recording_copy.h"

namespace teleop::bag::test {
namespace {

class McapRoundTrip : public ::testing::TestWithParam<McapCompression> {};

TEST_P(McapRoundTrip, EveryMessageReadsBackWithItsTopicTimesAndPayload) {
  BagDir dir;
  const std::string path = dir.parent() + "/run1.mcap";
  record_mcap(path, 200, GetParam());
  BagReader reader(path);
  EXPECT_EQ(reader.warning(), "");
  const char* expected[] = {"mcap (none)", "mcap (zstd)", "mcap (lz4)"};
  EXPECT_EQ(reader.format(), expected[static_cast<int>(GetParam())]);
  ASSERT_EQ(reader.topics().size(), 2u);
  EXPECT_EQ(reader.topic(1).name, "a");
  EXPECT_EQ(reader.topic(1).type, "teleop_msgs/msg/a");
  EXPECT_EQ(reader.topic(1).qos_profile, "- depth: 1\n");
  EXPECT_EQ(reader.topic(1).schema, "int32 x\n");
  EXPECT_EQ(reader.topic(1).schema_encoding, "ros2msg");
  EXPECT_EQ(reader.message_count(), 200u);
  EXPECT_EQ(reader.start_ns(), 1'000'000);
  EXPECT_EQ(reader.end_ns(), 200'000'000);
  const auto all = read_all(reader);
  ASSERT_EQ(all.size(), 200u);
  for (size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(all[i].recv_ns, 1'000'000LL * static_cast<int64_t>(i + 1));
    EXPECT_EQ(all[i].publish_ns, all[i].recv_ns - 10);
    EXPECT_EQ(all[i].topic_id, i % 2 == 0 ? 1 : 2);
    EXPECT_EQ(all[i].data, payload(300, static_cast<uint32_t>(i)));
  }
}

INSTANTIATE_TEST_SUITE_P(Compressions, McapRoundTrip,
                         ::testing::Values(McapCompression::kZstd, McapCompression::kLz4, McapCompression::kNone));

TEST(McapReader, SelectsTopicsAndOrdersByReceiveTimeAcrossChunks) {
  BagDir dir;
  const std::string path = dir.parent() + "/run1.mcap";
  {
    McapWriterOptions options;
    options.path = path;
    options.chunk_bytes = 1;  // a chunk per message: the order comes from the reader
    McapWriter writer(options);
    const int a = writer.add_topic(typed_topic("a"));
    const auto data = payload(8, 0);
    for (const int64_t t : {30, 10, 20}) writer.write({a, t, 0, 0, {}, data.data(), data.size()});
  }
  BagReader reader(path);
  EXPECT_NE(reader.format().find("mcap (zstd)"), std::string::npos);
  const auto all = read_all(reader);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].recv_ns, 10);
  EXPECT_EQ(all[2].recv_ns, 30);
  EXPECT_EQ(all[0].publish_ns, 10) << "an unknown publish time is the log time";
}

TEST(McapReader, ReadsOnlyTheSelectedTopics) {
  BagDir dir;
  const std::string path = dir.parent() + "/run1.mcap";
  record_mcap(path, 50);
  BagReader reader(path);
  reader.select({reader.topic_id("b")});
  const auto all = read_all(reader);
  ASSERT_EQ(all.size(), 25u);
  for (const auto& m : all) EXPECT_EQ(m.topic_id, 2);
}

TEST(McapConvert, SqliteToMcapAndBackKeepsEveryMessage) {
  BagDir dir;
  record_simple(dir.dir(), 40);
  const std::string mcap = dir.parent() + "/converted.mcap";
  {
    BagReader sqlite(dir.dir());
    McapWriter writer({mcap});
    EXPECT_EQ(copy_recording(sqlite, writer), 40u);
  }
  const std::string back = dir.parent() + "/back";
  {
    BagReader from_mcap(mcap);
    BagWriter writer({back});
    EXPECT_EQ(copy_recording(from_mcap, writer), 40u);
  }
  BagReader original(dir.dir());
  BagReader round(back);
  const auto a = read_all(original);
  const auto b = read_all(round);
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].recv_ns, b[i].recv_ns);
    EXPECT_EQ(a[i].data, b[i].data);
  }
  EXPECT_EQ(round.topics()[0].type, original.topics()[0].type);
}

}  // namespace
}  // namespace teleop::bag::test

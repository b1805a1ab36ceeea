// What is written comes back: topics, payloads, receive times on both clocks, writers, in
// receive-time order, filtered by topic.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <numeric>
#include <random>

#include "bag_test_support.h"

namespace teleop::bag {
namespace {

using test::BagDir;
using test::guid;
using test::payload;
using test::read_all;
using test::topic;

struct Written {
  int topic_id;
  int64_t recv_ns;
  uint8_t writer;
  uint32_t seed;
  size_t size;
};

// 600 messages on three topics from four writers, written in shuffled time order
std::vector<Written> shuffled_messages() {
  std::vector<Written> messages;
  for (int i = 0; i < 600; ++i) {
    messages.push_back({1 + i % 3, 1'700'000'000'000'000'000LL + 1'000'000LL * i, static_cast<uint8_t>(10 * (i % 4)),
                        static_cast<uint32_t>(i), static_cast<size_t>(4 + (i * 37) % 500)});
  }
  std::shuffle(messages.begin(), messages.end(), std::mt19937(42));
  return messages;
}

void write_all(BagWriter& writer, const std::vector<Written>& messages) {
  for (const auto& m : messages) {
    const auto data = payload(m.size, m.seed);
    writer.write(m.topic_id, m.recv_ns, m.recv_ns / 3, guid(m.writer), data.data(), data.size());
  }
}

TEST(BagRoundTrip, MessagesComeBackInReceiveTimeOrderWithTheirTopicsWritersAndTimes) {
  BagDir bag;
  auto messages = shuffled_messages();
  {
    BagWriter writer({bag.dir()});
    EXPECT_EQ(writer.add_topic({"teleop/leader/joint_command", "teleop/msg/JointCommand", "- depth: 1\n", "", ""}), 1);
    EXPECT_EQ(writer.add_topic(topic("state")), 2);
    EXPECT_EQ(writer.add_topic(topic("wrench")), 3);
    write_all(writer, messages);
    writer.close();
  }
  BagReader reader(bag.dir());
  EXPECT_EQ(reader.warning(), "");
  ASSERT_EQ(reader.topics().size(), 3u);
  EXPECT_EQ(reader.topics()[0].name, "teleop/leader/joint_command");
  EXPECT_EQ(reader.topics()[0].type, "teleop/msg/JointCommand");
  EXPECT_EQ(reader.topics()[0].qos_profile, "- depth: 1\n");
  EXPECT_EQ(reader.topic(3).name, "wrench");
  EXPECT_EQ(reader.topic_id("state"), 2);
  EXPECT_EQ(reader.topic_id("nope"), -1);
  EXPECT_EQ(reader.message_count(), messages.size());
  EXPECT_EQ(reader.start_ns(), 1'700'000'000'000'000'000LL);
  EXPECT_EQ(reader.end_ns(), 1'700'000'000'000'000'000LL + 599'000'000LL);

  std::sort(messages.begin(), messages.end(), [](const Written& x, const Written& y) { return x.recv_ns < y.recv_ns; });
  const auto read = read_all(reader);
  ASSERT_EQ(read.size(), messages.size());
  for (size_t i = 0; i < read.size(); ++i) {
    EXPECT_EQ(read[i].topic_id, messages[i].topic_id) << i;
    EXPECT_EQ(read[i].recv_ns, messages[i].recv_ns) << i;
    EXPECT_EQ(read[i].recv_mono_ns, messages[i].recv_ns / 3) << i;
    EXPECT_EQ(read[i].writer, guid(messages[i].writer)) << i;
    EXPECT_EQ(read[i].data, payload(messages[i].size, messages[i].seed)) << i;
  }
}

TEST(BagRoundTrip, SelectReadsOnlyTheGivenTopicsAndStartsOver) {
  BagDir bag;
  test::record_simple(bag.dir(), 100);
  BagReader reader(bag.dir());
  reader.select({reader.topic_id("b")});
  const auto b = read_all(reader);
  ASSERT_EQ(b.size(), 50u);
  for (const auto& m : b) EXPECT_EQ(m.topic_id, 2);
  EXPECT_EQ(b.front().recv_ns, 2'000'000);

  reader.select({1, 2});
  EXPECT_EQ(read_all(reader).size(), 100u);
  reader.select({});
  EXPECT_EQ(read_all(reader).size(), 100u);
  BagMessage m;
  EXPECT_FALSE(reader.next(m));  // stays at the end
}

TEST(BagRoundTrip, EqualReceiveTimesKeepTheOrderWritten) {
  BagDir bag;
  {
    BagWriter writer({bag.dir()});
    writer.add_topic(topic("a"));
    for (uint8_t i = 0; i < 20; ++i) {
      const std::vector<uint8_t> data = {0, 1, 0, 0, i};
      writer.write(1, 42, i, guid(i), data.data(), data.size());
    }
  }
  BagReader reader(bag.dir());
  const auto read = read_all(reader);
  ASSERT_EQ(read.size(), 20u);
  for (uint8_t i = 0; i < 20; ++i) EXPECT_EQ(read[i].data.back(), i);
}

TEST(BagRoundTrip, TheSameTopicNameGivesTheSameId) {
  BagDir bag;
  BagWriter writer({bag.dir()});
  EXPECT_EQ(writer.add_topic(topic("a")), 1);
  EXPECT_EQ(writer.add_topic(topic("b")), 2);
  EXPECT_EQ(writer.add_topic(topic("a")), 1);
  writer.close();
  EXPECT_EQ(BagReader(bag.dir()).topics().size(), 2u);
}

TEST(BagRoundTrip, EmptyAndLargePayloadsComeBackWhole) {
  BagDir bag;
  const auto large = payload(2 << 20, 7);
  {
    BagWriter writer({bag.dir()});
    writer.add_topic(topic("a"));
    writer.write(1, 1, 1, guid(1), nullptr, 0);
    writer.write(1, 2, 2, guid(1), large.data(), large.size());
  }
  BagReader reader(bag.dir());
  const auto read = read_all(reader);
  ASSERT_EQ(read.size(), 2u);
  EXPECT_TRUE(read[0].data.empty());
  EXPECT_EQ(read[1].data, large);
}

TEST(BagRoundTrip, StatsCountWhatWasAppendedAndCommitted) {
  BagDir bag;
  BagWriterOptions options{bag.dir()};
  options.commit_period_ns = 0;  // every message its own commit
  BagWriter writer(options);
  writer.add_topic(topic("a"));  // committed at once
  const auto data = payload(300, 1);
  writer.write(1, 200, 0, guid(1), data.data(), data.size());
  writer.write(1, 100, 0, guid(1), data.data(), data.size());
  writer.write(1, 300, 0, guid(2), data.data(), data.size());
  EXPECT_EQ(writer.stats().messages, 3u);
  EXPECT_EQ(writer.stats().bytes, 900u);
  EXPECT_EQ(writer.stats().commits, 4u);
  EXPECT_EQ(writer.stats().first_ns, 100);
  EXPECT_EQ(writer.stats().last_ns, 300);
}

TEST(BagRoundTrip, AClosedBagIsTheDatabaseAndMetadataOnly) {
  BagDir bag;
  test::record_simple(bag.dir(), 10);
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(bag.dir())) files.push_back(entry.path().filename());
  std::sort(files.begin(), files.end());
  EXPECT_EQ(files, (std::vector<std::string>{"metadata.yaml", "run1_0.db3"}));
}

TEST(BagRoundTrip, AReaderSeesWhatALiveRecordingCommitted) {
  BagDir bag;
  BagWriterOptions options{bag.dir()};
  options.commit_period_ns = 3'600'000'000'000;
  BagWriter writer(options);
  writer.add_topic(topic("a"));
  const auto data = payload(300, 1);
  for (int i = 0; i < 10; ++i) writer.write(1, i, i, guid(1), data.data(), data.size());
  writer.flush();
  for (int i = 10; i < 15; ++i) writer.write(1, i, i, guid(1), data.data(), data.size());  // not committed
  BagReader reader(bag.dir());
  EXPECT_EQ(reader.message_count(), 10u);
  EXPECT_NE(reader.warning().find("still going on or was not closed"), std::string::npos) << reader.warning();
  EXPECT_EQ(read_all(reader).size(), 10u);
}

TEST(BagRoundTrip, ABagFolderGivenWithATrailingSlashIsNamedByTheFolder) {
  BagDir bag;
  test::record_simple(bag.dir() + "/", 4);
  EXPECT_TRUE(std::filesystem::exists(bag.db()));
  EXPECT_EQ(BagReader(bag.dir() + "/").message_count(), 4u);
}

TEST(BagRoundTrip, ABagWithoutItsMetadataInARenamedFolderIsFoundByItsOnlyDatabase) {
  BagDir bag;
  test::record_simple(bag.dir(), 6);
  std::filesystem::remove(bag.metadata());
  const std::string renamed = bag.parent() + "/renamed";
  std::filesystem::rename(bag.dir(), renamed);
  BagReader reader(renamed);
  EXPECT_EQ(reader.message_count(), 6u);
  EXPECT_NE(reader.warning().find("metadata.yaml missing"), std::string::npos);
}

}  // namespace
}  // namespace teleop::bag

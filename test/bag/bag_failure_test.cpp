// A full disk and a killed recorder: the writer reports the first, and what was committed before
// either stays readable.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "bag_test_support.h"
#include "test_helpers.h"

namespace teleop::bag {
namespace {

using teleop::test::error_of;
using test::BagDir;
using test::guid;
using test::payload;

constexpr int64_t kHour = 3'600'000'000'000;

// writes `count` 300-byte messages on topic 1, recv_ns continuing from `first`
void write_messages(BagWriter& writer, int first, int count) {
  const auto data = payload(300, 9);
  for (int i = first; i < first + count; ++i)
    writer.write(1, i, i, guid(static_cast<uint8_t>(i % 3)), data.data(), 300);
}

// The cap of max_db_bytes is PRAGMA max_page_count: SQLite answers SQLITE_FULL beyond it, as it
// does on a full disk (no root or tmpfs needed to test it).
TEST(BagFailure, AFullDiskIsReportedAndTheCommittedMessagesStayReadable) {
  BagDir bag;
  BagWriterOptions options{bag.dir()};
  options.commit_period_ns = kHour;
  options.max_db_bytes = 256 * 1024;
  BagWriter writer(options);
  writer.add_topic(test::topic("a"));
  write_messages(writer, 0, 100);
  writer.flush();

  std::string error;
  int written = 0;
  try {
    for (; written < 10'000; ++written) write_messages(writer, 100 + written, 1);
  } catch (const BagError& e) {
    error = e.what();
  }
  EXPECT_NE(error.find(bag.db() + ": appending a message: disk full"), std::string::npos) << error;
  EXPECT_GT(written, 100);  // the cap was reached after some uncommitted messages, which are lost
  EXPECT_EQ(writer.stats().messages, 100u);
  EXPECT_NE(error_of<BagError>([&] { write_messages(writer, 0, 1000); }).find("disk full"), std::string::npos);
  writer.flush();  // nothing pending: works
  writer.close();

  BagReader reader(bag.dir());
  EXPECT_EQ(reader.warning(), "");
  EXPECT_EQ(reader.message_count(), 100u);
  EXPECT_EQ(test::read_all(reader).size(), 100u);
}

TEST(BagFailure, AFullDiskWhileAddingATopicLosesNeitherTheTopicsBeforeNorTheWriter) {
  BagDir bag;
  BagWriterOptions options{bag.dir()};
  options.commit_period_ns = kHour;
  options.max_db_bytes = 64 * 1024;
  BagWriter writer(options);
  writer.add_topic(test::topic("a"));
  const std::string big_qos(128 * 1024, 'q');  // a topic row larger than the cap
  EXPECT_NE(error_of<BagError>([&] {
              writer.add_topic({"b", "teleop/msg/B", big_qos, "", ""});
            }).find("disk full"),
            std::string::npos);
  EXPECT_EQ(writer.add_topic(test::topic("c")), 2);  // b's id was never given out
  write_messages(writer, 0, 3);
  writer.close();
  BagReader reader(bag.dir());
  ASSERT_EQ(reader.topics().size(), 2u);
  EXPECT_EQ(reader.topics()[1].name, "c");
  EXPECT_EQ(reader.message_count(), 3u);
}

// The end of a recorder killed mid-recording: its writer is never closed nor destroyed.
[[noreturn]] void die_by_sigkill() {
  raise(SIGKILL);
  _exit(4);
}

// Runs `record` (which ends in die_by_sigkill()) in a child process.
void record_then_get_killed(const std::function<void()>& record) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    try {
      record();
    } catch (...) {
      _exit(3);
    }
    _exit(5);  // record() did not die
  }
  int status = 0;
  ASSERT_EQ(waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL) << "child status " << status;
}

TEST(BagFailure, AKilledRecorderLosesOnlyItsOpenTransaction) {
  BagDir bag;
  record_then_get_killed([&] {
    BagWriterOptions options{bag.dir()};
    options.commit_period_ns = kHour;
    BagWriter writer(options);
    writer.add_topic(test::topic("a"));
    write_messages(writer, 0, 500);
    writer.flush();
    write_messages(writer, 500, 300);  // never committed
    die_by_sigkill();
  });
  BagReader reader(bag.dir());
  EXPECT_EQ(reader.message_count(), 500u);
  EXPECT_NE(reader.warning().find("was not closed"), std::string::npos) << reader.warning();
  const auto read = test::read_all(reader);
  ASSERT_EQ(read.size(), 500u);
  EXPECT_EQ(read.back().recv_ns, 499);
  EXPECT_EQ(read.back().writer, guid(499 % 3));
}

TEST(BagFailure, AKilledRecorderLeavesStaleMetadataTheReaderNotices) {
  BagDir bag;
  record_then_get_killed([&] {
    BagWriterOptions options{bag.dir()};
    options.commit_period_ns = 0;  // every message committed
    options.metadata_period_ns = kHour;
    BagWriter writer(options);
    writer.add_topic(test::topic("a"));
    write_messages(writer, 0, 200);
    die_by_sigkill();
  });
  BagReader reader(bag.dir());
  EXPECT_EQ(reader.message_count(), 200u);
  EXPECT_NE(reader.warning().find("metadata.yaml is stale (it counts 0 messages, the database 200: the recorder "
                                  "was killed?): read from the database"),
            std::string::npos)
      << reader.warning();
  EXPECT_EQ(test::read_all(reader).size(), 200u);

  std::filesystem::remove(bag.metadata());
  BagReader without_metadata(bag.dir());
  EXPECT_EQ(without_metadata.message_count(), 200u);
  EXPECT_NE(without_metadata.warning().find("metadata.yaml missing (the recorder was killed?): read from the database"),
            std::string::npos)
      << without_metadata.warning();
}

}  // namespace
}  // namespace teleop::bag

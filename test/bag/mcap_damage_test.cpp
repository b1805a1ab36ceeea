// MCAP files as a killed recorder or a bad disk leave them: a file cut anywhere reads up to its
// last complete chunk (streamed, with a warning); `repair_mcap` gives it back its summary; a file
// with any byte damaged reads or is refused with a BagError naming it, never a crash.
#include <gtest/gtest.h>

#include <filesystem>

#include "mcap_test_support.h"
#include "teleop/bag/bag_reader.h"
#include "teleop/bag/recording_copy.h"

namespace teleop::bag::test {
namespace {

// what a reader makes of a file: its messages, or the error's text
struct Outcome {
  uint64_t messages = 0;
  std::string warning;
  std::string error;
};

Outcome read_file(const std::string& path) {
  Outcome outcome;
  try {
    BagReader reader(path);
    outcome.warning = reader.warning();
    outcome.messages = read_all(reader).size();
  } catch (const BagError& e) {
    outcome.error = e.what();
  }
  return outcome;
}

TEST(McapDamage, AFileCutAnywhereReadsItsCompleteChunksOrIsRefusedByName) {
  BagDir dir;
  const std::string whole = dir.parent() + "/whole.mcap";
  record_mcap(whole, 60, McapCompression::kZstd, 2000);  // ~7 messages a chunk
  const auto bytes = file_bytes(whole);
  const std::string cut = dir.parent() + "/cut.mcap";
  uint64_t last = 0;
  for (size_t size = 0; size < bytes.size(); ++size) {
    write_bytes(cut, bytes, size);
    const Outcome o = read_file(cut);
    if (!o.error.empty()) {
      EXPECT_NE(o.error.find(cut), std::string::npos) << o.error;
      EXPECT_LT(size, 8u + 9u) << "only a file without its magic is refused: " << o.error;
      continue;
    }
    EXPECT_GE(o.messages, last) << "a longer cut never reads less, at " << size;
    last = o.messages;
    EXPECT_NE(o.warning, "") << "a cut file says it is cut, at " << size;
  }
  EXPECT_EQ(last, 60u) << "cut only in its summary, every chunk is there";
}

TEST(McapDamage, RepairWritesTheSummaryOfAKilledRecording) {
  BagDir dir;
  const std::string whole = dir.parent() + "/whole.mcap";
  record_mcap(whole, 60, McapCompression::kLz4, 2000);
  const auto bytes = file_bytes(whole);
  BagReader intact(whole);
  const std::string killed = dir.parent() + "/killed.mcap";
  write_bytes(killed, bytes, bytes.size() / 2);  // as SIGKILL leaves it: no summary, a chunk cut
  const Outcome before = read_file(killed);
  ASSERT_EQ(before.error, "");
  EXPECT_NE(before.warning.find("teleop bag repair"), std::string::npos) << before.warning;
  EXPECT_EQ(repair_mcap(killed), before.messages);
  BagReader repaired(killed);
  EXPECT_EQ(repaired.warning(), "");
  EXPECT_EQ(repaired.format(), "mcap (zstd)");
  EXPECT_EQ(repaired.message_count(), before.messages);
  EXPECT_EQ(repaired.topics().size(), 2u);
  EXPECT_EQ(repaired.topic(2).schema, "int32 x\n");
  EXPECT_FALSE(std::filesystem::exists(killed + ".repair"));
}

TEST(McapDamage, AnyDamagedByteReadsOrIsRefusedNeverCrashes) {
  BagDir dir;
  const std::string whole = dir.parent() + "/whole.mcap";
  record_mcap(whole, 12, McapCompression::kZstd, 1500);
  const auto bytes = file_bytes(whole);
  const std::string damaged = dir.parent() + "/damaged.mcap";
  for (size_t at = 0; at < bytes.size(); ++at) {
    for (const uint8_t flip : {0x01, 0x80, 0xFF}) {
      auto copy = bytes;
      copy[at] ^= flip;
      write_bytes(damaged, copy, copy.size());
      const Outcome o = read_file(damaged);
      if (!o.error.empty()) {
        EXPECT_NE(o.error.find(damaged), std::string::npos) << o.error;
      }
    }
  }
}

TEST(McapDamage, NotAnMcapFileIsRefusedByName) {
  BagDir dir;
  const std::string path = dir.parent() + "/notes.txt";
  write_bytes(path, std::vector<uint8_t>(100, 'x'), 100);
  const Outcome o = read_file(path);
  EXPECT_NE(o.error.find(path + ": not a recording"), std::string::npos) << o.error;
  EXPECT_NE(read_file(dir.parent() + "/absent.mcap").error.find("no such file"), std::string::npos);
}

TEST(McapWriterErrors, AnExistingFileIsNeverOverwritten) {
  BagDir dir;
  const std::string path = dir.parent() + "/run1.mcap";
  record_mcap(path, 2);
  try {
    McapWriter writer({path});
    FAIL() << "overwrote";
  } catch (const BagError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": exists already"), std::string::npos) << e.what();
  }
}

TEST(McapWriterErrors, TheSizeCapIsReportedAsAFullDiskAndTheFileStaysReadable) {
  BagDir dir;
  const std::string path = dir.parent() + "/capped.mcap";
  McapWriterOptions options{path};
  options.compression = McapCompression::kNone;
  options.chunk_bytes = 1000;
  options.max_bytes = 20'000;
  std::string error;
  {
    McapWriter writer(options);
    const int a = writer.add_topic(typed_topic("a"));
    const auto data = payload(300, 1);
    try {
      for (int i = 0; i < 1000; ++i) writer.write({a, i + 1, 0, 0, {}, data.data(), data.size()});
    } catch (const BagError& e) {
      error = e.what();
    }
    EXPECT_LT(writer.stats().messages, 1000u);
  }
  EXPECT_NE(error.find("disk full"), std::string::npos) << error;
  BagReader reader(path);
  EXPECT_EQ(reader.warning(), "") << "the summary is written past the cap";
  EXPECT_GT(reader.message_count(), 30u);
}

}  // namespace
}  // namespace teleop::bag::test

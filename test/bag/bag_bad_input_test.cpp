// Every way a bag folder can be wrong gives a BagError naming the file and the problem, never a
// crash; so does every wrong use of the writer.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include "alias_bomb.h"
#include "bag_test_support.h"
#include "test_helpers.h"

namespace teleop::bag {
namespace {

using teleop::test::error_of;
using test::BagDir;

std::string open_error(const std::string& dir) {
  return error_of<BagError>([&] { BagReader reader(dir); });
}

// opening and reading every message: damage may show in either
std::string read_error(const std::string& dir) {
  return error_of<BagError>([&] {
    BagReader reader(dir);
    test::read_all(reader);
  });
}

void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

void overwrite(const std::string& path, std::streamoff offset, size_t size) {
  std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
  file.seekp(offset);
  const std::string junk(size, '\xA5');
  file.write(junk.data(), static_cast<std::streamsize>(junk.size()));
}

void replace_in_file(const std::string& path, const std::string& pattern, const std::string& with) {
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write_text(path, std::regex_replace(text, std::regex(pattern), with));
}

TEST(BagBadInput, AFolderWithoutADatabaseIsNotABag) {
  BagDir bag;
  std::filesystem::create_directories(bag.dir());
  write_text(bag.dir() + "/notes.txt", "hello");
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.dir()), std::string::npos) << error;
  EXPECT_NE(error.find("not a bag"), std::string::npos) << error;
}

TEST(BagBadInput, AMissingFolderOrAFileThatIsNoMcapIsNotARecording) {
  BagDir bag;
  EXPECT_NE(open_error(bag.dir()).find(bag.dir() + ": no such file or folder"), std::string::npos);
  write_text(bag.parent() + "/file", "x");
  EXPECT_NE(open_error(bag.parent() + "/file").find("file: not a recording (an MCAP file starts with"),
            std::string::npos);
}

TEST(BagBadInput, MetadataNamingAMissingDatabase) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  std::filesystem::remove(bag.db());
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.db() + ": missing"), std::string::npos) << error;
}

TEST(BagBadInput, ATruncatedDatabase) {
  BagDir bag;
  test::record_simple(bag.dir(), 2000);
  std::filesystem::resize_file(bag.db(), std::filesystem::file_size(bag.db()) / 2);
  const std::string error = read_error(bag.dir());
  EXPECT_NE(error.find(bag.db()), std::string::npos) << error;
  EXPECT_NE(error.find("corrupt"), std::string::npos) << error;
}

TEST(BagBadInput, ADatabaseOverwrittenInTheMiddle) {
  BagDir bag;
  test::record_simple(bag.dir(), 2000);
  overwrite(bag.db(), static_cast<std::streamoff>(std::filesystem::file_size(bag.db()) / 2 / 4096 * 4096), 4096);
  const std::string error = read_error(bag.dir());
  EXPECT_NE(error.find(bag.db()), std::string::npos) << error;
  EXPECT_NE(error.find("corrupt"), std::string::npos) << error;
}

TEST(BagBadInput, AFileThatIsNotADatabase) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  write_text(bag.db(), std::string(8192, 'x'));
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.db()), std::string::npos) << error;
  EXPECT_NE(error.find("not an SQLite database"), std::string::npos) << error;
}

TEST(BagBadInput, ADatabaseWithoutRosbag2sTables) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  test::run_sql(bag.db(), "DROP TABLE topics");
  EXPECT_NE(open_error(bag.dir()).find(bag.db() + ": no table topics"), std::string::npos);
}

TEST(BagBadInput, MetadataOfANewerRosbag2) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  replace_in_file(bag.metadata(), "version: 5", "version: 9");
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.metadata()), std::string::npos) << error;
  EXPECT_NE(error.find("rosbag2 metadata version 9 is newer than this reads (up to 5)"), std::string::npos) << error;
}

TEST(BagBadInput, MetadataThatIsNotYaml) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  write_text(bag.metadata(), "rosbag2_bagfile_information: {version: [");
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.metadata() + ": not readable as YAML"), std::string::npos) << error;
}

// a recording from elsewhere is read like a configuration: an alias bomb is refused at once
TEST(BagBadInput, MetadataThatIsAnAliasBomb) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  write_text(bag.metadata(), teleop::test::alias_bomb(11));
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.metadata() + ":6: " + teleop::test::kAliasBombError), std::string::npos) << error;
}

TEST(BagBadInput, MetadataWithoutItsKeys) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  write_text(bag.metadata(), "rosbag2_bagfile_information: {version: 5}\n");
  std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.metadata() + ": malformed rosbag2 metadata"), std::string::npos) << error;
  write_text(bag.metadata(), "something: else\n");
  error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.metadata() + ": no rosbag2_bagfile_information"), std::string::npos) << error;
}

TEST(BagBadInput, ABagOfANewerTeleop) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  test::run_sql(bag.db(), "UPDATE teleop_bag SET format_version = 2");
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.db() + ": recorded by a newer teleop (format 2, this reads up to 1)"), std::string::npos)
      << error;
}

TEST(BagBadInput, AMessageWhoseTopicIdHasNoTopic) {
  BagDir bag;
  test::record_simple(bag.dir(), 10);
  test::run_sql(bag.db(), "UPDATE messages SET topic_id = 9 WHERE id = 5");
  const std::string error = open_error(bag.dir());
  EXPECT_NE(error.find(bag.db() + ": message 5 has topic id 9, which has no topic"), std::string::npos) << error;
}

TEST(BagBadInput, AMessageWhoseWriterIsMissing) {
  BagDir bag;
  test::record_simple(bag.dir(), 10);
  test::run_sql(bag.db(), "UPDATE messages SET writer_id = 7 WHERE id = 3");
  const std::string error = read_error(bag.dir());
  EXPECT_NE(error.find(bag.db() + ": message 3 names writer 7"), std::string::npos) << error;
}

TEST(BagBadInput, SelectingATopicTheBagDoesNotHave) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  BagReader reader(bag.dir());
  EXPECT_NE(error_of<BagError>([&] { reader.select({3}); }).find("no topic with id 3"), std::string::npos);
  EXPECT_NE(error_of<BagError>([&] { reader.topic(0); }).find("no topic with id 0"), std::string::npos);
}

TEST(BagBadInput, TheWriterNeverWritesOverAFolderWithFiles) {
  BagDir bag;
  test::record_simple(bag.dir(), 2);
  const std::string error = error_of<BagError>([&] { BagWriter writer({bag.dir()}); });
  EXPECT_NE(error.find(bag.dir() + ": exists and is not empty"), std::string::npos) << error;
  EXPECT_EQ(BagReader(bag.dir()).message_count(), 2u);  // untouched
}

TEST(BagBadInput, TheWriterRefusesATopicIdNeverAddedAndWritesAfterClose) {
  BagDir bag;
  BagWriter writer({bag.dir()});
  writer.add_topic(test::topic("a"));
  const auto data = test::payload(8, 1);
  for (int id : {0, 2, -1}) {
    const std::string error = error_of<BagError>([&] { writer.write(id, 1, 1, test::guid(1), data.data(), 8); });
    EXPECT_NE(error.find("topic id " + std::to_string(id) + ", which was never added"), std::string::npos) << error;
  }
  writer.close();
  writer.close();  // idempotent
  EXPECT_NE(error_of<BagError>([&] { writer.write(1, 1, 1, test::guid(1), data.data(), 8); }).find("closed"),
            std::string::npos);
}

}  // namespace
}  // namespace teleop::bag

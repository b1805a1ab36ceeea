#pragma once
// Shared by the units of teleop::bag: a fresh bag folder, payloads, GUIDs, reading a bag whole.

#include <gtest/gtest.h>
#include <sqlite3.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

#include "teleop/bag/bag_reader.h"
#include "teleop/bag/bag_writer.h"

namespace teleop::bag::test {

/// Where the bags of the tests go: /dev/shm (tmpfs) when there is one, where the fsyncs of the
/// writer (metadata.yaml, SQLite's checkpoints) cost nothing; on a busy disk each costs tens of ms.
inline std::filesystem::path scratch_dir() {
  std::error_code ec;
  return std::filesystem::is_directory("/dev/shm", ec) ? std::filesystem::path("/dev/shm")
                                                       : std::filesystem::temp_directory_path();
}

/// A bag folder "<scratch>/teleop_bag_<pid>_<test>/run1" that does not exist yet, removed with its parent.
class BagDir {
 public:
  BagDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    parent_ =
        scratch_dir() / ("teleop_bag_" + std::to_string(getpid()) + "_" + info->test_suite_name() + "_" + info->name());
    std::filesystem::remove_all(parent_);
    std::filesystem::create_directories(parent_);
  }
  ~BagDir() { std::filesystem::remove_all(parent_); }
  BagDir(const BagDir&) = delete;
  BagDir& operator=(const BagDir&) = delete;

  std::string dir() const { return (parent_ / "run1").string(); }
  std::string db() const { return (parent_ / "run1" / "run1_0.db3").string(); }
  std::string metadata() const { return (parent_ / "run1" / "metadata.yaml").string(); }
  std::string parent() const { return parent_.string(); }

 private:
  std::filesystem::path parent_;
};

inline WriterGuid guid(uint8_t n) {
  WriterGuid g{};
  for (size_t i = 0; i < g.size(); ++i) g[i] = static_cast<uint8_t>(n + i);
  return g;
}

/// A CDR payload of `size` bytes (>= 4): the little-endian encapsulation header, then a pattern.
inline std::vector<uint8_t> payload(size_t size, uint32_t seed) {
  std::vector<uint8_t> bytes(size);
  const uint8_t header[4] = {0x00, 0x01, 0x00, 0x00};
  for (size_t i = 0; i < size; ++i) bytes[i] = i < 4 ? header[i] : static_cast<uint8_t>(seed * 31 + i);
  return bytes;
}

inline TopicInfo topic(const std::string& name) { return {name, "teleop/msg/" + name, "", "", ""}; }

/// Every selected message of a reader, in its order.
inline std::vector<BagMessage> read_all(BagReader& reader) {
  std::vector<BagMessage> out;
  BagMessage m;
  while (reader.next(m)) out.push_back(m);
  return out;
}

/// A closed bag of `count` 300-byte messages on topics "a" and "b" (alternating), recv_ns
/// 1'000'000 * (i + 1), mono 5 * that, writers guid(1) and guid(2).
inline void record_simple(const std::string& dir, int count) {
  BagWriter writer({dir});
  const int a = writer.add_topic(topic("a"));
  const int b = writer.add_topic(topic("b"));
  for (int i = 0; i < count; ++i) {
    const auto data = payload(300, static_cast<uint32_t>(i));
    const int64_t t = 1'000'000LL * (i + 1);
    writer.write(i % 2 ? b : a, t, 5 * t, guid(static_cast<uint8_t>(1 + i % 2)), data.data(), data.size());
  }
  writer.close();
}

/// Runs SQL on a database file with the SQLite C API (as a user with the sqlite3 shell would).
inline void run_sql(const std::string& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(db_path.c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int rc = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  EXPECT_EQ(rc, SQLITE_OK) << sql << ": " << (error ? error : "");
  sqlite3_free(error);
  sqlite3_close(db);
}

/// The first column of the first row of a query, as text ("" when no row).
inline std::string query_text(const std::string& db_path, const std::string& sql) {
  sqlite3* db = nullptr;
  sqlite3_open_v2(db_path.c_str(), &db, SQLITE_OPEN_READONLY, nullptr);
  sqlite3_stmt* stmt = nullptr;
  std::string out;
  if (sqlite3_prepare_v2(db, sql.c_str(), -1, &stmt, nullptr) == SQLITE_OK && sqlite3_step(stmt) == SQLITE_ROW) {
    const auto* text = sqlite3_column_text(stmt, 0);
    out = text ? reinterpret_cast<const char*>(text) : "";
  } else {
    ADD_FAILURE() << sql << ": " << sqlite3_errmsg(db);
  }
  sqlite3_finalize(stmt);
  sqlite3_close(db);
  return out;
}

}  // namespace teleop::bag::test

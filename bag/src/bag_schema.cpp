#include "bag_schema.h"

#include <algorithm>
#include <set>
#include <sstream>
#include <vector>

#include "teleop/bag/bag_format.h"

namespace teleop::bag {
namespace {

// rosbag2's tables (Humble, schema version 2: no `schema` table, offered_qos_profiles present),
// then ours. The names of our extra columns must not be columns of `topics` too: rosbag2 joins
// the two tables and names `data` and `timestamp` unqualified.
constexpr const char* kCreateSql = R"sql(
CREATE TABLE topics(
  id INTEGER PRIMARY KEY,
  name TEXT NOT NULL,
  type TEXT NOT NULL,
  serialization_format TEXT NOT NULL,
  offered_qos_profiles TEXT NOT NULL);
CREATE TABLE writers(
  id INTEGER PRIMARY KEY,
  guid BLOB NOT NULL UNIQUE);
CREATE TABLE messages(
  id INTEGER PRIMARY KEY,
  topic_id INTEGER NOT NULL,
  timestamp INTEGER NOT NULL,
  data BLOB NOT NULL,
  recv_mono_ns INTEGER,
  writer_id INTEGER REFERENCES writers(id));
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
CREATE TABLE teleop_bag(format_version INTEGER NOT NULL);
)sql";

struct TableColumns {
  const char* table;
  std::vector<std::string> columns;
};

const std::vector<TableColumns>& rosbag2_tables() {
  static const std::vector<TableColumns> tables = {
      {"topics", {"id", "name", "type", "serialization_format", "offered_qos_profiles"}},
      {"messages", {"id", "topic_id", "timestamp", "data"}},
  };
  return tables;
}

const std::vector<TableColumns>& teleop_tables() {
  static const std::vector<TableColumns> tables = {
      {"messages", {"recv_mono_ns", "writer_id"}},
      {"writers", {"id", "guid"}},
      {"teleop_bag", {"format_version"}},
  };
  return tables;
}

std::set<std::string> columns_of(SqliteDb& db, const std::string& table) {
  SqliteStatement info(db, "SELECT name FROM pragma_table_info(?1)");
  info.bind(1, table);
  std::set<std::string> columns;
  while (info.step("reading the columns of " + table)) columns.insert(info.column_text(0));
  return columns;
}

void require_columns(SqliteDb& db, const TableColumns& wanted, const std::string& kind) {
  const auto present = columns_of(db, wanted.table);
  if (present.empty()) throw BagError(db.path() + ": no table " + wanted.table + " (not a " + kind + ")");
  for (const auto& column : wanted.columns) {
    if (!present.count(column)) {
      throw BagError(db.path() + ": table " + wanted.table + " has no column " + column + " (not a " + kind + ")");
    }
  }
}

// quick_check answers "ok", or its findings: one row each, some of several lines
std::vector<std::string> quick_check_findings(SqliteDb& db) {
  SqliteStatement check(db, "PRAGMA quick_check");
  std::vector<std::string> findings;
  while (check.step("checking the database (PRAGMA quick_check)")) {
    std::istringstream rows(check.column_text(0));
    for (std::string line; std::getline(rows, line);) {
      if (line != "ok" && line.rfind("***", 0) != 0) findings.push_back(line);  // "*** in database main ***"
    }
  }
  return findings;
}

void check_integrity(SqliteDb& db) {
  const auto findings = quick_check_findings(db);
  if (findings.empty()) return;
  constexpr size_t kShown = 3;  // one line of error, not quick_check's hundred
  std::string shown;
  for (size_t i = 0; i < std::min(kShown, findings.size()); ++i) shown += (i ? "; " : "") + findings[i];
  if (findings.size() > kShown) shown += "; " + std::to_string(findings.size() - kShown) + " more";
  throw BagError(db.path() + ": the database is corrupt (quick_check: " + shown + ")");
}

int read_format_version(SqliteDb& db) {
  SqliteStatement query(db, "SELECT MAX(format_version) FROM teleop_bag");
  if (!query.step("reading teleop_bag") || query.column_is_null(0)) {
    throw BagError(db.path() + ": table teleop_bag is empty (no format version)");
  }
  return static_cast<int>(query.column_int64(0));
}

}  // namespace

void create_schema(SqliteDb& db) {
  db.exec("BEGIN", "creating the tables");
  db.exec(kCreateSql, "creating the tables");
  db.exec("INSERT INTO teleop_bag (format_version) VALUES (" + std::to_string(kBagFormatVersion) + ")",
          "creating the tables");
  db.exec("COMMIT", "creating the tables");
}

SchemaInfo check_schema(SqliteDb& db) {
  check_integrity(db);
  for (const auto& table : rosbag2_tables()) require_columns(db, table, "rosbag2 sqlite3 bag");
  SchemaInfo info;
  info.teleop = !columns_of(db, "teleop_bag").empty();
  if (!info.teleop) return info;
  info.format_version = read_format_version(db);
  if (info.format_version > kBagFormatVersion) {
    throw BagError(db.path() + ": recorded by a newer teleop (format " + std::to_string(info.format_version) +
                   ", this reads up to " + std::to_string(kBagFormatVersion) + ")");
  }
  for (const auto& table : teleop_tables()) require_columns(db, table, "teleop bag");
  return info;
}

}  // namespace teleop::bag

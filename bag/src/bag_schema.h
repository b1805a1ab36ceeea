#pragma once
// The tables of a bag's database (docs/recording.md): rosbag2's topics and messages, plus our
// columns and tables that rosbag2 never reads. Creating them, and checking a database has them.

#include <string>

#include "sqlite_db.h"

namespace teleop::bag {

/// The statements the writer prepares once, in the column order they bind.
inline constexpr const char* kInsertTopicSql =
    "INSERT INTO topics (name, type, serialization_format, offered_qos_profiles) VALUES (?1, ?2, 'cdr', ?3)";
inline constexpr const char* kInsertWriterSql = "INSERT INTO writers (guid) VALUES (?1)";
inline constexpr const char* kInsertMessageSql =
    "INSERT INTO messages (topic_id, timestamp, data, recv_mono_ns, writer_id) VALUES (?1, ?2, ?3, ?4, ?5)";

/// Creates every table and index in an empty database and records kBagFormatVersion.
void create_schema(SqliteDb& db);

/// What a database holds besides rosbag2's tables.
struct SchemaInfo {
  bool teleop = false;     ///< our table teleop_bag is there (else a plain rosbag2 bag)
  int format_version = 0;  ///< teleop_bag.format_version, 0 for a plain rosbag2 bag
};

/// Checks the database is sound (`PRAGMA quick_check`), has the tables and columns rosbag2 reads
/// (and ours when it says it is a teleop bag), and is not of a newer format than we read.
/// Throws BagError naming the database.
SchemaInfo check_schema(SqliteDb& db);

}  // namespace teleop::bag

#pragma once
// The writers table: one row per DDS writer GUID, inserted the first time a message of it is
// written, so that a message carries an 8-byte row id instead of the 16-byte GUID.

#include <cstdint>
#include <map>

#include "sqlite_db.h"
#include "teleop/bag/bag_types.h"

namespace teleop::bag {

class WriterTable {
 public:
  explicit WriterTable(SqliteDb& db);

  /// The writer's row id; inserts the row (into the open transaction) the first time.
  int64_t id_of(const WriterGuid& guid);
  /// The open transaction was committed: its rows are durable.
  void commit();
  /// The open transaction was rolled back: its rows are gone, and forgotten.
  void roll_back();

 private:
  SqliteDb& db_;
  SqliteStatement insert_;
  std::map<WriterGuid, int64_t> ids_;
  int64_t max_id_ = 0;            // the newest row's id
  int64_t committed_max_id_ = 0;  // the newest committed row's id
};

}  // namespace teleop::bag

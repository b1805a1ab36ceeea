#pragma once
// Iterating a bag's messages in receive-time order, optionally of some topics only.

#include <memory>
#include <string>
#include <vector>

#include "sqlite_db.h"
#include "teleop/bag/bag_types.h"

namespace teleop::bag {

class MessageCursor {
 public:
  /// Messages of `topic_ids` (empty: all) by timestamp, then by id (the order written).
  /// `teleop_columns`: the database has our recv_mono_ns and writers (else a plain rosbag2 bag:
  /// they read as 0 and an all-zero GUID). `topic_count` bounds the valid topic ids.
  MessageCursor(SqliteDb& db, bool teleop_columns, const std::vector<int>& topic_ids, int topic_count);

  /// The next message into `out`; false at the end. Throws BagError on a damaged row.
  bool next(BagMessage& out);

 private:
  void read_row(BagMessage& out) const;
  void read_writer(int64_t message_id, BagMessage& out) const;

  SqliteDb& db_;
  int topic_count_;
  std::unique_ptr<SqliteStatement> query_;
  bool done_ = false;
};

}  // namespace teleop::bag

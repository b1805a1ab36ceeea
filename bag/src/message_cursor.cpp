#include "message_cursor.h"

#include <cstring>

namespace teleop::bag {
namespace {

// columns: 0 id, 1 topic_id, 2 timestamp, 3 recv_mono_ns, 4 writer_id, 5 guid, 6 data
std::string select_sql(bool teleop_columns, size_t topic_filter_size) {
  std::string sql = teleop_columns
                        ? "SELECT m.id, m.topic_id, m.timestamp, m.recv_mono_ns, m.writer_id, w.guid, m.data "
                          "FROM messages m LEFT JOIN writers w ON w.id = m.writer_id"
                        : "SELECT m.id, m.topic_id, m.timestamp, NULL, NULL, NULL, m.data FROM messages m";
  if (topic_filter_size > 0) {
    sql += " WHERE m.topic_id IN (?";
    for (size_t i = 1; i < topic_filter_size; ++i) sql += ", ?";
    sql += ")";
  }
  // timestamp_idx holds (timestamp, rowid): this order needs no sort
  return sql + " ORDER BY m.timestamp, m.id";
}

}  // namespace

MessageCursor::MessageCursor(SqliteDb& db, bool teleop_columns, const std::vector<int>& topic_ids, int topic_count)
    : db_(db), topic_count_(topic_count) {
  for (int id : topic_ids) {
    if (id < 1 || id > topic_count) {
      throw BagError(db.path() + ": no topic with id " + std::to_string(id) + " to select (the bag has " +
                     std::to_string(topic_count) + ")");
    }
  }
  query_ = std::make_unique<SqliteStatement>(db, select_sql(teleop_columns, topic_ids.size()));
  for (size_t i = 0; i < topic_ids.size(); ++i) query_->bind(static_cast<int>(i) + 1, int64_t{topic_ids[i]});
}

bool MessageCursor::next(BagMessage& out) {
  if (done_) return false;
  if (!query_->step("reading the messages")) {
    done_ = true;
    return false;
  }
  read_row(out);
  return true;
}

void MessageCursor::read_row(BagMessage& out) const {
  const int64_t id = query_->column_int64(0);
  const int64_t topic_id = query_->column_int64(1);
  if (topic_id < 1 || topic_id > topic_count_) {
    throw BagError(db_.path() + ": message " + std::to_string(id) + " has topic id " + std::to_string(topic_id) +
                   ", which has no topic");
  }
  out.topic_id = static_cast<int>(topic_id);
  out.recv_ns = query_->column_int64(2);
  out.recv_mono_ns = query_->column_int64(3);  // NULL reads as 0: unknown
  read_writer(id, out);
  const uint8_t* data = query_->column_blob(6);
  out.data.assign(data, data + query_->column_bytes(6));
}

void MessageCursor::read_writer(int64_t message_id, BagMessage& out) const {
  out.writer.fill(0);
  if (query_->column_is_null(4)) return;  // no writer recorded
  if (query_->column_is_null(5)) {
    throw BagError(db_.path() + ": message " + std::to_string(message_id) + " names writer " +
                   std::to_string(query_->column_int64(4)) + ", which is not in the writers table");
  }
  const uint8_t* guid = query_->column_blob(5);
  const size_t size = query_->column_bytes(5);
  if (size != out.writer.size()) {
    throw BagError(db_.path() + ": writer " + std::to_string(query_->column_int64(4)) + " has a GUID of " +
                   std::to_string(size) + " bytes, not 16");
  }
  std::memcpy(out.writer.data(), guid, size);
}

}  // namespace teleop::bag

#include "writer_table.h"

#include "bag_schema.h"

namespace teleop::bag {

WriterTable::WriterTable(SqliteDb& db) : db_(db), insert_(db, kInsertWriterSql) {}

int64_t WriterTable::id_of(const WriterGuid& guid) {
  const auto known = ids_.find(guid);
  if (known != ids_.end()) return known->second;
  insert_.bind_blob(1, guid.data(), guid.size());
  insert_.run("adding a writer");
  const int64_t id = sqlite3_last_insert_rowid(db_.handle());
  ids_.emplace(guid, id);
  max_id_ = id;
  return id;
}

void WriterTable::commit() { committed_max_id_ = max_id_; }

void WriterTable::roll_back() {
  // the rolled-back rows had the largest ids (SQLite gives a new row the largest id + 1)
  std::erase_if(ids_, [this](const auto& entry) { return entry.second > committed_max_id_; });
  max_id_ = committed_max_id_;
}

}  // namespace teleop::bag

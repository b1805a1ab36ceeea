// A bag folder in the layout of rosbag2's sqlite3 storage (docs/recording.md).
#include <filesystem>
#include <memory>
#include <system_error>

#include "bag_location.h"
#include "bag_schema.h"
#include "message_cursor.h"
#include "recording_source.h"
#include "sqlite_db.h"
#include "topic_table.h"

namespace teleop::bag {
namespace {

class SqliteSource : public RecordingSource {
 public:
  explicit SqliteSource(const std::string& dir);

  const std::vector<TopicInfo>& topics() const override { return topics_; }
  uint64_t message_count() const override { return message_count_; }
  int64_t start_ns() const override { return start_ns_; }
  int64_t end_ns() const override { return end_ns_; }
  void select(const std::vector<int>& topic_ids) override;
  bool next(BagMessage& out) override;
  const std::string& warning() const override { return warning_; }
  const std::string& data_path() const override { return db_->path(); }
  std::string format() const override { return "sqlite3"; }

 private:
  void count_messages();
  void note(const std::string& text);
  void note_what_metadata_missed(const BagLocation& location);

  std::unique_ptr<SqliteDb> db_;
  SchemaInfo schema_;
  std::vector<TopicInfo> topics_;
  uint64_t message_count_ = 0;
  int64_t start_ns_ = 0;
  int64_t end_ns_ = 0;
  std::unique_ptr<MessageCursor> cursor_;
  std::string warning_;
};

SqliteSource::SqliteSource(const std::string& dir) {
  const BagLocation location = locate_bag(dir);
  db_ = std::make_unique<SqliteDb>(location.db_path, SqliteDb::Mode::kReadOnly);
  schema_ = check_schema(*db_);
  topics_ = read_topics(*db_);
  check_message_topics(*db_);
  count_messages();
  note_what_metadata_missed(location);
  if (!schema_.teleop)
    note("not recorded by teleop (no table teleop_bag): monotonic receive times and writers unknown");
}

void SqliteSource::count_messages() {
  SqliteStatement query(*db_, "SELECT COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages");
  query.step("counting the messages");
  message_count_ = static_cast<uint64_t>(query.column_int64(0));
  start_ns_ = query.column_int64(1);  // NULL without messages: 0
  end_ns_ = query.column_int64(2);
}

// a recorder killed mid-recording leaves metadata.yaml missing (killed before its first rewrite)
// or behind the database, and its WAL file beside the database
void SqliteSource::note_what_metadata_missed(const BagLocation& location) {
  if (!location.metadata) {
    note("metadata.yaml missing (the recorder was killed?): read from the database");
  } else if (location.metadata->message_count != message_count_) {
    note("metadata.yaml is stale (it counts " + std::to_string(location.metadata->message_count) +
         " messages, the database " + std::to_string(message_count_) +
         ": the recorder was killed?): read from the database");
  }
  std::error_code ec;
  if (std::filesystem::exists(location.db_path + "-wal", ec)) {
    note("the recording is still going on or was not closed (" + location.db_path + "-wal present)");
  }
}

void SqliteSource::note(const std::string& text) { warning_ += (warning_.empty() ? "" : "; ") + text; }

void SqliteSource::select(const std::vector<int>& topic_ids) {
  cursor_.reset();  // its statement goes before the new one is prepared
  cursor_ = std::make_unique<MessageCursor>(*db_, schema_.teleop, topic_ids, static_cast<int>(topics_.size()));
}

bool SqliteSource::next(BagMessage& out) {
  if (!cursor_) select({});
  return cursor_->next(out);
}

}  // namespace

std::unique_ptr<RecordingSource> open_sqlite_bag(const std::string& dir) { return std::make_unique<SqliteSource>(dir); }

}  // namespace teleop::bag

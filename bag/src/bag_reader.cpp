#include "teleop/bag/bag_reader.h"

#include <filesystem>
#include <memory>
#include <system_error>

#include "bag_location.h"
#include "bag_schema.h"
#include "message_cursor.h"
#include "sqlite_db.h"
#include "topic_table.h"

namespace teleop::bag {

class BagReader::Impl {
 public:
  explicit Impl(const std::string& dir);

  const std::vector<TopicInfo>& topics() const { return topics_; }
  const TopicInfo& topic(int topic_id) const;
  int topic_id(const std::string& name) const;
  uint64_t message_count() const { return message_count_; }
  int64_t start_ns() const { return start_ns_; }
  int64_t end_ns() const { return end_ns_; }
  void select(const std::vector<int>& topic_ids);
  bool next(BagMessage& out);
  const std::string& warning() const { return warning_; }
  const std::string& db_path() const { return db_->path(); }

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

BagReader::Impl::Impl(const std::string& dir) {
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

void BagReader::Impl::count_messages() {
  SqliteStatement query(*db_, "SELECT COUNT(*), MIN(timestamp), MAX(timestamp) FROM messages");
  query.step("counting the messages");
  message_count_ = static_cast<uint64_t>(query.column_int64(0));
  start_ns_ = query.column_int64(1);  // NULL without messages: 0
  end_ns_ = query.column_int64(2);
}

// a recorder killed mid-recording leaves metadata.yaml missing (killed before its first rewrite)
// or behind the database, and its WAL file beside the database
void BagReader::Impl::note_what_metadata_missed(const BagLocation& location) {
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

void BagReader::Impl::note(const std::string& text) { warning_ += (warning_.empty() ? "" : "; ") + text; }

const TopicInfo& BagReader::Impl::topic(int topic_id) const {
  if (topic_id < 1 || topic_id > static_cast<int>(topics_.size())) {
    throw BagError(db_->path() + ": no topic with id " + std::to_string(topic_id));
  }
  return topics_[static_cast<size_t>(topic_id - 1)];
}

int BagReader::Impl::topic_id(const std::string& name) const {
  for (size_t i = 0; i < topics_.size(); ++i) {
    if (topics_[i].name == name) return static_cast<int>(i) + 1;
  }
  return -1;
}

void BagReader::Impl::select(const std::vector<int>& topic_ids) {
  cursor_.reset();  // its statement goes before the new one is prepared
  cursor_ = std::make_unique<MessageCursor>(*db_, schema_.teleop, topic_ids, static_cast<int>(topics_.size()));
}

bool BagReader::Impl::next(BagMessage& out) {
  if (!cursor_) select({});
  return cursor_->next(out);
}

BagReader::BagReader(const std::string& dir) : impl_(std::make_unique<Impl>(dir)) {}
BagReader::~BagReader() = default;

const std::vector<TopicInfo>& BagReader::topics() const { return impl_->topics(); }
const TopicInfo& BagReader::topic(int topic_id) const { return impl_->topic(topic_id); }
int BagReader::topic_id(const std::string& name) const { return impl_->topic_id(name); }
uint64_t BagReader::message_count() const { return impl_->message_count(); }
int64_t BagReader::start_ns() const { return impl_->start_ns(); }
int64_t BagReader::end_ns() const { return impl_->end_ns(); }
void BagReader::select(const std::vector<int>& topic_ids) { impl_->select(topic_ids); }
bool BagReader::next(BagMessage& out) { return impl_->next(out); }
const std::string& BagReader::warning() const { return impl_->warning(); }
const std::string& BagReader::db_path() const { return impl_->db_path(); }

}  // namespace teleop::bag

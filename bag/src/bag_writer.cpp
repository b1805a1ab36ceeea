#include "teleop/bag/bag_writer.h"

#include <algorithm>
#include <memory>
#include <utility>
#include <vector>

#include "atomic_file.h"
#include "bag_layout.h"
#include "bag_metadata.h"
#include "bag_schema.h"
#include "recording_tally.h"
#include "sqlite_db.h"
#include "teleop/common/clock.h"
#include "writer_table.h"

namespace teleop::bag {
namespace {

int64_t query_int(SqliteDb& db, const std::string& sql) {
  SqliteStatement query(db, sql);
  query.step(sql);
  return query.column_int64(0);
}

// SQLite answers SQLITE_FULL when the file would grow beyond max_page_count pages, as on a full
// disk (the WAL beside it is not counted: it holds up to ~4 MB before being folded back in)
void limit_size(SqliteDb& db, int64_t max_bytes) {
  const int64_t pages = std::max<int64_t>(1, max_bytes / query_int(db, "PRAGMA page_size"));
  query_int(db, "PRAGMA max_page_count=" + std::to_string(pages));
}

}  // namespace

class BagWriter::Impl {
 public:
  explicit Impl(BagWriterOptions options);

  int add_topic(const TopicInfo& topic);
  void write(int topic_id, int64_t recv_ns, int64_t recv_mono_ns, const WriterGuid& writer, const uint8_t* data,
             size_t size);
  void poll();
  void flush();
  void close();
  bool closed() const { return !db_; }

  const BagStats& stats() const { return tally_.stats(); }
  const std::string& db_path() const { return db_path_; }
  const std::string& metadata_path() const { return metadata_path_; }

 private:
  void open_database();
  int find_topic(const std::string& name) const;
  void check_open() const;
  void check_topic(int topic_id) const;
  void begin_if_idle();
  void commit(int64_t now_ns);
  void keep_up(int64_t now_ns);
  void write_metadata(int64_t now_ns);
  void forget_open_transaction() noexcept;
  void release() noexcept;
  // runs a step that writes; after a failure the open transaction is rolled back (SQLite may
  // have done so already) and forgotten, and the error passed on
  template <typename Step>
  auto guarded(Step&& step) {
    try {
      return step();
    } catch (const BagError&) {
      forget_open_transaction();
      throw;
    }
  }

  BagWriterOptions options_;
  std::string db_file_;
  std::string db_path_;
  std::string metadata_path_;
  // the statements after their connection: destroyed before it
  std::unique_ptr<SqliteDb> db_;
  std::unique_ptr<SqliteStatement> insert_topic_;
  std::unique_ptr<SqliteStatement> insert_message_;
  std::unique_ptr<WriterTable> writers_;
  std::vector<TopicInfo> topics_;
  RecordingTally tally_;
  bool transaction_open_ = false;
  bool metadata_stale_ = true;
  int64_t last_commit_ns_ = 0;
  int64_t last_metadata_ns_ = 0;
};

BagWriter::Impl::Impl(BagWriterOptions options)
    : options_(std::move(options)),
      db_file_(db_file_name(options_.dir)),
      db_path_(path_in(options_.dir, db_file_)),
      metadata_path_(bag::metadata_path(options_.dir)) {
  create_bag_dir(options_.dir);
  open_database();
  const int64_t now = monotonic_now_ns();
  last_commit_ns_ = now;
  write_metadata(now);
}

void BagWriter::Impl::open_database() {
  db_ = std::make_unique<SqliteDb>(db_path_, SqliteDb::Mode::kCreate);
  // WAL with synchronous NORMAL: a commit is an append to the WAL without an fsync; it survives
  // the process being killed (a power cut may take the last commits, never the file)
  db_->exec("PRAGMA journal_mode=WAL; PRAGMA synchronous=NORMAL", "setting the journal");
  if (options_.max_db_bytes > 0) limit_size(*db_, options_.max_db_bytes);
  create_schema(*db_);
  insert_topic_ = std::make_unique<SqliteStatement>(*db_, kInsertTopicSql);
  insert_message_ = std::make_unique<SqliteStatement>(*db_, kInsertMessageSql);
  writers_ = std::make_unique<WriterTable>(*db_);
}

int BagWriter::Impl::find_topic(const std::string& name) const {
  const auto it = std::find_if(topics_.begin(), topics_.end(), [&](const TopicInfo& t) { return t.name == name; });
  return it == topics_.end() ? -1 : static_cast<int>(it - topics_.begin()) + 1;
}

int BagWriter::Impl::add_topic(const TopicInfo& topic) {
  check_open();
  const int known = find_topic(topic.name);
  if (known > 0) return known;
  return guarded([&] {
    begin_if_idle();
    insert_topic_->bind(1, topic.name);
    insert_topic_->bind(2, topic.type);
    insert_topic_->bind(3, topic.qos_profile);
    insert_topic_->run("adding topic " + topic.name);
    const auto id = static_cast<int>(sqlite3_last_insert_rowid(db_->handle()));
    // committed at once, so that the topic is never rolled back with a transaction of messages
    commit(monotonic_now_ns());
    topics_.push_back(topic);
    tally_.add_topic();
    metadata_stale_ = true;
    return id;
  });
}

void BagWriter::Impl::write(int topic_id, int64_t recv_ns, int64_t recv_mono_ns, const WriterGuid& writer,
                            const uint8_t* data, size_t size) {
  check_open();
  check_topic(topic_id);
  guarded([&] {
    begin_if_idle();
    const int64_t writer_id = writers_->id_of(writer);
    insert_message_->bind(1, topic_id);
    insert_message_->bind(2, recv_ns);
    insert_message_->bind_blob(3, data, size);
    insert_message_->bind(4, recv_mono_ns);
    insert_message_->bind(5, writer_id);
    insert_message_->run("appending a message");
    tally_.add(topic_id, recv_ns, size);
    keep_up(monotonic_now_ns());
  });
}

void BagWriter::Impl::poll() {
  check_open();
  guarded([&] { keep_up(monotonic_now_ns()); });
}

void BagWriter::Impl::flush() {
  check_open();
  guarded([&] {
    const int64_t now = monotonic_now_ns();
    commit(now);
    write_metadata(now);
  });
}

void BagWriter::Impl::close() {
  if (closed()) return;
  try {
    flush();
  } catch (...) {
    release();
    throw;
  }
  release();
}

void BagWriter::Impl::check_open() const {
  if (closed()) throw BagError(db_path_ + ": the bag writer is closed");
}

void BagWriter::Impl::check_topic(int topic_id) const {
  if (topic_id < 1 || topic_id > static_cast<int>(topics_.size())) {
    throw BagError(db_path_ + ": a message of topic id " + std::to_string(topic_id) +
                   ", which was never added (add_topic first)");
  }
}

void BagWriter::Impl::begin_if_idle() {
  if (transaction_open_) return;
  db_->exec("BEGIN", "starting a transaction");
  transaction_open_ = true;
}

void BagWriter::Impl::commit(int64_t now_ns) {
  if (transaction_open_) {
    db_->exec("COMMIT", "committing");
    transaction_open_ = false;
    tally_.commit();
    writers_->commit();
    metadata_stale_ = true;
  }
  last_commit_ns_ = now_ns;
}

// commits when the commit period has passed, and rewrites metadata.yaml when its period has
// (after a commit: it describes what is in the database)
void BagWriter::Impl::keep_up(int64_t now_ns) {
  if (now_ns - last_commit_ns_ >= options_.commit_period_ns) commit(now_ns);
  if (now_ns - last_metadata_ns_ < options_.metadata_period_ns) return;
  commit(now_ns);
  if (metadata_stale_) {
    write_metadata(now_ns);
  } else {
    last_metadata_ns_ = now_ns;  // the file is current: its period starts again
  }
}

void BagWriter::Impl::write_metadata(int64_t now_ns) {
  BagSummary summary;
  summary.db_file = db_file_;
  summary.topics = topics_;
  summary.topic_counts = tally_.topic_counts();
  summary.message_count = tally_.stats().messages;
  summary.first_ns = tally_.stats().first_ns;
  summary.last_ns = tally_.stats().last_ns;
  write_file_atomically(metadata_path_, metadata_yaml(summary));
  metadata_stale_ = false;
  last_metadata_ns_ = now_ns;
}

void BagWriter::Impl::forget_open_transaction() noexcept {
  if (!transaction_open_ || closed()) return;
  db_->exec_quietly("ROLLBACK");
  transaction_open_ = false;
  tally_.roll_back();
  writers_->roll_back();
}

// statements first, then the connection; the WAL is folded back into the file and the journal
// switched back to a rollback journal, so a closed bag is one file that opens read-only anywhere
void BagWriter::Impl::release() noexcept {
  forget_open_transaction();
  writers_.reset();
  insert_message_.reset();
  insert_topic_.reset();
  db_->exec_quietly("PRAGMA journal_mode=DELETE");
  db_.reset();
}

BagWriter::BagWriter(BagWriterOptions options) : impl_(std::make_unique<Impl>(std::move(options))) {}

BagWriter::~BagWriter() {
  try {
    impl_->close();
  } catch (...) {
    // a destructor never throws: what was committed before stays readable
  }
}

int BagWriter::add_topic(const TopicInfo& topic) { return impl_->add_topic(topic); }

void BagWriter::write(int topic_id, int64_t recv_ns, int64_t recv_mono_ns, const WriterGuid& writer,
                      const uint8_t* data, size_t size) {
  impl_->write(topic_id, recv_ns, recv_mono_ns, writer, data, size);
}

void BagWriter::write(const MessageToWrite& m) {
  impl_->write(m.topic_id, m.recv_ns, m.recv_mono_ns, m.writer, m.data, m.size);
}

void BagWriter::poll() { impl_->poll(); }
void BagWriter::flush() { impl_->flush(); }
void BagWriter::close() { impl_->close(); }
const BagStats& BagWriter::stats() const { return impl_->stats(); }
const std::string& BagWriter::db_path() const { return impl_->db_path(); }
const std::string& BagWriter::metadata_path() const { return impl_->metadata_path(); }

}  // namespace teleop::bag

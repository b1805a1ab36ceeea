#pragma once
// Records messages into a bag folder in the layout of rosbag2's sqlite3 storage (ROS 2 Humble:
// metadata.yaml version 5 beside <folder>/<folder-name>_0.db3), docs/recording.md.
// Not for a control loop: it allocates and does file I/O; run it in a tool's own thread.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "teleop/bag/bag_error.h"
#include "teleop/bag/bag_format.h"
#include "teleop/bag/bag_types.h"
#include "teleop/bag/recording_writer.h"

namespace teleop::bag {

struct BagWriterOptions {
  std::string dir;                             ///< created; an existing non-empty folder is an error
  int64_t commit_period_ns = 200'000'000;      ///< the open transaction is committed at least this often
  int64_t metadata_period_ns = 1'000'000'000;  ///< metadata.yaml rewritten (tmp + rename) at least this often
  /// Cap on the database's size in bytes (PRAGMA max_page_count), 0: none. Reaching it is
  /// reported like a full disk: a recording can be kept from filling the disk.
  int64_t max_db_bytes = 0;
};

/// One bag being recorded. Every failure throws BagError naming the file; a full disk (or the
/// max_db_bytes cap) throws "... disk full ...", and everything committed before stays readable.
/// A writer killed mid-recording loses at most the messages of its open transaction.
class BagWriter : public RecordingWriter {
 public:
  /// Creates the folder, the database (WAL journal, synchronous NORMAL: a commit survives the
  /// process being killed) and an initial metadata.yaml.
  explicit BagWriter(BagWriterOptions options);
  /// close() if not closed; never throws.
  ~BagWriter() override;
  BagWriter(const BagWriter&) = delete;
  BagWriter& operator=(const BagWriter&) = delete;

  /// The topic's id (1, 2, ... in the order added); the same name again returns the same id.
  /// Commits the open transaction with the new topic, so that a topic is never lost once added.
  int add_topic(const TopicInfo& topic) override;

  /// Appends one message to the open transaction; commits when commit_period_ns passed since the
  /// last commit (by CLOCK_MONOTONIC) and rewrites metadata.yaml when metadata_period_ns passed.
  /// `recv_ns` is the receive time on CLOCK_REALTIME (rosbag2's timestamp), `recv_mono_ns` the
  /// same instant on CLOCK_MONOTONIC. An unknown topic id throws.
  void write(int topic_id, int64_t recv_ns, int64_t recv_mono_ns, const WriterGuid& writer, const uint8_t* data,
             size_t size);
  /// The same, as RecordingWriter (the publish time is not kept in this layout).
  void write(const MessageToWrite& message) override;

  /// Commits and rewrites metadata.yaml if their periods have passed, as write() does: for a
  /// caller whose bus is quiet (no write() to do it) calling it now and then.
  void poll() override;

  /// Commits now and rewrites metadata.yaml.
  void flush();

  /// flush(), then finalizes the database (its WAL folded back in: one self-contained file).
  /// Idempotent. Releases everything even when the flush throws.
  void close() override;

  const BagStats& stats() const override;
  const std::string& db_path() const;
  const std::string& data_path() const override { return db_path(); }
  const std::string& metadata_path() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace teleop::bag

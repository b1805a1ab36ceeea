#pragma once
// Reads a recording, docs/recording.md: an MCAP file (recorded by McapWriter or any MCAP writer
// of CDR messages: recv_mono_ns is 0 and the writer unknown; read through its summary when it has
// one, else streamed up to its last complete chunk), or a bag folder recorded by BagWriter (or a
// plain rosbag2 sqlite3 bag of one file: then recv_mono_ns is 0 and the writer unknown).

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "teleop/bag/bag_error.h"
#include "teleop/bag/bag_format.h"
#include "teleop/bag/bag_types.h"

namespace teleop::bag {

class BagReader {
 public:
  /// Opens `path`: a file starting with MCAP's magic is an MCAP recording (its records checked as
  /// they are read, its summary's CRC checked); a folder is a sqlite3 bag. Validates a bag:
  /// metadata.yaml (when missing the database is read alone and
  /// warning() says so), its version, the database (opens, `PRAGMA quick_check` passes, the
  /// tables are there, the format is not newer than ours, every message's topic exists).
  /// Throws BagError naming the file and the problem.
  explicit BagReader(const std::string& path);
  ~BagReader();
  BagReader(const BagReader&) = delete;
  BagReader& operator=(const BagReader&) = delete;

  /// The topics ordered by id: topics()[topic_id - 1] (the ids are 1..N, checked on opening).
  const std::vector<TopicInfo>& topics() const;
  /// The topic of an id; throws BagError when there is none.
  const TopicInfo& topic(int topic_id) const;
  /// The id of the topic with this name, -1 when absent.
  int topic_id(const std::string& name) const;

  /// Messages in the database (counted there, not taken from metadata.yaml).
  uint64_t message_count() const;
  /// Smallest and largest recv_ns in the database (0 when empty).
  int64_t start_ns() const;
  int64_t end_ns() const;

  /// Starts an iteration over the messages ordered by recv_ns (then by the order written), of
  /// the given topic ids only (empty: all). An unknown id throws. next() without select()
  /// iterates everything.
  void select(const std::vector<int>& topic_ids);
  /// The next message into `out` (its buffer reused); false at the end. A database damaged
  /// beyond what quick_check saw throws BagError.
  bool next(BagMessage& out);

  /// Empty, or what the reader noticed but could read anyway, e.g. "metadata.yaml missing (the
  /// recorder was killed?): read from the database". Several notes are joined by "; ".
  const std::string& warning() const;
  /// The file that holds the messages: the bag's database, the MCAP file.
  const std::string& db_path() const;
  /// "sqlite3", or "mcap" with its chunks' compression, e.g. "mcap (zstd)".
  std::string format() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace teleop::bag

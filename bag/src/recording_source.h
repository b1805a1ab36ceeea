#pragma once
// What BagReader reads a recording through, whatever its format: a bag folder in rosbag2's
// sqlite3 layout (SqliteSource) or an MCAP file (McapSource); open_recording() tells them apart.

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "teleop/bag/bag_types.h"

namespace teleop::bag {

class RecordingSource {
 public:
  virtual ~RecordingSource() = default;

  /// Topics ordered by id: topics()[id - 1].
  virtual const std::vector<TopicInfo>& topics() const = 0;
  virtual uint64_t message_count() const = 0;
  virtual int64_t start_ns() const = 0;
  virtual int64_t end_ns() const = 0;
  /// Starts an iteration in receive-time order over these (valid) topic ids, empty: all.
  virtual void select(const std::vector<int>& topic_ids) = 0;
  virtual bool next(BagMessage& out) = 0;
  virtual const std::string& warning() const = 0;
  virtual const std::string& data_path() const = 0;
  /// "sqlite3", or "mcap" with its chunks' compression, e.g. "mcap (zstd)".
  virtual std::string format() const = 0;
};

/// The recording at `path`: a folder is a sqlite3 bag, a file starting with MCAP's magic an MCAP
/// recording. Throws BagError naming the path when it is neither or cannot be read.
std::unique_ptr<RecordingSource> open_recording(const std::string& path);

std::unique_ptr<RecordingSource> open_sqlite_bag(const std::string& dir);
std::unique_ptr<RecordingSource> open_mcap(const std::string& file);

}  // namespace teleop::bag

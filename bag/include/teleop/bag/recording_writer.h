#pragma once
// What the recorder writes a recording through, whatever its format: BagWriter (rosbag2's
// sqlite3 layout) or McapWriter (an MCAP file). Not for a control loop: both allocate and do
// file I/O; run one in a tool's own thread.

#include <string>

#include "teleop/bag/bag_error.h"
#include "teleop/bag/bag_types.h"

namespace teleop::bag {

class RecordingWriter {
 public:
  virtual ~RecordingWriter() = default;

  /// The topic's id (1, 2, ... in the order added); the same name again returns the same id.
  virtual int add_topic(const TopicInfo& topic) = 0;
  /// Appends one message; an unknown topic id throws BagError.
  virtual void write(const MessageToWrite& message) = 0;
  /// Makes durable what is due (a commit, a chunk) when its period has passed: for a caller
  /// whose bus is quiet, now and then.
  virtual void poll() = 0;
  /// Writes everything and finishes the file(s). Idempotent.
  virtual void close() = 0;

  virtual const BagStats& stats() const = 0;
  /// The file that holds the messages (the database, the .mcap file).
  virtual const std::string& data_path() const = 0;
};

}  // namespace teleop::bag

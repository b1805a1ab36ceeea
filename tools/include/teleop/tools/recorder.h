#pragma once
// `teleop record -o PATH`: every teleop topic on the bus (or those chosen), as the serialized
// samples with their receive times, into an MCAP file with each type's ROS 2 schema (default) or
// a folder in rosbag2's sqlite3 layout with the writers too (bag/, docs/recording.md). Topics are
// subscribed as discovery finds them, so nodes may start after the recorder.

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include "teleop/bag/mcap_writer.h"
#include "teleop/tools/message_schemas.h"
#include "teleop/tools/topic_tools.h"

namespace teleop::tools {

struct RecordOptions {
  /// The recording: an MCAP file, or a sqlite3 bag's folder (created; must not exist, or for a
  /// folder be empty).
  std::string dir;
  RecordingFormat format = RecordingFormat::kMcap;
  /// An MCAP recording's chunks.
  bag::McapCompression compression = bag::McapCompression::kZstd;
  /// Only these topics; empty: every teleop topic.
  std::vector<std::string> topics;
  /// Stop after this long (0: until interrupted).
  double duration_s = 0.0;
  /// Samples waiting for the disk at most; beyond, a sample is dropped and counted (memory stays
  /// bounded when the disk cannot keep up).
  size_t queue_capacity = 1 << 17;
  /// Stop with an error once the recording would grow beyond this [bytes], as on a full disk
  /// (what was recorded stays readable); 0: no cap.
  int64_t max_bytes = 0;
};

struct RecordResult {
  uint64_t messages = 0;
  uint64_t bytes = 0;
  /// Dropped because the queue to the disk was full.
  uint64_t dropped = 0;
  /// Gaps in the writers' sequence numbers: samples that never reached the recorder.
  uint64_t missed = 0;
  double seconds = 0.0;
  /// CPU time the recorder used (user + system, all its threads) [s].
  double cpu_s = 0.0;
  std::vector<std::string> topics;
};

/// Throws ConfigError naming the first of `topics` that is no teleop topic (a fixed name of
/// topics.h, or a family prefix with a name after it), with the topic it may have meant: a typo
/// in `record --topics` is refused before recording, not found out after it.
void check_record_topics(const std::vector<std::string>& topics);

/// Records until interrupted or the duration is over. Throws bag::BagError (a full disk, the size
/// cap: after closing the recording, which stays readable) or ConfigError.
RecordResult record(const BusOptions& bus, const RecordOptions& options, FILE* log);

}  // namespace teleop::tools

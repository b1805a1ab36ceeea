#pragma once
// Records messages into one MCAP file (mcap.dev/spec, ROS 2 profile), docs/recording.md: each
// topic a Channel (message encoding "cdr") with its type's Schema ("ros2msg"), the messages in
// compressed chunks with per-channel message indexes, and on close a summary (schemas, channels,
// statistics, chunk indexes) for indexed readers. A chunk is written, and flushed to the kernel,
// once it is chunk_period_ns old or chunk_bytes big: a writer killed with SIGKILL leaves a file
// that a streaming reader reads up to its last chunk (`teleop bag repair` adds the summary).

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "teleop/bag/recording_writer.h"

namespace teleop::bag {

enum class McapCompression { kNone, kZstd, kLz4 };

struct McapWriterOptions {
  std::string path;  ///< created; an existing file is an error
  McapCompression compression = McapCompression::kZstd;
  /// A chunk is written at most this long (CLOCK_MONOTONIC) after its first message: what a kill
  /// can lose. Half a second keeps that within a second with the recorder's queue in front.
  int64_t chunk_period_ns = 500'000'000;
  /// ... or once its uncompressed messages reach this many bytes.
  size_t chunk_bytes = size_t{4} << 20;
  /// Cap on the file's size in bytes, 0: none. Reaching it is reported like a full disk; the
  /// summary is still written on close.
  int64_t max_bytes = 0;
};

/// One MCAP file being recorded. Every failure throws BagError naming the file.
class McapWriter : public RecordingWriter {
 public:
  /// Creates the file and writes its magic and Header.
  explicit McapWriter(McapWriterOptions options);
  /// close() if not closed; never throws.
  ~McapWriter() override;
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  /// Writes the topic's Schema (once per type: `type` is its name, `schema` its data; a topic
  /// without a schema gets one with the name alone) and its Channel, at once.
  int add_topic(const TopicInfo& topic) override;
  /// log_time is recv_ns, publish_time publish_ns (recv_ns when 0); recv_mono_ns and the writer
  /// are not kept in MCAP.
  void write(const MessageToWrite& message) override;
  void poll() override;
  /// Writes the open chunk, DataEnd, the summary and the footer.
  void close() override;

  const BagStats& stats() const override;
  const std::string& data_path() const override;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace teleop::bag

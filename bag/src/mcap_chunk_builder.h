#pragma once
// One chunk being filled: its Message records uncompressed, each channel's (log_time, offset)
// index, the time range; finished into a compressed Chunk record, its MessageIndex records and
// the ChunkIndex the summary keeps.

#include <cstdint>
#include <map>
#include <vector>

#include "mcap_compression.h"
#include "mcap_records.h"

namespace teleop::bag::mcap {

/// A chunk gone into the file: its index entry, and its messages per channel for the statistics.
struct FinishedChunk {
  ChunkIndexRecord index;
  std::map<uint16_t, uint64_t> message_counts;
};

class ChunkBuilder {
 public:
  void add(const MessageRecord& message);

  bool empty() const { return records_.empty(); }
  size_t uncompressed_bytes() const { return records_.size(); }

  /// Appends the Chunk record and then one MessageIndex record per channel to `out`, which will
  /// be written at file offset `file_offset`; returns the chunk's index entry and starts a new
  /// chunk.
  FinishedChunk finish(Compression compression, uint64_t file_offset, std::vector<uint8_t>& out);

 private:
  std::vector<uint8_t> records_;
  std::vector<uint8_t> compressed_;
  std::map<uint16_t, MessageIndexRecord> indexes_;
  uint64_t start_time_ = 0;
  uint64_t end_time_ = 0;
};

}  // namespace teleop::bag::mcap

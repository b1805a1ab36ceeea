#pragma once
// What an MCAP file's summary section holds, collected while writing: the schemas and channels,
// one ChunkIndex per chunk and the statistics; and the bytes of the summary section, the summary
// offsets, the footer and the closing magic, once the data section is complete.

#include <cstdint>
#include <vector>

#include "mcap_chunk_builder.h"
#include "mcap_records.h"

namespace teleop::bag::mcap {

class SummaryBuilder {
 public:
  void add_schema(const SchemaRecord& schema);
  void add_channel(const ChannelRecord& channel);
  /// A chunk that is in the file: its index, and its messages counted in the statistics.
  void add_chunk(const FinishedChunk& chunk);

  /// The summary (schemas, channels, statistics, chunk indexes), the summary offsets, the footer
  /// with its CRC and the magic, appended to `out`, which starts at file offset `summary_start`
  /// (right after the DataEnd record).
  void finish(uint64_t summary_start, std::vector<uint8_t>& out) const;

  const StatisticsRecord& statistics() const { return statistics_; }

 private:
  std::vector<SchemaRecord> schemas_;
  std::vector<ChannelRecord> channels_;
  std::vector<ChunkIndexRecord> chunks_;
  StatisticsRecord statistics_;
};

}  // namespace teleop::bag::mcap

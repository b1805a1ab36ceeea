#include "mcap_summary.h"

#include <algorithm>

#include "mcap_compression.h"

namespace teleop::bag::mcap {
namespace {

// a group of records of one opcode in the summary, and the SummaryOffset that points at it
template <typename Record>
void append_group(Op op, const std::vector<Record>& records, uint64_t summary_start, std::vector<uint8_t>& out,
                  std::vector<SummaryOffsetRecord>& offsets) {
  if (records.empty()) return;
  RecordEncoder encoder(out);
  const uint64_t start = summary_start + out.size();
  for (const Record& r : records) encode(encoder, r);
  offsets.push_back({op, start, summary_start + out.size() - start});
}

}  // namespace

void SummaryBuilder::add_schema(const SchemaRecord& schema) {
  schemas_.push_back(schema);
  ++statistics_.schema_count;
}

void SummaryBuilder::add_channel(const ChannelRecord& channel) {
  channels_.push_back(channel);
  ++statistics_.channel_count;
}

void SummaryBuilder::add_chunk(const FinishedChunk& chunk) {
  StatisticsRecord& s = statistics_;
  const ChunkIndexRecord& index = chunk.index;
  const bool first = s.message_count == 0;
  s.message_start_time = first ? index.message_start_time : std::min(s.message_start_time, index.message_start_time);
  s.message_end_time = first ? index.message_end_time : std::max(s.message_end_time, index.message_end_time);
  for (const auto& [channel, count] : chunk.message_counts) {
    s.channel_message_counts[channel] += count;
    s.message_count += count;
  }
  chunks_.push_back(index);
  ++s.chunk_count;
}

void SummaryBuilder::finish(uint64_t summary_start, std::vector<uint8_t>& out) const {
  const size_t begin = out.size();
  std::vector<SummaryOffsetRecord> offsets;
  const uint64_t at = summary_start - begin;  // file offset of out[0]
  append_group(Op::kSchema, schemas_, at, out, offsets);
  append_group(Op::kChannel, channels_, at, out, offsets);
  append_group(Op::kStatistics, std::vector<StatisticsRecord>{statistics_}, at, out, offsets);
  append_group(Op::kChunkIndex, chunks_, at, out, offsets);
  const uint64_t summary_offset_start = at + out.size();
  RecordEncoder encoder(out);
  for (const SummaryOffsetRecord& offset : offsets) encode(encoder, offset);
  encode_footer_without_crc(encoder, summary_start, summary_offset_start);
  // the CRC covers the summary, the offsets and the footer up to its own field
  encoder.u32(crc32_of({out.data() + begin, out.size() - begin}));
  encoder.raw(kMagic.data(), kMagic.size());
}

}  // namespace teleop::bag::mcap

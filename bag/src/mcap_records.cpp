#include "mcap_records.h"

namespace teleop::bag::mcap {
namespace {

// A Map<uint16, uint64> (message_index_offsets, channel_message_counts)
void encode_counts(RecordEncoder& out, const std::map<uint16_t, uint64_t>& map) {
  const size_t list = out.begin_list();
  for (const auto& [key, value] : map) {
    out.u16(key);
    out.u64(value);
  }
  out.end_list(list);
}

std::map<uint16_t, uint64_t> decode_counts(RecordDecoder in) {
  std::map<uint16_t, uint64_t> map;
  while (in.remaining() > 0) {
    const uint16_t key = in.u16();
    map[key] = in.u64();
  }
  return map;
}

}  // namespace

void encode_header(RecordEncoder& out) {
  const size_t record = out.begin_record(Op::kHeader);
  out.string(kProfile);
  out.string(kLibrary);
  out.end_record(record);
}

void encode(RecordEncoder& out, const SchemaRecord& r) {
  const size_t record = out.begin_record(Op::kSchema);
  out.u16(r.id);
  out.string(r.name);
  out.string(r.encoding);
  out.string(r.data);  // uint32-prefixed bytes, as a string is
  out.end_record(record);
}

void encode(RecordEncoder& out, const ChannelRecord& r) {
  const size_t record = out.begin_record(Op::kChannel);
  out.u16(r.id);
  out.u16(r.schema_id);
  out.string(r.topic);
  out.string(r.message_encoding);
  const size_t list = out.begin_list();
  for (const auto& [key, value] : r.metadata) {
    out.string(key);
    out.string(value);
  }
  out.end_list(list);
  out.end_record(record);
}

void encode(RecordEncoder& out, const MessageRecord& r) {
  const size_t record = out.begin_record(Op::kMessage);
  out.u16(r.channel_id);
  out.u32(r.sequence);
  out.u64(r.log_time);
  out.u64(r.publish_time);
  out.raw(r.data.data, r.data.size);
  out.end_record(record);
}

void encode(RecordEncoder& out, const ChunkRecord& r) {
  const size_t record = out.begin_record(Op::kChunk);
  out.u64(r.message_start_time);
  out.u64(r.message_end_time);
  out.u64(r.uncompressed_size);
  out.u32(r.uncompressed_crc);
  out.string(r.compression);
  out.u64(r.records.size);
  out.raw(r.records.data, r.records.size);
  out.end_record(record);
}

void encode(RecordEncoder& out, const MessageIndexRecord& r) {
  const size_t record = out.begin_record(Op::kMessageIndex);
  out.u16(r.channel_id);
  const size_t list = out.begin_list();
  for (const auto& [time, offset] : r.entries) {
    out.u64(time);
    out.u64(offset);
  }
  out.end_list(list);
  out.end_record(record);
}

void encode(RecordEncoder& out, const ChunkIndexRecord& r) {
  const size_t record = out.begin_record(Op::kChunkIndex);
  out.u64(r.message_start_time);
  out.u64(r.message_end_time);
  out.u64(r.chunk_start_offset);
  out.u64(r.chunk_length);
  encode_counts(out, r.message_index_offsets);
  out.u64(r.message_index_length);
  out.string(r.compression);
  out.u64(r.compressed_size);
  out.u64(r.uncompressed_size);
  out.end_record(record);
}

void encode(RecordEncoder& out, const StatisticsRecord& r) {
  const size_t record = out.begin_record(Op::kStatistics);
  out.u64(r.message_count);
  out.u16(r.schema_count);
  out.u32(r.channel_count);
  out.u32(r.attachment_count);
  out.u32(r.metadata_count);
  out.u32(r.chunk_count);
  out.u64(r.message_start_time);
  out.u64(r.message_end_time);
  encode_counts(out, r.channel_message_counts);
  out.end_record(record);
}

void encode(RecordEncoder& out, const SummaryOffsetRecord& r) {
  const size_t record = out.begin_record(Op::kSummaryOffset);
  out.u8(static_cast<uint8_t>(r.group_opcode));
  out.u64(r.group_start);
  out.u64(r.group_length);
  out.end_record(record);
}

void encode_data_end(RecordEncoder& out, uint32_t data_section_crc) {
  const size_t record = out.begin_record(Op::kDataEnd);
  out.u32(data_section_crc);
  out.end_record(record);
}

void encode_footer_without_crc(RecordEncoder& out, uint64_t summary_start, uint64_t summary_offset_start) {
  out.u8(static_cast<uint8_t>(Op::kFooter));
  out.u64(8 + 8 + 4);
  out.u64(summary_start);
  out.u64(summary_offset_start);
}

SchemaRecord decode_schema(RecordDecoder in) {
  SchemaRecord r;
  r.id = in.u16();
  r.name = in.string();
  r.encoding = in.string();
  r.data = in.string();
  return r;
}

ChannelRecord decode_channel(RecordDecoder in) {
  ChannelRecord r;
  r.id = in.u16();
  r.schema_id = in.u16();
  r.topic = in.string();
  r.message_encoding = in.string();
  RecordDecoder map = in.list();
  while (map.remaining() > 0) {
    std::string key = map.string();
    r.metadata[key] = map.string();
  }
  return r;
}

MessageRecord decode_message(RecordDecoder in) {
  MessageRecord r;
  r.channel_id = in.u16();
  r.sequence = in.u32();
  r.log_time = in.u64();
  r.publish_time = in.u64();
  r.data = in.rest();
  return r;
}

ChunkRecord decode_chunk(RecordDecoder in) {
  ChunkRecord r;
  r.message_start_time = in.u64();
  r.message_end_time = in.u64();
  r.uncompressed_size = in.u64();
  r.uncompressed_crc = in.u32();
  r.compression = in.string();
  r.records = in.take(in.u64());
  return r;
}

MessageIndexRecord decode_message_index(RecordDecoder in) {
  MessageIndexRecord r;
  r.channel_id = in.u16();
  RecordDecoder list = in.list();
  while (list.remaining() > 0) {
    const uint64_t time = list.u64();
    r.entries.emplace_back(time, list.u64());
  }
  return r;
}

ChunkIndexRecord decode_chunk_index(RecordDecoder in) {
  ChunkIndexRecord r;
  r.message_start_time = in.u64();
  r.message_end_time = in.u64();
  r.chunk_start_offset = in.u64();
  r.chunk_length = in.u64();
  r.message_index_offsets = decode_counts(in.list());
  r.message_index_length = in.u64();
  r.compression = in.string();
  r.compressed_size = in.u64();
  r.uncompressed_size = in.u64();
  return r;
}

StatisticsRecord decode_statistics(RecordDecoder in) {
  StatisticsRecord r;
  r.message_count = in.u64();
  r.schema_count = in.u16();
  r.channel_count = in.u32();
  r.attachment_count = in.u32();
  r.metadata_count = in.u32();
  r.chunk_count = in.u32();
  r.message_start_time = in.u64();
  r.message_end_time = in.u64();
  r.channel_message_counts = decode_counts(in.list());
  return r;
}

FooterRecord decode_footer(RecordDecoder in) {
  FooterRecord r;
  r.summary_start = in.u64();
  r.summary_offset_start = in.u64();
  r.summary_crc = in.u32();
  return r;
}

}  // namespace teleop::bag::mcap

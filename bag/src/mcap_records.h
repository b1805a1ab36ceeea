#pragma once
// The MCAP records teleop writes and reads (mcap.dev/spec), as structs, with their encoding into
// a buffer and their decoding from a record's content. A Message's data and a Chunk's records
// stay views into the bytes they were decoded from.

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "record_decoder.h"
#include "record_encoder.h"

namespace teleop::bag::mcap {

struct SchemaRecord {
  uint16_t id = 0;  ///< 0 is reserved (no schema)
  std::string name;
  std::string encoding;
  std::string data;
};

struct ChannelRecord {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
  std::map<std::string, std::string> metadata;
};

struct MessageRecord {
  uint16_t channel_id = 0;
  uint32_t sequence = 0;
  uint64_t log_time = 0;
  uint64_t publish_time = 0;
  ByteSpan data;
};

struct ChunkRecord {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t uncompressed_size = 0;
  uint32_t uncompressed_crc = 0;  ///< 0: not computed
  std::string compression;        ///< "", "zstd" or "lz4"
  ByteSpan records;               ///< compressed
};

/// One channel's messages in a chunk: (log_time, offset into the uncompressed records).
struct MessageIndexRecord {
  uint16_t channel_id = 0;
  std::vector<std::pair<uint64_t, uint64_t>> entries;
};

struct ChunkIndexRecord {
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  uint64_t chunk_start_offset = 0;
  uint64_t chunk_length = 0;  ///< the whole Chunk record, opcode and length included
  std::map<uint16_t, uint64_t> message_index_offsets;
  uint64_t message_index_length = 0;
  std::string compression;
  uint64_t compressed_size = 0;
  uint64_t uncompressed_size = 0;
};

struct StatisticsRecord {
  uint64_t message_count = 0;
  uint16_t schema_count = 0;
  uint32_t channel_count = 0;
  uint32_t attachment_count = 0;
  uint32_t metadata_count = 0;
  uint32_t chunk_count = 0;
  uint64_t message_start_time = 0;
  uint64_t message_end_time = 0;
  std::map<uint16_t, uint64_t> channel_message_counts;
};

struct SummaryOffsetRecord {
  Op group_opcode = Op::kSchema;
  uint64_t group_start = 0;
  uint64_t group_length = 0;
};

struct FooterRecord {
  uint64_t summary_start = 0;  ///< 0: no summary
  uint64_t summary_offset_start = 0;
  uint32_t summary_crc = 0;
};

void encode_header(RecordEncoder& out);
void encode(RecordEncoder& out, const SchemaRecord& r);
void encode(RecordEncoder& out, const ChannelRecord& r);
void encode(RecordEncoder& out, const MessageRecord& r);
/// The Chunk record around `compressed` records.
void encode(RecordEncoder& out, const ChunkRecord& r);
void encode(RecordEncoder& out, const MessageIndexRecord& r);
void encode(RecordEncoder& out, const ChunkIndexRecord& r);
void encode(RecordEncoder& out, const StatisticsRecord& r);
void encode(RecordEncoder& out, const SummaryOffsetRecord& r);
void encode_data_end(RecordEncoder& out, uint32_t data_section_crc);
/// Everything of the Footer record but the CRC, which covers these bytes too.
void encode_footer_without_crc(RecordEncoder& out, uint64_t summary_start, uint64_t summary_offset_start);

// Each decodes a record's content (after opcode and length); a short or corrupt one throws.
SchemaRecord decode_schema(RecordDecoder in);
ChannelRecord decode_channel(RecordDecoder in);
MessageRecord decode_message(RecordDecoder in);
ChunkRecord decode_chunk(RecordDecoder in);
MessageIndexRecord decode_message_index(RecordDecoder in);
ChunkIndexRecord decode_chunk_index(RecordDecoder in);
StatisticsRecord decode_statistics(RecordDecoder in);
FooterRecord decode_footer(RecordDecoder in);

}  // namespace teleop::bag::mcap

// Reading an MCAP file's catalogue through its summary: footer, summary (schemas, channels,
// statistics, chunk indexes) and each chunk's message indexes, without decompressing a chunk.
#include <string>

#include "mcap_catalogue.h"
#include "mcap_compression.h"
#include "mcap_format.h"

namespace teleop::bag::mcap {
namespace {

// the footer and where the summary is; false when the file has no (sound) footer
bool read_footer(ByteSpan bytes, FooterRecord& footer, uint64_t& footer_at, std::string& why) {
  const size_t tail = kFooterRecordBytes + kMagic.size();
  if (bytes.size < kMagic.size() + tail) return (why = "no footer"), false;
  footer_at = bytes.size - tail;
  const uint8_t* magic = bytes.data + bytes.size - kMagic.size();
  if (!std::equal(kMagic.begin(), kMagic.end(), magic)) return (why = "no closing magic"), false;
  RecordDecoder in({bytes.data + footer_at, kFooterRecordBytes}, "footer");
  if (static_cast<Op>(in.u8()) != Op::kFooter || in.u64() != kFooterRecordBytes - kRecordPrefixBytes) {
    return (why = "no footer before the closing magic"), false;
  }
  footer = decode_footer(in);
  if (footer.summary_start == 0) return (why = "no summary"), false;
  if (footer.summary_start < kMagic.size() || footer.summary_start > footer_at) {
    return (why = "the footer points outside the file"), false;
  }
  return true;
}

bool summary_crc_matches(ByteSpan bytes, const FooterRecord& footer, uint64_t footer_at) {
  if (footer.summary_crc == 0) return true;  // not computed by its writer
  const uint64_t end = footer_at + kFooterRecordBytes - 4;
  return crc32_of({bytes.data + footer.summary_start, static_cast<size_t>(end - footer.summary_start)}) ==
         footer.summary_crc;
}

// one chunk's messages, from its message index records
void add_indexed_messages(const MappedFile& file, const ChunkIndexRecord& index, uint32_t chunk_no,
                          McapCatalogue& out) {
  RecordDecoder whole(file.bytes(), file.path());
  for (const auto& [channel, offset] : index.message_index_offsets) {
    const std::string what = file.path() + ": message index at byte " + std::to_string(offset);
    RecordDecoder at = whole;
    at.take(offset);
    if (static_cast<Op>(at.u8()) != Op::kMessageIndex) throw BagError(what + ": not a MessageIndex record");
    const MessageIndexRecord record = decode_message_index(RecordDecoder(at.take(at.u64()), what));
    for (const auto& [time, message_offset] : record.entries) {
      out.messages.push_back({time, message_offset, chunk_no, record.channel_id});
    }
  }
}

}  // namespace

bool index_catalogue(const MappedFile& file, McapCatalogue& out, std::string& why) {
  const ByteSpan bytes = file.bytes();
  FooterRecord footer;
  uint64_t footer_at = 0;
  if (!read_footer(bytes, footer, footer_at, why)) return false;
  if (!summary_crc_matches(bytes, footer, footer_at)) return (why = "the summary does not match its CRC"), false;
  const ByteSpan summary{bytes.data + footer.summary_start, static_cast<size_t>(footer_at - footer.summary_start)};
  const std::string what = file.path() + ": summary at byte " + std::to_string(footer.summary_start);
  std::vector<ChunkIndexRecord> chunks;
  uint64_t counted = 0;
  for_each_record(summary, what, [&](Op op, const RecordDecoder& in, size_t) {
    add_definition(op, in, out);
    if (op == Op::kChunkIndex) {
      chunks.push_back(decode_chunk_index(in));
    } else if (op == Op::kStatistics) {
      counted = decode_statistics(in).message_count;
    }
  });
  for (const ChunkIndexRecord& chunk : chunks) {
    out.compressions.insert(chunk.compression);
    const auto chunk_no = static_cast<uint32_t>(out.chunks.size());
    out.chunks.push_back({chunk.chunk_start_offset, chunk.chunk_length});
    add_indexed_messages(file, chunk, chunk_no, out);
  }
  // messages outside chunks, or chunks without message indexes, are not in the index
  if (out.messages.size() != counted) return (why = "its message indexes do not cover every message"), false;
  out.indexed = true;
  return true;
}

McapCatalogue read_catalogue(const MappedFile& file) {
  McapCatalogue indexed;
  std::string why;
  if (index_catalogue(file, indexed, why)) return indexed;
  McapCatalogue streamed = stream_catalogue(file);
  if (why != "no summary" || !streamed.warning.empty()) {
    const std::string repair = "`teleop bag repair " + file.path() + "` writes the summary";
    streamed.warning = (streamed.warning.empty() ? "" : streamed.warning + "; ") + why + ": streamed (" + repair + ")";
  }
  return streamed;
}

}  // namespace teleop::bag::mcap

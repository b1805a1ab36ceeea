// Reading an MCAP file's catalogue by streaming through its data section, record by record, up
// to the summary or to the last complete record of a file whose writer was killed.
#include <string>

#include "mcap_catalogue.h"
#include "mcap_format.h"

namespace teleop::bag::mcap {
namespace {

// the messages (and any schemas or channels) inside one chunk
void scan_chunk(const MappedFile& file, const ChunkRef& ref, McapCatalogue& out, std::vector<uint8_t>& buffer) {
  const auto chunk_no = static_cast<uint32_t>(out.chunks.size());
  out.chunks.push_back(ref);
  const ByteSpan records = chunk_records(file, ref, buffer);
  const std::string what = file.path() + ": chunk at byte " + std::to_string(ref.offset);
  for_each_record(records, what, [&](Op op, const RecordDecoder& in, size_t at) {
    if (op == Op::kMessage) {
      const MessageRecord m = decode_message(in);
      out.messages.push_back({m.log_time, at, chunk_no, m.channel_id});
    } else {
      add_definition(op, in, out);
    }
  });
}

std::string chunk_compression(const MappedFile& file, const ChunkRef& ref) {
  RecordDecoder in(file.bytes(), file.path());
  in.take(ref.offset + kRecordPrefixBytes);
  return decode_chunk(RecordDecoder(in.take(ref.length - kRecordPrefixBytes), file.path())).compression;
}

}  // namespace

void add_definition(Op op, const RecordDecoder& in, McapCatalogue& out) {
  if (op == Op::kSchema) {
    SchemaRecord schema = decode_schema(in);
    out.schemas[schema.id] = std::move(schema);
  } else if (op == Op::kChannel) {
    ChannelRecord channel = decode_channel(in);
    out.channels[channel.id] = std::move(channel);
  }
}

McapCatalogue stream_catalogue(const MappedFile& file) {
  McapCatalogue out;
  const ByteSpan bytes = file.bytes();
  std::vector<uint8_t> buffer;
  uint64_t at = kMagic.size();
  bool ended = false;
  while (!ended) {
    const uint64_t left = bytes.size - at;
    uint64_t length = 0;
    if (left >= kRecordPrefixBytes) {
      RecordDecoder prefix({bytes.data + at + 1, 8}, file.path());
      length = prefix.u64();
    }
    if (left < kRecordPrefixBytes || length > left - kRecordPrefixBytes) {
      out.warning = "the file ends " + std::string(left == 0 ? "after" : "inside") + " a record at byte " +
                    std::to_string(at) + " (the recorder was killed?): read up to its last complete chunk";
      break;
    }
    const auto op = static_cast<Op>(bytes.data[at]);
    const ByteSpan content{bytes.data + at + kRecordPrefixBytes, static_cast<size_t>(length)};
    const RecordDecoder in(content, file.path() + ": record at byte " + std::to_string(at));
    if (op == Op::kChunk) {
      const ChunkRef ref{at, kRecordPrefixBytes + length};
      out.compressions.insert(chunk_compression(file, ref));
      scan_chunk(file, ref, out, buffer);
    } else if (op == Op::kMessage) {
      const MessageRecord m = decode_message(in);
      out.messages.push_back({m.log_time, at, MessageRef::kUnchunked, m.channel_id});
    } else {
      add_definition(op, in, out);
    }
    ended = op == Op::kDataEnd || op == Op::kFooter;
    at += kRecordPrefixBytes + length;
  }
  return out;
}

}  // namespace teleop::bag::mcap

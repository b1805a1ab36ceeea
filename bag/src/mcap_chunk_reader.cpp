// Opening one chunk of an MCAP file: its record decoded and its records decompressed.
#include "mcap_catalogue.h"
#include "mcap_compression.h"

namespace teleop::bag::mcap {

ByteSpan chunk_records(const MappedFile& file, const ChunkRef& ref, std::vector<uint8_t>& buffer) {
  const std::string what = file.path() + ": chunk at byte " + std::to_string(ref.offset);
  RecordDecoder whole(file.bytes(), what);
  whole.take(ref.offset);
  RecordDecoder record(whole.take(ref.length), what);
  if (static_cast<Op>(record.u8()) != Op::kChunk) throw BagError(what + ": not a Chunk record");
  const ChunkRecord chunk = decode_chunk(RecordDecoder(record.take(record.u64()), what));
  decompress(compression_named(chunk.compression, what), chunk.records, chunk.uncompressed_size, buffer, what);
  const ByteSpan records{buffer.data(), buffer.size()};
  if (chunk.uncompressed_crc != 0 && crc32_of(records) != chunk.uncompressed_crc) {
    throw BagError(what + ": corrupt (its records do not match their CRC)");
  }
  return records;
}

}  // namespace teleop::bag::mcap

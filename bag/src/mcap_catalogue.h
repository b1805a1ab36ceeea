#pragma once
// What an MCAP reader knows of a file before reading its messages: schemas, channels, chunks,
// and where each message is. Built from the summary and the message indexes when the file has
// them (indexed), else by streaming through the data section up to the last complete record
// (a recorder killed with SIGKILL leaves such a file).

#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "mapped_file.h"
#include "mcap_records.h"

namespace teleop::bag::mcap {

/// A chunk of the file: its whole record.
struct ChunkRef {
  uint64_t offset = 0;
  uint64_t length = 0;
};

/// Where one message is.
struct MessageRef {
  static constexpr uint32_t kUnchunked = std::numeric_limits<uint32_t>::max();
  uint64_t log_time = 0;
  uint64_t offset = 0;  ///< of its record: in the uncompressed chunk, or in the file when unchunked
  uint32_t chunk = kUnchunked;
  uint16_t channel = 0;
};

struct McapCatalogue {
  std::map<uint16_t, SchemaRecord> schemas;
  std::map<uint16_t, ChannelRecord> channels;
  std::vector<ChunkRef> chunks;
  std::vector<MessageRef> messages;  ///< in file order
  std::set<std::string> compressions;
  bool indexed = false;  ///< read through the summary
  std::string warning;   ///< what the reader noticed but could read anyway
};

/// The file's catalogue: through its summary when it has a sound one, else streamed. Throws
/// BagError naming the file and the place when a complete record is corrupt.
McapCatalogue read_catalogue(const MappedFile& file);

/// Streams the data section up to DataEnd, or to the last complete record of a cut file.
McapCatalogue stream_catalogue(const MappedFile& file);
/// Through the summary; false (and `why` says what is wrong) when there is no sound one.
bool index_catalogue(const MappedFile& file, McapCatalogue& out, std::string& why);

/// A Schema or Channel record into the catalogue (a later one of the same id replaces it); any
/// other record is ignored.
void add_definition(Op op, const RecordDecoder& in, McapCatalogue& out);

/// The uncompressed records of the chunk whose record is at `ref`, into `buffer` (CRC checked
/// when the chunk has one).
ByteSpan chunk_records(const MappedFile& file, const ChunkRef& ref, std::vector<uint8_t>& buffer);

/// Each record in `bytes` as (opcode, its content decoder, its offset in `bytes`); a record
/// running past the end throws BagError named `what`.
template <typename Visit>
void for_each_record(ByteSpan bytes, const std::string& what, Visit&& visit) {
  RecordDecoder in(bytes, what);
  while (in.remaining() > 0) {
    const size_t at = in.position();
    const auto op = static_cast<Op>(in.u8());
    const ByteSpan content = in.take(in.u64());
    visit(op, RecordDecoder(content, what + ": record at offset " + std::to_string(at)), at);
  }
}

}  // namespace teleop::bag::mcap

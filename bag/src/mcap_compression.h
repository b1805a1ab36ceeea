#pragma once
// A chunk's records compressed and back: zstd (one frame), lz4 (the LZ4 frame format), or none,
// named as MCAP names them ("zstd", "lz4", ""). On Debian's libzstd and liblz4.

#include <cstdint>
#include <string>
#include <vector>

#include "record_decoder.h"
#include "teleop/bag/mcap_writer.h"

namespace teleop::bag::mcap {

using Compression = McapCompression;

/// MCAP's name of it: "", "zstd", "lz4".
const char* compression_name(Compression c);
/// The compression of an MCAP name; throws BagError for a name we cannot read, naming `what`.
Compression compression_named(const std::string& name, const std::string& what);

/// `in` compressed into `out` (replaced).
void compress(Compression c, ByteSpan in, std::vector<uint8_t>& out);
/// `in` decompressed into `out` (replaced), which must come to exactly `size` bytes: anything
/// else (a corrupt frame, a wrong size) throws BagError naming `what`.
void decompress(Compression c, ByteSpan in, uint64_t size, std::vector<uint8_t>& out, const std::string& what);

/// CRC-32 (ISO-HDLC, zlib's) of the bytes, continuing `crc` (0 to start): MCAP's CRCs.
uint32_t crc32_of(ByteSpan bytes, uint32_t crc = 0);

}  // namespace teleop::bag::mcap

#pragma once
// Reading MCAP's primitive types from bytes that may be truncated or corrupt: every read is
// bounds-checked and a short one throws BagError naming the file, the record and the offset.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>

#include "teleop/bag/bag_error.h"

namespace teleop::bag::mcap {

/// Contiguous bytes: a record's content, a decompressed chunk, a whole file.
struct ByteSpan {
  const uint8_t* data = nullptr;
  size_t size = 0;
};

class RecordDecoder {
 public:
  /// `what` names the bytes in errors, e.g. "/data/run1.mcap: Chunk at byte 4096".
  RecordDecoder(ByteSpan bytes, std::string what) : bytes_(bytes), what_(std::move(what)) {}

  uint8_t u8() { return static_cast<uint8_t>(little_endian(1)); }
  uint16_t u16() { return static_cast<uint16_t>(little_endian(2)); }
  uint32_t u32() { return static_cast<uint32_t>(little_endian(4)); }
  uint64_t u64() { return little_endian(8); }
  std::string string();
  /// `size` bytes in place.
  ByteSpan take(uint64_t size);
  /// A uint32-length-prefixed Map or Array, as a decoder of its own.
  RecordDecoder list();
  /// Whatever is left (a Message's data).
  ByteSpan rest() { return take(remaining()); }

  size_t remaining() const { return bytes_.size - at_; }
  size_t position() const { return at_; }
  const std::string& what() const { return what_; }

 private:
  uint64_t little_endian(int bytes);
  void need(uint64_t bytes, const char* field) const;

  ByteSpan bytes_;
  size_t at_ = 0;
  std::string what_;
};

}  // namespace teleop::bag::mcap

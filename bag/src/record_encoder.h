#pragma once
// Appending MCAP's primitive types to a byte buffer: little-endian integers, uint32-prefixed
// strings and byte arrays, and records whose length is filled in once their content is written.

#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

#include "mcap_format.h"

namespace teleop::bag::mcap {

class RecordEncoder {
 public:
  explicit RecordEncoder(std::vector<uint8_t>& out) : out_(out) {}

  void u8(uint8_t v) { out_.push_back(v); }
  void u16(uint16_t v) { little_endian(v, 2); }
  void u32(uint32_t v) { little_endian(v, 4); }
  void u64(uint64_t v) { little_endian(v, 8); }
  /// A uint32 byte length, then the bytes (MCAP's String and the Schema's data).
  void string(std::string_view s);
  /// The bytes alone (a Message's data runs to the end of its record).
  void raw(const uint8_t* data, size_t size);

  /// Starts a record: its opcode and a length to be patched; returns where the length sits.
  size_t begin_record(Op op);
  /// Patches the record's content length (everything appended since begin_record).
  void end_record(size_t length_at);
  /// Starts a uint32-length-prefixed Map or Array; returns where the length sits.
  size_t begin_list();
  void end_list(size_t length_at);

  size_t size() const { return out_.size(); }

 private:
  void little_endian(uint64_t v, int bytes);
  void patch(size_t at, uint64_t v, int bytes);

  std::vector<uint8_t>& out_;
};

}  // namespace teleop::bag::mcap

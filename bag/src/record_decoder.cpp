#include "record_decoder.h"

namespace teleop::bag::mcap {

void RecordDecoder::need(uint64_t bytes, const char* field) const {
  if (bytes > remaining()) {
    throw BagError(what_ + ": truncated or corrupt (" + field + " of " + std::to_string(bytes) + " bytes at offset " +
                   std::to_string(at_) + ", " + std::to_string(remaining()) + " left)");
  }
}

uint64_t RecordDecoder::little_endian(int bytes) {
  need(static_cast<uint64_t>(bytes), "an integer");
  uint64_t v = 0;
  for (int i = 0; i < bytes; ++i) v |= static_cast<uint64_t>(bytes_.data[at_ + static_cast<size_t>(i)]) << (8 * i);
  at_ += static_cast<size_t>(bytes);
  return v;
}

std::string RecordDecoder::string() {
  const ByteSpan s = take(u32());
  return {reinterpret_cast<const char*>(s.data), s.size};
}

ByteSpan RecordDecoder::take(uint64_t size) {
  need(size, "a field");
  const ByteSpan span{bytes_.data + at_, static_cast<size_t>(size)};
  at_ += static_cast<size_t>(size);
  return span;
}

RecordDecoder RecordDecoder::list() { return RecordDecoder(take(u32()), what_); }

}  // namespace teleop::bag::mcap

#include "record_encoder.h"

namespace teleop::bag::mcap {

void RecordEncoder::little_endian(uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out_.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

void RecordEncoder::patch(size_t at, uint64_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) out_[at + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (8 * i));
}

void RecordEncoder::string(std::string_view s) {
  u32(static_cast<uint32_t>(s.size()));
  raw(reinterpret_cast<const uint8_t*>(s.data()), s.size());
}

void RecordEncoder::raw(const uint8_t* data, size_t size) {
  if (size > 0) out_.insert(out_.end(), data, data + size);
}

size_t RecordEncoder::begin_record(Op op) {
  u8(static_cast<uint8_t>(op));
  const size_t at = out_.size();
  u64(0);
  return at;
}

void RecordEncoder::end_record(size_t length_at) { patch(length_at, out_.size() - length_at - 8, 8); }

size_t RecordEncoder::begin_list() {
  const size_t at = out_.size();
  u32(0);
  return at;
}

void RecordEncoder::end_list(size_t length_at) { patch(length_at, out_.size() - length_at - 4, 4); }

}  // namespace teleop::bag::mcap

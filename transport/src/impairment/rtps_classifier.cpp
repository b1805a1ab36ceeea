#include "rtps_classifier.h"

#include <cstring>

namespace teleop::transport::impairment {
namespace {

// RTPS 2.x: 20-byte header ("RTPS", version, vendor, GUID prefix), then submessages of
// id (1), flags (1, bit 0 = little endian), octetsToNextHeader (2), body
constexpr uint32_t kHeaderSize = 20;
constexpr uint32_t kSubmessageHeaderSize = 4;

// submessages whose body starts with readerId, writerId (DATA and DATA_FRAG after 4 more bytes)
constexpr uint8_t kAckNack = 0x06;
constexpr uint8_t kHeartbeat = 0x07;
constexpr uint8_t kGap = 0x08;
constexpr uint8_t kNackFrag = 0x12;
constexpr uint8_t kHeartbeatFrag = 0x13;
constexpr uint8_t kData = 0x15;
constexpr uint8_t kDataFrag = 0x16;

// built-in entity ids of SPDP (key 0x000100) and SEDP (0x000003, 0x000004) endpoints; the
// last byte (kind) is 0xc2/0xc7 for writers/readers
bool is_discovery_entity(const uint8_t* id) {
  if ((id[3] & 0xc0) != 0xc0) return false;
  const uint32_t key = (uint32_t{id[0]} << 16) | (uint32_t{id[1]} << 8) | id[2];
  return key == 0x000100 || key == 0x000003 || key == 0x000004;
}

}  // namespace

bool is_discovery_message(const uint8_t* data, uint32_t size) {
  if (size < kHeaderSize || std::memcmp(data, "RTPS", 4) != 0) return false;
  uint32_t offset = kHeaderSize;
  while (offset + kSubmessageHeaderSize <= size) {
    const uint8_t id = data[offset];
    const bool little_endian = (data[offset + 1] & 0x01) != 0;
    const uint32_t length = little_endian ? (uint32_t{data[offset + 2]} | (uint32_t{data[offset + 3]} << 8))
                                          : ((uint32_t{data[offset + 2]} << 8) | data[offset + 3]);
    const uint32_t body = offset + kSubmessageHeaderSize;
    uint32_t ids = 0;
    switch (id) {
      case kAckNack:
      case kHeartbeat:
      case kGap:
      case kNackFrag:
      case kHeartbeatFrag: ids = body; break;
      case kData:
      case kDataFrag: ids = body + 4; break;  // extraFlags, octetsToInlineQos first
      default: break;
    }
    if (ids != 0 && ids + 8 <= size && (is_discovery_entity(data + ids) || is_discovery_entity(data + ids + 4))) {
      return true;
    }
    // length 0 means "to the end of the message" (last submessage)
    if (length == 0) break;
    offset = body + length;
  }
  return false;
}

}  // namespace teleop::transport::impairment

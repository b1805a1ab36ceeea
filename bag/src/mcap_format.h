#pragma once
// The constants of the MCAP container format (mcap.dev/spec, major version 0): the magic, the
// record opcodes, and the well-known names teleop writes (the ROS 2 profile). docs/recording.md.

#include <array>
#include <cstdint>

namespace teleop::bag::mcap {

/// Begins and ends every MCAP file: 0x89 "MCAP" '0' "\r\n".
inline constexpr std::array<uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};

/// A record's first byte.
enum class Op : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

/// A record's opcode byte and its uint64 content length.
inline constexpr size_t kRecordPrefixBytes = 9;
/// The footer record: prefix, summary_start, summary_offset_start, summary_crc.
inline constexpr size_t kFooterRecordBytes = kRecordPrefixBytes + 8 + 8 + 4;

inline constexpr const char* kProfile = "ros2";
inline constexpr const char* kLibrary = "teleop";
inline constexpr const char* kSchemaEncoding = "ros2msg";
inline constexpr const char* kMessageEncoding = "cdr";
/// The channel metadata key rosbag2 keeps a topic's QoS under.
inline constexpr const char* kQosMetadataKey = "offered_qos_profiles";

}  // namespace teleop::bag::mcap

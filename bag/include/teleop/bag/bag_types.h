#pragma once
// What a recording holds: topics, and messages as the opaque CDR bytes a DDS writer put on the
// wire (from the 4-byte encapsulation header on), with when and from which writer they came.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace teleop::bag {

/// A DDS writer's GUID: the 12-byte participant prefix and the 4-byte entity id.
using WriterGuid = std::array<uint8_t, 16>;

/// A recorded topic. Its id (BagWriter::add_topic, BagReader::topic_id) counts from 1 in the
/// order the topics were added.
struct TopicInfo {
  std::string name;         ///< "teleop/leader/joint_command"
  std::string type;         ///< ROS-style type name, e.g. "teleop/msg/JointCommand"
  std::string qos_profile;  ///< offered QoS as YAML text (rosbag2's offered_qos_profiles), may be ""
  /// The type's definition in `schema_encoding` ("ros2msg": the .msg text with its dependencies
  /// appended, as ROS 2 records it in MCAP); "" when unknown. A sqlite3 bag keeps none.
  std::string schema;
  std::string schema_encoding;
};

/// One recorded message.
struct BagMessage {
  int topic_id = 0;
  int64_t recv_ns = 0;        ///< receive time, CLOCK_REALTIME, ns since the Unix epoch
  int64_t recv_mono_ns = 0;   ///< receive time, CLOCK_MONOTONIC of the recording host (0: unknown)
  int64_t publish_ns = 0;     ///< when the writer published it (its header stamp), CLOCK_REALTIME (0: unknown)
  WriterGuid writer{};        ///< all zero: unknown (a bag not recorded by teleop, an MCAP recording)
  std::vector<uint8_t> data;  ///< the serialized CDR payload, encapsulation header included
};

/// The receive time a replay paces messages by: the monotonic one when it was recorded (immune
/// to clock steps), else the realtime one (MCAP recordings, plain rosbag2 bags).
inline int64_t pacing_time_ns(const BagMessage& m) { return m.recv_mono_ns != 0 ? m.recv_mono_ns : m.recv_ns; }

/// A message handed to a RecordingWriter: its times, writer and serialized payload.
struct MessageToWrite {
  int topic_id = 0;
  int64_t recv_ns = 0;       ///< as BagMessage
  int64_t recv_mono_ns = 0;  ///< as BagMessage
  int64_t publish_ns = 0;    ///< as BagMessage
  WriterGuid writer{};
  const uint8_t* data = nullptr;
  size_t size = 0;
};

/// What a BagWriter has appended so far (committed or in the open transaction).
struct BagStats {
  uint64_t messages = 0;
  uint64_t bytes = 0;    ///< payload bytes
  uint64_t commits = 0;  ///< transactions committed
  int64_t first_ns = 0;  ///< smallest recv_ns (0 before the first message)
  int64_t last_ns = 0;   ///< largest recv_ns
};

}  // namespace teleop::bag

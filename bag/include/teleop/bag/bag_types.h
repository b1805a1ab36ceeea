#pragma once
// What a recording holds: topics, and messages as the opaque CDR bytes a DDS writer put on the
// wire (from the 4-byte encapsulation header on), with when and from which writer they came.

#include <array>
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
};

/// One recorded message.
struct BagMessage {
  int topic_id = 0;
  int64_t recv_ns = 0;        ///< receive time, CLOCK_REALTIME, ns since the Unix epoch
  int64_t recv_mono_ns = 0;   ///< receive time, CLOCK_MONOTONIC of the recording host (0: unknown)
  WriterGuid writer{};        ///< all zero: unknown (a bag not recorded by teleop)
  std::vector<uint8_t> data;  ///< the serialized CDR payload, encapsulation header included
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

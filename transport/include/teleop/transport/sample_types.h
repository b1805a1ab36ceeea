#pragma once
// The catalogue of teleop sample types, by name: what lets a tool handle a topic it knows only
// from discovery (its type name) without a type of its own for it.

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "teleop/transport/qos.h"

namespace teleop::transport {

struct SampleType {
  /// The DDS type name the writers announce, e.g. "teleop::msg::JointState".
  std::string dds_name;
  /// The ROS 2 style name recordings store, e.g. "teleop/msg/JointState".
  std::string bag_name;
  /// The DDS type name under ROS 2 naming (naming.h), e.g. "teleop_msgs::msg::dds_::JointState_".
  std::string ros2_name;
  /// The largest serialized size, CDR encapsulation included [bytes].
  uint32_t max_serialized_size = 0;
};

/// Every sample type of idl/.
const std::vector<SampleType>& sample_types();
/// The type of that DDS name (plain or ROS 2 naming) or ROS 2 style name; null when it is not a
/// teleop type.
const SampleType* find_sample_type(std::string_view name);

/// A topic of topics.h with a fixed name: what a recorder can subscribe to before any writer
/// is there (the per-object and per-pair families are found by discovery).
struct KnownTopic {
  std::string name;
  const SampleType* type;
  QosPreset qos;
};
const std::vector<KnownTopic>& known_topics();

/// The QoS preset of a topic by its name (topics.h, including the per-object and per-pair topic
/// families); kStream for names it does not know.
QosPreset topic_qos(std::string_view topic);

}  // namespace teleop::transport

#include "teleop/transport/naming.h"

namespace teleop::transport {
namespace {

constexpr std::string_view kTeleopModule = "teleop::msg::";

}  // namespace

std::string dds_topic_name(Naming naming, std::string_view topic) {
  std::string name;
  if (naming == Naming::kRos2) name = kRos2TopicPrefix;
  name += topic;
  return name;
}

std::optional<std::string> teleop_topic_name(Naming naming, std::string_view dds_topic) {
  if (naming == Naming::kPlain) return std::string(dds_topic);
  if (!dds_topic.starts_with(kRos2TopicPrefix)) return std::nullopt;
  return std::string(dds_topic.substr(kRos2TopicPrefix.size()));
}

std::string ros2_type_name(std::string_view teleop_type) {
  // rosidl names the DDS type of package P's message M "P::msg::dds_::M_"; teleop's package is
  // teleop_msgs, its messages named as the IDL structs
  std::string_view leaf = teleop_type;
  if (leaf.starts_with(kTeleopModule)) leaf.remove_prefix(kTeleopModule.size());
  std::string name = "teleop_msgs::msg::dds_::";
  name += leaf;
  name += '_';
  return name;
}

std::string dds_type_name(Naming naming, std::string_view teleop_type) {
  return naming == Naming::kRos2 ? ros2_type_name(teleop_type) : std::string(teleop_type);
}

}  // namespace teleop::transport

#pragma once
// How teleop's topics and types are named on the wire. `plain`: as in topics.h and idl/
// (topic "teleop/follower/joint_state", type "teleop::msg::JointState"). `ros2`: ROS 2's DDS
// conventions, so that a ROS 2 system sees and reads the topics with the teleop_msgs package
// (idl/ros2/teleop_msgs): topic "rt/teleop/follower/joint_state", type
// "teleop_msgs::msg::dds_::JointState_". Everything above the participant (NodeStatus flows,
// tools, recordings) keeps the plain topic names; only the DDS entities are renamed.

#include <optional>
#include <string>
#include <string_view>

namespace teleop::transport {

enum class Naming { kPlain, kRos2 };

/// The prefix ROS 2 gives the DDS topic of a ROS topic.
inline constexpr std::string_view kRos2TopicPrefix = "rt/";

/// The DDS topic of a teleop topic.
std::string dds_topic_name(Naming naming, std::string_view topic);

/// The teleop topic of a DDS topic found by discovery; nullopt when the DDS topic is not one of
/// this naming's (under `ros2`, ROS 2's services and other non-`rt/` topics).
std::optional<std::string> teleop_topic_name(Naming naming, std::string_view dds_topic);

/// The DDS type name of a teleop type under `naming`: "teleop::msg::JointState" stays as it is
/// (plain) or becomes "teleop_msgs::msg::dds_::JointState_" (ros2).
std::string dds_type_name(Naming naming, std::string_view teleop_type);

/// The ROS 2 DDS type name of a teleop type ("teleop::msg::X" -> "teleop_msgs::msg::dds_::X_").
std::string ros2_type_name(std::string_view teleop_type);

}  // namespace teleop::transport

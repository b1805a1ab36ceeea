#pragma once
// What a recording says about a teleop topic: in MCAP its type as the ROS 2 message
// ("teleop_msgs/msg/JointState") with the ros2msg schema ROS 2 would embed, in a sqlite3 bag
// the ROS-style name ("teleop/msg/JointState") alone (docs/recording.md).

#include <string>

#include "teleop/bag/bag_types.h"
#include "teleop/transport/sample_types.h"

namespace teleop::tools {

enum class RecordingFormat { kMcap, kSqlite3 };

/// The ROS 2 message of a teleop type, "teleop_msgs/msg/JointState" (transport's
/// find_sample_type finds the type by it too).
std::string ros2_msg_name(const transport::SampleType& type);

/// The ros2msg schema of a message of idl/ros2/teleop_msgs, e.g. "JointState": its .msg text,
/// then each message it uses (transitively, once each, in order of first use) after a line of
/// 80 '=' and a line "MSG: teleop_msgs/<Name>", as ROS 2's rosbag2 writes it. Throws
/// std::out_of_range for a name that is not there.
std::string ros2_msg_schema(const std::string& message);

/// The topic `name` of `type` as a recording of `format` keeps it.
bag::TopicInfo recorded_topic(const std::string& name, const transport::SampleType& type, const std::string& qos,
                              RecordingFormat format);

/// A topic read from one recording as one of `format` keeps it: a teleop type is renamed (and
/// its schema filled in for MCAP); any other is kept as it is.
bag::TopicInfo topic_for(const bag::TopicInfo& topic, RecordingFormat format);

}  // namespace teleop::tools

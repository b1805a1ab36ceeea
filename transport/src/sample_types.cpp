#include "teleop/transport/sample_types.h"

#include <algorithm>

#include "teleop/transport/naming.h"
#include "teleop/transport/topics.h"
#include "teleop/transport/type_support.h"

namespace teleop::transport {
namespace {

template <typename T>
SampleType describe() {
  typename PubSubTypeOf<T>::type support;
  SampleType type;
  type.dds_name = support.getName();
  type.bag_name = type.dds_name;
  // "teleop::msg::JointState" -> "teleop/msg/JointState"
  for (size_t at = type.bag_name.find("::"); at != std::string::npos; at = type.bag_name.find("::", at)) {
    type.bag_name.replace(at, 2, "/");
  }
  type.ros2_name = ros2_type_name(type.dds_name);
  type.max_serialized_size = support.m_typeSize;
  return type;
}

template <typename T>
bool named(std::string_view topic, const TopicSpec<T>& spec) {
  return topic == spec.name;
}

// the ROS 2 message of idl/ros2/teleop_msgs, as MCAP recordings name their schemas
bool is_ros2_msg_name(const SampleType& type, std::string_view name) {
  constexpr std::string_view kPackage = "teleop_msgs";  // teleop/msg/X -> teleop_msgs/msg/X
  const std::string_view rest = std::string_view(type.bag_name).substr(type.bag_name.find('/'));
  return name.size() == kPackage.size() + rest.size() && name.substr(0, kPackage.size()) == kPackage &&
         name.substr(kPackage.size()) == rest;
}

}  // namespace

const std::vector<SampleType>& sample_types() {
  static const std::vector<SampleType> types{
      describe<msg::JointState>(),    describe<msg::JointCommand>(),  describe<msg::CartesianCommand>(),
      describe<msg::WrenchStamped>(), describe<msg::JointTorque>(),   describe<msg::HandCommand>(),
      describe<msg::HandState>(),     describe<msg::NodeStatus>(),    describe<msg::ResetRequest>(),
      describe<msg::TdpaEnergy>(),    describe<msg::GeomDistances>(), describe<msg::ObjectPose>(),
      describe<msg::EmergencyStop>(),
  };
  return types;
}

const SampleType* find_sample_type(std::string_view name) {
  const auto& types = sample_types();
  const auto it = std::find_if(types.begin(), types.end(), [&](const SampleType& t) {
    return t.dds_name == name || t.bag_name == name || t.ros2_name == name || is_ros2_msg_name(t, name);
  });
  return it == types.end() ? nullptr : &*it;
}

template <typename T>
KnownTopic known(const TopicSpec<T>& spec) {
  return {spec.name, find_sample_type(typename PubSubTypeOf<T>::type().getName()), spec.qos};
}

const std::vector<KnownTopic>& known_topics() {
  using namespace topics;
  static const std::vector<KnownTopic> list{
      known(kLeaderCommand),        known(kLeaderCartesian), known(kLeaderState),   known(kFollowerState),
      known(kFollowerWrench),       known(kTwinFeedback),    known(kTwinState),     known(kTwinCommand),
      known(kHandCommand),          known(kHandState),       known(kHandJoints),    known(kTdpaLeaderToFollower),
      known(kTdpaFollowerToLeader), known(kTwinDistances),   known(kLockstepState), known(kLockstepCommand),
      known(kResetRequest),         known(kNodeStatus),      known(kEmergencyStop),
  };
  return list;
}

QosPreset topic_qos(std::string_view topic) {
  using namespace topics;
  if (named(topic, kNodeStatus)) return kNodeStatus.qos;
  if (named(topic, kResetRequest)) return kResetRequest.qos;
  if (named(topic, kEmergencyStop)) return kEmergencyStop.qos;
  if (named(topic, kLockstepState)) return kLockstepState.qos;
  if (named(topic, kLockstepCommand)) return kLockstepCommand.qos;
  return QosPreset::kStream;
}

}  // namespace teleop::transport

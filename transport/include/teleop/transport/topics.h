#pragma once
// Every topic of the system, in one place, typed: a topic can only be used with its sample type.

#include <teleop/msg/arm.h>
#include <teleop/msg/hand.h>
#include <teleop/msg/status.h>
#include <teleop/msg/twin.h>

#include "teleop/transport/qos.h"

namespace teleop::transport {

template <typename T>
struct TopicSpec {
  using Sample = T;
  const char* name;
  QosPreset qos;
};

namespace topics {

// leader station -> follower robot: the operator's commanded motion
inline constexpr TopicSpec<msg::JointCommand> kLeaderCommand{"teleop/leader/joint_command", QosPreset::kStream};
inline constexpr TopicSpec<msg::CartesianCommand> kLeaderCartesian{"teleop/leader/cartesian_command", QosPreset::kStream};
// leader device state (for the twin in model-mediated teleoperation)
inline constexpr TopicSpec<msg::JointState> kLeaderState{"teleop/leader/joint_state", QosPreset::kStream};
// follower robot -> everyone: measured state and estimated external wrench
inline constexpr TopicSpec<msg::JointState> kFollowerState{"teleop/follower/joint_state", QosPreset::kStream};
inline constexpr TopicSpec<msg::WrenchStamped> kFollowerWrench{"teleop/follower/wrench", QosPreset::kStream};
// follower site -> twin: measured pose of a tracked object, one topic per object, named this
// prefix + the object's name (a stream: the newest pose is what counts)
inline constexpr const char* kFollowerObjectPosePrefix = "teleop/follower/object_pose/";
// twin -> leader: rendered constraint torque (haptic feedback) and the twin's own state
inline constexpr TopicSpec<msg::JointTorque> kTwinFeedback{"teleop/twin/feedback_torque", QosPreset::kStream};
inline constexpr TopicSpec<msg::JointState> kTwinState{"teleop/twin/joint_state", QosPreset::kStream};
inline constexpr TopicSpec<msg::JointCommand> kTwinCommand{"teleop/twin/joint_command", QosPreset::kStream};
// hand
inline constexpr TopicSpec<msg::HandCommand> kHandCommand{"teleop/hand/command", QosPreset::kStream};
inline constexpr TopicSpec<msg::HandState> kHandState{"teleop/hand/state", QosPreset::kStream};
// the hand's 20 joint angles from its 9 motors (q = S_m m + q0), for the twin and viewers
inline constexpr TopicSpec<msg::JointState> kHandJoints{"teleop/hand/joint_state", QosPreset::kStream};
// passivity energy packets, one topic per direction
inline constexpr TopicSpec<msg::TdpaEnergy> kTdpaLeaderToFollower{"teleop/tdpa/leader_to_follower",
                                                                  QosPreset::kStream};
inline constexpr TopicSpec<msg::TdpaEnergy> kTdpaFollowerToLeader{"teleop/tdpa/follower_to_leader",
                                                                  QosPreset::kStream};
// twin -> everyone: minimum distances of its configured geometry pairs; contact wrenches, one
// topic per configured contact pair, named this prefix + the pair's name
inline constexpr TopicSpec<msg::GeomDistances> kTwinDistances{"teleop/twin/distances", QosPreset::kStream};
inline constexpr const char* kTwinContactWrenchPrefix = "teleop/twin/contact_wrench/";
// lock-step simulation (thesis §3.4): the twin's state for step n, the controller's command for
// step n; reliable, every sample counts
inline constexpr TopicSpec<msg::JointState> kLockstepState{"teleop/lockstep/state", QosPreset::kEvent};
inline constexpr TopicSpec<msg::JointCommand> kLockstepCommand{"teleop/lockstep/command", QosPreset::kEvent};
// an operator's reset of a node's latched faults, one topic for all nodes (the target says whom)
inline constexpr TopicSpec<msg::ResetRequest> kResetRequest{"teleop/reset", QosPreset::kEvent};
// the stop chain: emergency stops and the enables that end them, one topic for all nodes (the
// target says whom; empty: everyone)
inline constexpr TopicSpec<msg::EmergencyStop> kEmergencyStop{"teleop/emergency_stop", QosPreset::kEvent};
// node health, one topic for all nodes (the header's source says who)
inline constexpr TopicSpec<msg::NodeStatus> kNodeStatus{"teleop/node_status", QosPreset::kState};

}  // namespace topics
}  // namespace teleop::transport

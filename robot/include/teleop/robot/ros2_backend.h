#pragma once
// A ROS 2 robot as a hardware backend (`hardware: ros2`): the arm behind ros2_control, commanded
// through a forward_command_controller (std_msgs/Float64MultiArray of efforts, positions or
// velocities) and read from joint_state_broadcaster's sensor_msgs/JointState, on the robot's own
// DDS domain with ROS 2's names and types (docs/robots.md). The section's `ros2:` keys configure it.

#include <memory>
#include <string>
#include <vector>

#include "teleop/common/config.h"
#include "teleop/robot/hardware_registry.h"
#include "teleop/transport/participant_config.h"

namespace teleop::robot {

/// What the robot's forward_command_controller takes: the follower's torque (on the robot's own
/// gravity compensation) or its joint reference.
enum class Ros2CommandInterface { kEffort, kPosition, kVelocity };

struct Ros2HardwareConfig {
  static transport::ParticipantConfig default_participant();

  /// The robot's joint names in the follower's joint order (matched by name in each JointState).
  std::vector<std::string> joints;
  /// Joints the robot's JointState carries besides these (a gripper's fingers), knowingly ignored;
  /// any other name there is a configuration error.
  std::vector<std::string> ignored_joints;
  Ros2CommandInterface interface = Ros2CommandInterface::kEffort;
  /// ROS 2 topic names (`/forward_effort_controller/commands`; DDS: rt/...).
  std::string command_topic;
  std::string state_topic = "/joint_states";
  /// A measured external wrench (geometry_msgs/WrenchStamped, in the robot's base frame, the wrench
  /// the environment exerts on the end effector); "" when the robot has none.
  std::string wrench_topic;
  /// The base frame's name: a wrench stamped with another frame_id is refused ("": not checked).
  std::string wrench_frame;
  /// The robot's DDS domain (`ros2.transport`, the keys of a node's `transport:` but impairment):
  /// by default its ROS_DOMAIN_ID 0, multicast discovery, UDP.
  transport::ParticipantConfig participant = default_participant();
  /// A state older than this on arrival (monotonic) is stale: the follower holds.
  double state_timeout_s = 0.02;
  /// How long the start waits for the robot's first state and its controller's subscription.
  double connect_timeout_s = 10.0;
  /// The follower's cycle locked in phase to the robot's: it starts `phase_lock_lead_s` after the
  /// robot's state arrives, so that the command it computes from that state makes the robot's next
  /// cycle (off: the two 1 kHz loops drift against each other, and a command waits 0-1 ms for the
  /// follower's cycle and 0-1 ms for the robot's).
  bool phase_lock = true;
  double phase_lock_lead_s = 150e-6;
  /// Effort robots only: the robot adds g(q) itself (franka_ros2 does); required, since the hold
  /// command is zero effort.
  bool gravity_compensated = true;
  /// What the robot can do, per joint; +-infinity where not given (the follower's own limits apply).
  std::vector<double> q_min_rad;
  std::vector<double> q_max_rad;
  std::vector<double> max_torque_nm;
};

class Ros2HardwareSpec final : public HardwareSpec {
 public:
  explicit Ros2HardwareSpec(Ros2HardwareConfig config) : config_(std::move(config)) {}
  const char* backend() const override { return "ros2"; }
  /// Joins the robot's domain and waits for its first state and its controller (throws naming the
  /// topic, or the joints missing and extra).
  std::unique_ptr<RobotHardware> make(double period_s) const override;
  const Ros2HardwareConfig& config() const { return config_; }

 private:
  Ros2HardwareConfig config_;
};

/// Reads `section.ros2` (throws ConfigError naming the key).
std::shared_ptr<const Ros2HardwareSpec> parse_ros2_hardware(const ConfigNode& section);

/// Registers the ROS 2 robot as `ros2`.
void add_ros2_backend(HardwareRegistry& registry);

}  // namespace teleop::robot

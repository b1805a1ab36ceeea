#pragma once
// RobotHardware on a ROS 2 robot (ros2_backend.h): read() takes the newest JointState the link
// received and judges it by its arrival, write() sends the torque or the joint reference the
// robot's controller takes, hold() the command that keeps it still by its own means. Destroyed,
// it sends that hold once more and waits for the controller to take it: a forward_command_controller
// keeps applying its last command for as long as it runs.

#include <string>

#include "ros2_robot_link.h"
#include "teleop/robot/robot_hardware.h"
#include "teleop/robot/ros2_backend.h"

namespace teleop::robot {

class Ros2Hardware final : public RobotHardware {
 public:
  /// Joins the robot's domain and waits (up to connect_timeout_s) for its first valid state (and
  /// wrench, when configured) and for its controller to subscribe; throws std::runtime_error naming
  /// the topic or the joints.
  explicit Ros2Hardware(const Ros2HardwareConfig& config);
  ~Ros2Hardware() override;

  size_t joints() const override { return config_.joints.size(); }
  [[nodiscard]] HardwareStatus read(ArmState& state) override;
  [[nodiscard]] HardwareStatus write(const JointVector& tau_nm) override;
  void set_reference(const JointVector& q_rad, const JointVector& dq_radps) override;
  [[nodiscard]] HardwareStatus hold() override;
  bool compensates_gravity() const override { return config_.gravity_compensated; }
  HardwareLimits limits() const override;
  const char* name() const override { return name_.c_str(); }
  int64_t cycle_phase_ns() const override;
  /// The states and wrenches the link refused (names, array sizes, frames, non-finite values).
  void report_counters(std::vector<std::pair<std::string, double>>& counters) const override;

 private:
  void wait_for_robot();

  Ros2HardwareConfig config_;
  std::string name_;
  Ros2RobotLink link_;
  RobotStateRecord state_;
  RobotWrenchRecord wrench_;
  JointVector q_ref_rad_{};
  JointVector dq_ref_radps_{};
  // a position robot holds the pose it had when the hold began
  bool holding_ = false;
  JointVector hold_q_rad_{};
};

}  // namespace teleop::robot

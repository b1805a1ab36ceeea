#pragma once
// The robot the follower drives, behind a small interface: the node never knows whether it is
// a simulation or a real arm. Torque-controlled, like the Franka interface: commanded torques
// come on top of the gravity compensation the robot does itself.

#include <cstdint>

#include "teleop/common/joint_model.h"

namespace teleop::follower {

/// Measured state of the arm.
struct ArmState {
  JointVector q_rad{};
  JointVector dq_radps{};
  /// Link-side torque the joints apply (the simulation's actuator torque).
  JointVector tau_measured_nm{};
  /// External torque: the simulation's contact and limit torques (ground truth), or a real
  /// robot's own estimate. The follower's observer supersedes it where available.
  JointVector tau_ext_nm{};
  /// External force and torque at the end effector, base frame [N, N*m].
  std::array<double, 3> force_ext_n{};
  std::array<double, 3> torque_ext_nm{};
};

enum class HardwareStatus { kOk, kFault };

class RobotHardware {
 public:
  virtual ~RobotHardware() = default;

  virtual size_t joints() const = 0;
  /// Reads the current state. Real-time safe.
  [[nodiscard]] virtual HardwareStatus read(ArmState& state) = 0;
  /// Commands joint torques (on top of gravity compensation) for the next period. Real-time safe.
  [[nodiscard]] virtual HardwareStatus write(const JointVector& tau_nm) = 0;
  /// A name for logs and reports ("simple", "mujoco:scene_wall.xml").
  virtual const char* name() const = 0;
};

}  // namespace teleop::follower

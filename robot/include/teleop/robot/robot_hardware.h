#pragma once
// The robot the follower drives, behind a small interface: the node never knows whether it is
// a simulation or a real arm. Torque-controlled; a robot may compensate gravity itself (like the
// Franka interface), and says so.

#include <cstdint>

#include "teleop/common/joint_model.h"

namespace teleop::robot {

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

/// What the robot itself can do, per joint (infinite where it has no limit).
struct HardwareLimits {
  JointVector q_min_rad{};
  JointVector q_max_rad{};
  /// Largest total link-side torque a joint's drive produces.
  JointVector max_torque_nm{};
};

class RobotHardware {
 public:
  virtual ~RobotHardware() = default;

  virtual size_t joints() const = 0;
  /// Reads the current state. Real-time safe.
  [[nodiscard]] virtual HardwareStatus read(ArmState& state) = 0;
  /// Commands joint torques for the next period (on top of the robot's own gravity compensation
  /// when compensates_gravity()). Real-time safe.
  [[nodiscard]] virtual HardwareStatus write(const JointVector& tau_nm) = 0;
  /// True when the robot adds g(q) to every commanded torque itself (as the Franka interface
  /// does): the follower then sends its controller's torque minus its own g(q).
  virtual bool compensates_gravity() const = 0;
  virtual HardwareLimits limits() const = 0;
  /// A name for logs and reports ("simple", "mujoco:scene_wall.xml").
  virtual const char* name() const = 0;
};

}  // namespace teleop::robot

#pragma once
// The robot the follower drives, behind a small interface: the node never knows whether it is
// a simulation or a real arm. Torque-controlled; a robot may compensate gravity itself (like the
// Franka interface), and says so.

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

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
  /// The robot measured that wrench itself (a force-torque sensor, its own estimate), in the base
  /// frame: the follower's `hardware` estimate is then its joint torques (J^T w), not tau_ext_nm.
  bool wrench_measured = false;
  /// When the robot measured this state, on its own clock [ns] (a ROS 2 robot's header stamp);
  /// 0 where it does not say: then each read is one cycle after the last.
  int64_t measured_ns = 0;
};

enum class HardwareStatus {
  kOk,
  /// The robot failed (a drive fault, a refused command): it needs an operator.
  kFault,
  /// The robot's state is not current (late, or invalid since): read() gave the last one known,
  /// from which no torque may be computed; the follower holds through hold() until it is current.
  kStale,
};

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
  /// The joint reference the follower's law tracks this period (position, velocity), given before
  /// write(): a robot commanded in positions or velocities (a ros2_control position controller)
  /// sends it instead of the torque; one commanded in torque ignores it. Real-time safe.
  virtual void set_reference(const JointVector& q_rad, const JointVector& dq_radps) {
    (void)q_rad;
    (void)dq_radps;
  }
  /// Holds still by the robot's own means (zero torque on its gravity compensation, its position
  /// controller on the pose it had) instead of a write(), while its state is stale. Real-time safe.
  [[nodiscard]] virtual HardwareStatus hold() { return HardwareStatus::kOk; }
  /// True when the robot adds g(q) to every commanded torque itself (as the Franka interface
  /// does): the follower then sends its controller's torque minus its own g(q).
  virtual bool compensates_gravity() const = 0;
  virtual HardwareLimits limits() const = 0;
  /// A robot that keeps its own cycle (a ROS 2 controller manager): a time the follower's cycle
  /// should start at, modulo its period (just after the robot's newest state arrived, monotonic),
  /// so that its command reaches the robot's next cycle. 0: the follower's cycle drives the robot
  /// (a simulation stepped by write()). Real-time safe.
  virtual int64_t cycle_phase_ns() const { return 0; }
  /// Adds the robot's own counters (samples it refused) to the follower's report. After the loop.
  virtual void report_counters(std::vector<std::pair<std::string, double>>& counters) const { (void)counters; }
  /// A name for logs and reports ("simple", "mujoco:scene_wall.xml").
  virtual const char* name() const = 0;
};

}  // namespace teleop::robot

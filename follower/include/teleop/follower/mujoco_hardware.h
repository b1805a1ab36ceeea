#pragma once
// RobotHardware on a MuJoCo simulation of the arm (config/models): each write() applies the
// torques plus gravity compensation and advances the simulation by one control period.

#include <string>

#include "teleop/follower/robot_hardware.h"
#include "teleop/sim/actuated_joints.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::follower {

struct MujocoHardwareConfig {
  /// MJCF file of the arm (and its scene).
  std::string model_path;
  /// Keyframe to start from ("" = the model's default state).
  std::string keyframe;
  /// Control period; the model's timestep must divide it.
  double period_s = 0.001;
};

class MujocoHardware final : public RobotHardware {
 public:
  /// Loads the model (throws std::runtime_error naming the file); the arm is the model's hinge
  /// joints driven by its motor actuators, in actuator order.
  explicit MujocoHardware(const MujocoHardwareConfig& config);

  size_t joints() const override { return arm_.count; }
  [[nodiscard]] HardwareStatus read(ArmState& state) override;
  [[nodiscard]] HardwareStatus write(const JointVector& tau_nm) override;
  const char* name() const override { return name_.c_str(); }
  bool compensates_gravity() const override { return true; }
  /// The joints' ranges and the motors' control ranges from the model.
  HardwareLimits limits() const override;

  /// Puts the arm at rest at `q_rad` (setup time, not for the control loop).
  void place(const JointVector& q_rad);
  /// The simulation, for tests and the twin (not for the control loop).
  sim::MujocoModel& simulation() { return sim_; }

 private:
  void compute_gravity();
  void compute_external_wrench(ArmState& state) const;

  sim::MujocoModel sim_;
  // a second data for gravity: the same pose at rest, so the simulation itself is not disturbed
  std::unique_ptr<mjData, void (*)(mjData*)> rest_;
  std::string name_;
  sim::ActuatedJoints arm_;
  int substeps_ = 1;
  JointVector gravity_nm_{};
  int ee_body_ = -1;
};

}  // namespace teleop::follower

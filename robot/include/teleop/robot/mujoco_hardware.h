#pragma once
// RobotHardware on a MuJoCo simulation (config/models): one arm of a MujocoScene. write()
// applies the torques plus gravity compensation (unless the arm is configured without); the scene advances by one control period after
// it — at once for a one-arm scene, or once every arm has written for a shared one (the owner of
// the scene steps it then).

#include <memory>
#include <optional>
#include <string>

#include "teleop/robot/mujoco_scene.h"
#include "teleop/robot/robot_hardware.h"
#include "teleop/sim/actuated_joints.h"

namespace teleop::robot {

struct MujocoHardwareConfig : MujocoSceneConfig {
  /// The arm: the hinge joints with a motor whose names start with this ("" = every one).
  std::string joint_prefix;
  /// The site on the end effector whose body's contacts make the external wrench.
  std::string ee_site = "ee_site";
  /// The arm adds its gravity torque to every command, as a Franka does (true), or not, as an arm
  /// of plain servo drives does (false: the follower adds it, and an emulated arm of CAN drives
  /// turns this one).
  bool gravity_compensated = true;
};

class MujocoHardware final : public RobotHardware {
 public:
  /// The only arm of its own scene (loaded here; throws std::runtime_error naming the file):
  /// write() steps it.
  explicit MujocoHardware(const MujocoHardwareConfig& config);
  /// One arm of a shared scene: write() leaves the stepping to the scene's owner.
  MujocoHardware(std::shared_ptr<MujocoScene> scene, const MujocoHardwareConfig& config);

  size_t joints() const override { return arm_.count; }
  [[nodiscard]] HardwareStatus read(ArmState& state) override;
  [[nodiscard]] HardwareStatus write(const JointVector& tau_nm) override;
  const char* name() const override { return name_.c_str(); }
  bool compensates_gravity() const override { return gravity_compensated_; }
  /// The joints' ranges and the motors' control ranges from the model.
  HardwareLimits limits() const override;

  /// Puts the arm at rest at `q_rad` (setup time, not for the control loop).
  void place(const JointVector& q_rad);
  /// Puts the joints `held` marks at rest at their angle in `q_rad`, the others as they are
  /// (holding brakes that engaged there, in an emulator's loop): one recomputation for all.
  /// Real-time safe.
  void place_joints(const JointVector& q_rad, const std::array<bool, kMaxJoints>& held);
  /// The simulation, for tests and the twin (not for the control loop).
  sim::MujocoModel& simulation() { return scene_->simulation(); }

 private:
  MujocoHardware(std::shared_ptr<MujocoScene> scene, const MujocoHardwareConfig& config, bool steps_scene);
  void compute_external_wrench(ArmState& state) const;

  std::shared_ptr<MujocoScene> scene_;
  bool steps_scene_;
  bool gravity_compensated_;
  std::string name_;
  sim::ActuatedJoints arm_;
  int ee_body_ = -1;
  // a "real" robot's sensors (MujocoSceneConfig::real_robot): noise on q, dq and the joint torque
  std::optional<sim::SensorNoise> noise_;
};

}  // namespace teleop::robot

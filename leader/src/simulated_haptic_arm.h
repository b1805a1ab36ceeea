#pragma once
// A simulated haptic device: the Panda-class arm on MuJoCo (gravity compensated by the device,
// torque controlled) with a simulated operator's hand holding it: a spring-damper pulling the
// device towards where the operator wants to go (set_operator_target). The rendered feedback
// acts against that hand, so what the operator feels changes where the device goes, and
// closed-loop effects (instability under delay) show.

#include <memory>

#include "teleop/robot/mujoco_hardware.h"
#include "teleop/leader/leader_device.h"

namespace teleop::leader {

struct HapticArmConfig {
  robot::MujocoHardwareConfig model;
  /// The operator's grip: joint stiffness [Nm/rad] and damping [Nm s/rad] of the hand.
  double hand_stiffness_nm_per_rad = 60.0;
  double hand_damping_nms_per_rad = 4.0;
  /// The script's home [rad]: where the device starts when the model's keyframe is not given, and
  /// what the operator's intent is measured from (set_operator_intent).
  JointVector start_rad{};
};

class SimulatedHapticArm final : public LeaderDevice {
 public:
  explicit SimulatedHapticArm(const HapticArmConfig& config);

  /// Where the operator pulls the device (joint space), and the torque the operator adds on
  /// purpose on top of the hand's spring-damper. Real-time safe.
  void set_operator_target(const JointVector& q_rad, const JointVector& dq_radps, const JointVector& intended_nm);
  /// The operator moves the device by the intended motion from where the device started (a
  /// keyframe's pose stands for the script's home, start_rad). Real-time safe.
  void set_operator_intent(const OperatorIntent& intent) override;

  size_t joints() const override { return arm_.joints(); }
  [[nodiscard]] bool read(DeviceState& state) override;
  [[nodiscard]] bool write(const JointVector& feedback_nm) override;
  const char* name() const override { return "simulated_haptic_arm"; }

 private:
  HapticArmConfig config_;
  robot::MujocoHardware arm_;
  robot::ArmState measured_{};
  JointVector start_q_rad_{};
  JointVector intent_target_{};
  JointVector target_q_{};
  JointVector target_dq_{};
  JointVector intended_nm_{};
  JointVector operator_nm_{};
  JointVector applied_{};
  bool hand_on_ = true;
};

}  // namespace teleop::leader

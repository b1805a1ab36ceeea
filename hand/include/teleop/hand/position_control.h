#pragma once
// The SVH study's control (shared/papers/svh-hand-gazebo-mujoco.md §III-B3: a PD per joint in
// the simulator, following a joint trajectory): a PD on each of the hand's 9 motor channels, the
// coupled joints following through the mechanism (the model's equalities). With the couplings
// switched off, the coupled joints are position-controlled on their own instead, towards their
// coupled reference, as Gazebo's mimic-joint plugin does with its PID (paper §III-A1).
// docs/hand.md.

#include "teleop/hand/hand_plant.h"

namespace teleop::hand {

struct PdGains {
  double kp_nm_per_rad = 0.0;
  double kd_nms_per_rad = 0.0;
};

/// The gains that make a PD on `inertia_kgm2` a second-order loop of natural frequency
/// `bandwidth_radps` and damping ratio `damping_ratio`: kp = J w^2, kd = 2 zeta J w. Throws
/// std::invalid_argument unless all three are positive and finite.
PdGains pd_gains_for(double inertia_kgm2, double bandwidth_radps, double damping_ratio);

/// tau = kp (q_ref - q) + kd (dq_ref - dq). Real-time safe.
inline double pd_torque(const PdGains& g, double q_ref, double dq_ref, double q, double dq) {
  return g.kp_nm_per_rad * (q_ref - q) + g.kd_nms_per_rad * (dq_ref - dq);
}

/// How the coupled joints follow their motor.
enum class CouplingMode {
  kConstraint,  ///< the model's equalities (the mechanism): only the 9 motors act
  kServo,       ///< equalities off, a PD of its own on each coupled joint (qfrc_applied), plus its bias force
};

class HandPositionControl {
 public:
  /// Sets `plant`'s equalities for `mode` and designs every PD for the plant's inertias at its
  /// current state (mj_forward done, e.g. at the pose it will hold): a motor channel through its
  /// couplings (kConstraint) or its main joint alone (kServo), at `bandwidth_radps`; each coupled
  /// joint in kServo on the inertia it feels alone (HandPlant::joint_inertia_kgm2) at
  /// `servo_bandwidth_radps`, faster than the motors': its link weighs grams and is shaken by its
  /// motor's joint moving beneath it.
  HandPositionControl(HandPlant& plant, CouplingMode mode, double bandwidth_radps, double damping_ratio,
                      double servo_bandwidth_radps = 200.0);

  /// Applies the torques that drive the motors towards `m_ref` (rates `dm_ref`): the 9 motor
  /// torques, and in kServo the coupled joints' torques in qfrc_applied, each within its motor's
  /// torque limit. Call between plant.begin_step() and plant.end_step(). Real-time safe.
  void apply(HandPlant& plant, const HandMotorVector& m_ref_rad, const HandMotorVector& dm_ref_radps) const;

  CouplingMode mode() const { return mode_; }
  const PdGains& motor_gains(size_t motor) const { return motor_gains_.at(motor); }
  const PdGains& joint_gains(size_t joint) const { return joint_gains_.at(joint); }

 private:
  CouplingMode mode_;
  std::array<PdGains, kHandMotors> motor_gains_{};
  std::array<PdGains, kHandJoints> joint_gains_{};  // kServo: the coupled joints'
};

}  // namespace teleop::hand

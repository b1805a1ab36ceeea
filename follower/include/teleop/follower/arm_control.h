#pragma once
// The follower's control stack for one 7-DoF arm, on teleop::control: the four modes of
// msg::ControlMode behind a bumpless ControllerSwitch, and the external-torque estimators
// (momentum observer, PARTI eqs. 6-7; the direct estimate with M ddq as a baseline) with the
// end-effector wrench from them (eq. 8). It computes on its own model of the arm (like a real
// robot's controller), independent of what the hardware is.

#include <memory>
#include <string>

#include "teleop/control/arm_dynamics.h"
#include "teleop/control/controller_switch.h"
#include "teleop/control/controllers.h"
#include "teleop/control/estimators.h"
#include "teleop/control/payload.h"
#include "teleop/follower/command_validator.h"
#include "teleop/robot/robot_hardware.h"
#include "teleop/sim/mujoco_model.h"

namespace teleop::follower {

/// Which estimate of the external torque the follower publishes.
enum class ExternalTorqueSource { kMomentumObserver, kDirect, kHardware };

struct ArmControlConfig {
  /// MJCF of the arm alone: the controller's model of the robot (7 DoF, site `ee_site`).
  std::string model_path;
  std::string ee_site = "ee_site";
  /// Gains of the position PD mode (the stiff "state space" stand-in).
  control::PositionPd::Gains position_pd{control::JointVector::Constant(600.0), control::JointVector::Constant(30.0)};
  /// Nullspace damping of the Cartesian mode (its stiffness comes with each command).
  control::JointVector nullspace_damping = control::JointVector::Constant(2.0);
  /// Rest posture the Cartesian mode pulls its nullspace towards.
  control::JointVector rest_posture_rad = control::JointVector::Zero();
  /// Torque blend on a mode change (docs/control.md: bounded per-cycle change).
  double blend_s = 0.05;
  /// K_O of the momentum observer [1/s] (bandwidth of its estimate).
  double observer_gain_per_s = 100.0;
  ExternalTorqueSource published_estimate = ExternalTorqueSource::kMomentumObserver;
  /// What the model lacks (docs/calibration.md): the payload's weight is held (added to the
  /// commanded torque) and, with the bias, taken out of the estimated external torque.
  control::ArmCalibration calibration;
};

class ArmControl {
 public:
  /// Loads the model (throws naming the file); setup time only.
  ArmControl(const ArmControlConfig& config, double cycle_s);

  /// Selects the command's mode (blending) and returns the total link-side torque, gravity
  /// included. Real-time safe.
  const control::JointVector& compute(const robot::ArmState& arm, const ValidCommand& command);
  /// Feeds the estimators with the new state and the torque that acted over the last cycle
  /// (the hardware's measured torque). Real-time safe.
  void estimate(const robot::ArmState& arm);

  /// g(q) at the state of the last compute()/estimate().
  const control::JointVector& gravity() const { return dynamics_.gravity(); }
  /// The arm's joint-space inertia at the last estimate.
  const control::JointMatrix& mass() const { return dynamics_.mass(); }
  /// The external joint torque chosen by `published_estimate`, less the calibrated payload and
  /// bias for the two estimators (the hardware's own knows its load); and both estimators' own,
  /// as they see the arm (what a calibration fits).
  const control::JointVector& external_torque() const { return external_; }
  const control::JointVector& observer_torque() const { return observer_.external_torque(); }
  const control::JointVector& direct_torque() const { return direct_.external_torque(); }
  /// The joint torque the calibrated payload's weight exerts at the last state (zero without one).
  const control::JointVector& payload_torque() const { return payload_torque_; }
  /// End-effector wrench from external_torque() (force, moment; base frame, at the site).
  const control::Vector6& wrench() const { return wrench_; }
  /// The wrench of the hardware's own external torque (a simulation's ground truth).
  const control::Vector6& hardware_wrench() const { return hardware_wrench_; }
  const Eigen::Vector3d& ee_position() const { return dynamics_.ee_position(); }
  msg::ControlMode mode() const { return static_cast<msg::ControlMode>(switch_.mode()); }
  bool blending() const { return switch_.blending(); }

 private:
  void load_state(const robot::ArmState& arm);
  /// The time since the last measurement the estimators saw [s]: the robot's stamps apart, or a
  /// cycle where it gives none; 0 for the same measurement again.
  double measurement_interval(const robot::ArmState& arm);
  void load_command(const ValidCommand& command);

  ArmControlConfig config_;
  sim::MujocoModel model_;
  control::ArmDynamics dynamics_;
  control::GravityCompensation gravity_mode_;
  control::JointImpedance joint_impedance_;
  control::CartesianImpedance cartesian_;
  control::PositionPd position_pd_;
  control::ControllerSwitch switch_;
  double cycle_s_;
  int64_t last_measured_ns_ = 0;
  control::MomentumObserver observer_;
  control::DirectEstimator direct_;
  control::JointVector hardware_estimate_ = control::JointVector::Zero();
  const control::JointVector* published_;
  bool calibrated_estimate_;  // the published estimate is one of ours, which the calibration corrects
  control::JointVector payload_torque_ = control::JointVector::Zero();
  control::JointVector external_ = control::JointVector::Zero();
  control::ArmState state_;
  control::ArmCommand command_;
  control::JointVector tau_ = control::JointVector::Zero();
  control::Vector6 wrench_ = control::Vector6::Zero();
  control::Vector6 hardware_wrench_ = control::Vector6::Zero();
};

}  // namespace teleop::follower

#include "teleop/follower/arm_control.h"

#include <algorithm>

namespace teleop::follower {
namespace {

// the switch's mode index is the msg::ControlMode value: controllers are added in that order
static_assert(msg::CONTROL_GRAVITY == 0 && msg::CONTROL_JOINT_IMPEDANCE == 1 && msg::CONTROL_CARTESIAN_IMPEDANCE == 2 &&
              msg::CONTROL_POSITION_PD == 3);

control::JointVector first_joints(const JointVector& v) {
  return Eigen::Map<const control::JointVector>(v.data());
}

}  // namespace

ArmControl::ArmControl(const ArmControlConfig& config, double cycle_s)
    : config_(config),
      model_(sim::MujocoModel::load(config.model_path)),
      dynamics_(model_.model(), config.ee_site),
      gravity_mode_(dynamics_),
      joint_impedance_(dynamics_, {control::JointVector::Zero(), control::JointVector::Zero()}),
      cartesian_(dynamics_, {}),
      position_pd_(config.position_pd),
      switch_(cycle_s, config.blend_s),
      cycle_s_(cycle_s),
      observer_(dynamics_, cycle_s, control::JointVector::Constant(config.observer_gain_per_s)),
      // the same bandwidth as the observer, so the two differ by method, not by filtering
      direct_(dynamics_, cycle_s, std::min(1.0, cycle_s * config.observer_gain_per_s)) {
  switch_.add(gravity_mode_);
  switch_.add(joint_impedance_);
  switch_.add(cartesian_);
  switch_.add(position_pd_);
  switch_.select(msg::CONTROL_JOINT_IMPEDANCE);
  command_.q_rest = config.rest_posture_rad;
  switch (config.published_estimate) {
    case ExternalTorqueSource::kMomentumObserver: published_ = &observer_.external_torque(); break;
    case ExternalTorqueSource::kDirect: published_ = &direct_.external_torque(); break;
    case ExternalTorqueSource::kHardware: published_ = &hardware_estimate_; break;
  }
  calibrated_estimate_ = config.published_estimate != ExternalTorqueSource::kHardware;
}

void ArmControl::load_state(const robot::ArmState& arm) {
  state_.q = first_joints(arm.q_rad);
  state_.dq = first_joints(arm.dq_radps);
}

void ArmControl::load_command(const ValidCommand& c) {
  command_.q_d = first_joints(c.q_des_rad);
  command_.dq_d = first_joints(c.dq_des_radps);
  command_.tau_ff = first_joints(c.tau_ff_nm);
  if (c.mode == msg::CONTROL_JOINT_IMPEDANCE) {
    joint_impedance_.set_gains({first_joints(c.stiffness), first_joints(c.damping)});
  }
  if (c.mode == msg::CONTROL_CARTESIAN_IMPEDANCE) {
    command_.x_d = Eigen::Vector3d(c.x_des_m[0], c.x_des_m[1], c.x_des_m[2]);
    command_.orientation_d = Eigen::Quaterniond(c.orientation_wxyz[0], c.orientation_wxyz[1], c.orientation_wxyz[2], c.orientation_wxyz[3]);
    command_.twist_d = Eigen::Map<const control::Vector6>(c.twist_des.data());
    control::CartesianImpedance::Gains g = cartesian_.gains();
    g.translational_stiffness = Eigen::Vector3d(c.translational_stiffness_n_per_m.data());
    g.rotational_stiffness = Eigen::Vector3d(c.rotational_stiffness_nm_per_rad.data());
    g.damping_ratio = c.damping_ratio;
    g.nullspace_stiffness = control::JointVector::Constant(c.nullspace_stiffness_nm_per_rad);
    g.nullspace_damping = config_.nullspace_damping;
    cartesian_.set_gains(g);
  }
}

const control::JointVector& ArmControl::compute(const robot::ArmState& arm, const ValidCommand& command) {
  load_state(arm);
  load_command(command);
  switch_.select(static_cast<int>(command.mode));
  tau_ = switch_.compute(state_, command_);
  // the payload held as the arm's own weight is (free when a controller brought the dynamics to state_)
  dynamics_.update(state_);
  payload_torque_ = control::payload_torque(dynamics_, config_.calibration.payload);
  tau_ -= payload_torque_;
  return tau_;
}

double ArmControl::measurement_interval(const robot::ArmState& arm) {
  const int64_t last_ns = last_measured_ns_;
  last_measured_ns_ = arm.measured_ns;
  if (arm.measured_ns == 0 || last_ns == 0) return cycle_s_;
  return static_cast<double>(arm.measured_ns - last_ns) * 1e-9;
}

void ArmControl::estimate(const robot::ArmState& arm) {
  load_state(arm);
  const control::JointVector applied = first_joints(arm.tau_measured_nm);
  const double interval_s = measurement_interval(arm);
  observer_.update(state_, applied, interval_s);
  direct_.update(state_, applied, interval_s);
  dynamics_.update(state_);
  if (arm.wrench_measured) {
    // a wrench measured at the end effector, as the joint torques it makes
    control::Vector6 w;
    w << arm.force_ext_n[0], arm.force_ext_n[1], arm.force_ext_n[2], arm.torque_ext_nm[0], arm.torque_ext_nm[1],
        arm.torque_ext_nm[2];
    hardware_estimate_ = dynamics_.jacobian().transpose() * w;
  } else {
    hardware_estimate_ = first_joints(arm.tau_ext_nm);
  }
  payload_torque_ = control::payload_torque(dynamics_, config_.calibration.payload);
  external_ = *published_;
  if (calibrated_estimate_) external_ -= payload_torque_ + config_.calibration.torque_bias_nm;
  wrench_ = control::wrench_from_torque(dynamics_, external_);
  hardware_wrench_ = control::wrench_from_torque(dynamics_, hardware_estimate_);
}

}  // namespace teleop::follower

#include "arm_kinematics.h"

#include "teleop/control/estimators.h"

namespace teleop::leader {

ArmKinematics::ArmKinematics(const std::string& model_path, const std::string& ee_site)
    : model_(sim::MujocoModel::load(model_path)), dynamics_(model_.model(), ee_site) {
  dynamics_.update(state_);
}

void ArmKinematics::update(const JointVector& q_rad, const JointVector& dq_radps) {
  for (int i = 0; i < control::kDof; ++i) {
    state_.q[i] = q_rad[static_cast<size_t>(i)];
    state_.dq[i] = dq_radps[static_cast<size_t>(i)];
  }
  dynamics_.update(state_);
  twist_.noalias() = dynamics_.jacobian() * state_.dq;
}

void ArmKinematics::torque_for_wrench(const control::Vector6& wrench, JointVector& tau_nm) const {
  const control::JointVector tau = dynamics_.jacobian().transpose() * wrench;
  for (int i = 0; i < control::kDof; ++i) tau_nm[static_cast<size_t>(i)] = tau[i];
}

control::Vector6 ArmKinematics::wrench_for_torque(const JointVector& tau_nm) const {
  control::JointVector tau;
  for (int i = 0; i < control::kDof; ++i) tau[i] = tau_nm[static_cast<size_t>(i)];
  return control::wrench_from_torque(dynamics_, tau);
}

}  // namespace teleop::leader

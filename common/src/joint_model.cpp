#include "teleop/common/joint_model.h"

#include <stdexcept>

namespace teleop {

JointModel::JointModel(const JointModelParams& params) : params_(params) {
  if (params.joints == 0 || params.joints > kMaxJoints) throw std::invalid_argument("JointModel: bad joint count");
  if (params.inertia_kgm2 <= 0) throw std::invalid_argument("JointModel: inertia must be positive");
  if (params.wall_joint >= params.joints) throw std::invalid_argument("JointModel: wall joint out of range");
}

void JointModel::reset(const JointVector& q_rad) {
  q_ = q_rad;
  dq_.fill(0.0);
  update_contact();
}

void JointModel::update_contact() {
  contact_.fill(0.0);
  const size_t j = params_.wall_joint;
  const double penetration = q_[j] - params_.wall_q_rad;
  // the wall only pushes, and only while penetrated
  if (penetration > 0) contact_[j] = -params_.wall_stiffness_nm_per_rad * penetration;
}

void JointModel::step(const JointVector& tau_nm, double dt_s) {
  for (size_t i = 0; i < params_.joints; ++i) {
    const double ddq = (tau_nm[i] + contact_[i] - params_.viscous_nms_per_rad * dq_[i]) / params_.inertia_kgm2;
    dq_[i] += ddq * dt_s;
    q_[i] += dq_[i] * dt_s;
  }
  update_contact();
}

}  // namespace teleop

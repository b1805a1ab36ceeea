#include "hand_ik.h"

#include <Eigen/Cholesky>
#include <algorithm>

namespace teleop::box_task {

using control::JointVector;

HandIk::HandIk(const mjModel* arm, std::string_view ee_site, const JointVector& q_rest, const IkSettings& settings)
    : dynamics_(arm, ee_site), q_rest_(q_rest), settings_(settings) {
  for (int j = 0; j < control::kDof; ++j) {
    q_min_[j] = arm->jnt_range[2 * j];
    q_max_[j] = arm->jnt_range[2 * j + 1];
  }
}

control::Vector6 HandIk::pose_error(const Eigen::Vector3d& position_m, const Eigen::Matrix3d& rotation) const {
  control::Vector6 error;
  error.head<3>() = position_m - dynamics_.ee_position();
  // rotation vector of R_d R^T, world frame (the Jacobian's angular rows are world frame too)
  const Eigen::AngleAxisd delta(rotation * dynamics_.ee_rotation().transpose());
  error.tail<3>() = delta.angle() * delta.axis();
  return error;
}

IkError HandIk::solve(const Eigen::Vector3d& position_m, const Eigen::Matrix3d& rotation, JointVector& q_rad) {
  const double lambda2 = settings_.damping * settings_.damping;
  const JointVector lower = q_min_.array() + settings_.limit_margin_rad;
  const JointVector upper = q_max_.array() - settings_.limit_margin_rad;
  control::ArmState state;
  for (int i = 0; i < settings_.iterations; ++i) {
    state.q = q_rad;
    dynamics_.update(state);
    const control::Jacobian& J = dynamics_.jacobian();
    // damped pseudo-inverse J^T (J J^T + lambda^2 I)^-1 and the nullspace it leaves
    const control::Matrix6 JJt = J * J.transpose() + lambda2 * control::Matrix6::Identity();
    const Eigen::Matrix<double, control::kDof, 6> pinv = J.transpose() * JJt.ldlt().solve(control::Matrix6::Identity());
    const control::JointMatrix nullspace = control::JointMatrix::Identity() - pinv * J;
    const JointVector step =
        pinv * pose_error(position_m, rotation) + nullspace * (settings_.nullspace_gain * (q_rest_ - q_rad));
    q_rad = (q_rad + step).cwiseMax(lower).cwiseMin(upper);
  }
  state.q = q_rad;
  dynamics_.update(state);
  const control::Vector6 error = pose_error(position_m, rotation);
  return {error.head<3>().norm(), error.tail<3>().norm()};
}

Eigen::Isometry3d HandIk::flange_pose(const JointVector& q_rad) {
  control::ArmState state;
  state.q = q_rad;
  dynamics_.update(state);
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = dynamics_.ee_rotation();
  pose.translation() = dynamics_.ee_position();
  return pose;
}

JointVector HandIk::joint_torque(const JointVector& q_rad, const Eigen::Vector3d& force_n) {
  control::ArmState state;
  state.q = q_rad;
  dynamics_.update(state);
  return dynamics_.jacobian().topRows<3>().transpose() * force_n;
}

double HandIk::limit_distance(const JointVector& q_rad) const {
  return std::min((q_rad - q_min_).minCoeff(), (q_max_ - q_rad).minCoeff());
}

}  // namespace teleop::box_task

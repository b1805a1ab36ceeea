#include "teleop/control/controllers.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

namespace teleop::control {

JointVector GravityCompensation::compute(const ArmState& state, const ArmCommand& /*command*/) {
  dyn_->update(state);
  return dyn_->gravity();
}

JointVector JointImpedance::compute(const ArmState& state, const ArmCommand& command) {
  dyn_->update(state);
  return gains_.stiffness.cwiseProduct(command.q_d - state.q) + gains_.damping.cwiseProduct(command.dq_d - state.dq) +
         dyn_->gravity() + command.tau_ff;
}

JointVector CartesianImpedance::compute(const ArmState& state, const ArmCommand& command) {
  dyn_->update(state);
  const JointMatrix& M = dyn_->mass();
  const Jacobian& J = dyn_->jacobian();

  // pose error, world frame
  error_.head<3>() = command.x_d - dyn_->ee_position();
  const Eigen::Quaterniond current(dyn_->ee_rotation());
  Eigen::Quaterniond delta = command.orientation_d.normalized() * current.conjugate();
  if (delta.w() < 0) delta.coeffs() = -delta.coeffs();
  const double sin_half = delta.vec().norm();
  const double angle = 2.0 * std::atan2(sin_half, delta.w());
  // rotation vector angle * axis; 2 vec for tiny angles (angle / sin_half -> 2)
  error_.tail<3>() = sin_half > 1e-12 ? Eigen::Vector3d(delta.vec() * (angle / sin_half)) : Eigen::Vector3d(2.0 * delta.vec());

  // task-space inertia Lambda = (J M^-1 J^T)^-1
  const Eigen::LDLT<JointMatrix> m_ldlt(M);
  const Eigen::Matrix<double, kDof, 6> minv_jt = m_ldlt.solve(J.transpose());
  Matrix6 lambda_inv = J * minv_jt;
  lambda_inv.diagonal().array() += gains_.lambda_damping;
  const Eigen::LDLT<Matrix6> l_ldlt(lambda_inv);
  const Matrix6 lambda = l_ldlt.solve(Matrix6::Identity());

  Vector6 k;
  k << gains_.translational_stiffness, gains_.rotational_stiffness;
  Vector6 d;
  for (int i = 0; i < 6; ++i) d[i] = 2.0 * gains_.damping_ratio * std::sqrt(k[i] * std::max(lambda(i, i), 0.0));

  const Vector6 velocity = J * state.dq;
  const Vector6 wrench = k.cwiseProduct(error_) + d.cwiseProduct(command.twist_d - velocity);

  // N = I - J^T Lambda J M^-1; N tau0 = tau0 - J^T (Lambda (J (M^-1 tau0)))
  const JointVector tau0 =
      gains_.nullspace_stiffness.cwiseProduct(command.q_rest - state.q) - gains_.nullspace_damping.cwiseProduct(state.dq);
  const JointVector minv_tau0 = m_ldlt.solve(tau0);
  const JointVector tau_null = tau0 - J.transpose() * (lambda * (J * minv_tau0));

  return J.transpose() * wrench + tau_null + dyn_->bias();
}

JointVector PositionPd::compute(const ArmState& state, const ArmCommand& command) {
  return gains_.kp.cwiseProduct(command.q_d - state.q) + gains_.kd.cwiseProduct(command.dq_d - state.dq) +
         command.tau_ff;
}

}  // namespace teleop::control

#include "teleop/control/estimators.h"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace teleop::control {

MomentumObserver::MomentumObserver(ArmDynamics& dynamics, double cycle_s, const JointVector& gain)
    : dyn_(&dynamics), h_(cycle_s), gain_(gain) {}

const JointVector& MomentumObserver::update(const ArmState& state, const JointVector& tau_applied) {
  dyn_->update(state);
  const JointMatrix& mass = dyn_->mass();
  if (!started_) {
    p0_ = mass * state.dq;
    integral_.setZero();
    r_.setZero();
    started_ = true;
  } else {
    integral_ += h_ * (tau_applied - bias_prev_ + r_) + (mass - mass_prev_) * state.dq;
    r_ = gain_.cwiseProduct(mass * state.dq - p0_ - integral_);
  }
  mass_prev_ = mass;
  bias_prev_ = dyn_->bias();
  return r_;
}

DirectEstimator::DirectEstimator(ArmDynamics& dynamics, double cycle_s, double gamma)
    : dyn_(&dynamics), h_(cycle_s), gamma_(gamma) {}

const JointVector& DirectEstimator::update(const ArmState& state, const JointVector& tau_applied) {
  dyn_->update(state);
  if (!started_) {
    estimate_.setZero();
    started_ = true;
  } else {
    const JointVector ddq = (state.dq - dq_prev_) / h_;
    const JointVector raw = dyn_->mass() * ddq + dyn_->bias() - tau_applied;
    estimate_ = gamma_ * raw + (1.0 - gamma_) * estimate_;
  }
  dq_prev_ = state.dq;
  return estimate_;
}

PartiDirectEstimator::PartiDirectEstimator(ArmDynamics& dynamics, double gamma) : dyn_(&dynamics), gamma_(gamma) {
  if (!(gamma > 0.0 && gamma <= 1.0)) throw std::invalid_argument("PartiDirectEstimator: gamma must be in (0, 1]");
}

const JointVector& PartiDirectEstimator::update(const JointVector& q, const JointVector& tau_d,
                                                const JointVector& tau_m) {
  // gravity only: the velocity does not enter eq. 5
  dyn_->update(ArmState{q, JointVector::Zero()});
  estimate_ = gamma_ * (tau_d - tau_m + dyn_->gravity()) + (1.0 - gamma_) * estimate_;
  return estimate_;
}

Vector6 wrench_from_torque(const ArmDynamics& dynamics, const JointVector& tau_ext, double mu) {
  const Jacobian& J = dynamics.jacobian();
  Matrix6 jjt = J * J.transpose();
  jjt.diagonal().array() += mu * mu;
  return Eigen::LDLT<Matrix6>(jjt).solve(J * tau_ext);
}

}  // namespace teleop::control

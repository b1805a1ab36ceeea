#include "teleop/control/estimators.h"

#include <Eigen/Cholesky>
#include <stdexcept>

namespace teleop::control {

MomentumObserver::MomentumObserver(ArmDynamics& dynamics, double cycle_s, const JointVector& gain)
    : dyn_(&dynamics), h_(cycle_s), gain_(gain) {}

const JointVector& MomentumObserver::update(const ArmState& state, const JointVector& tau_applied, double interval_s) {
  if (started_ && interval_s == 0.0) return r_;
  if (!(interval_s > 0.0)) started_ = false;  // a robot clock that went back: no interval to integrate over
  dyn_->update(state);
  const JointMatrix& mass = dyn_->mass();
  const JointVector p = mass * state.dq;
  if (!started_) {
    p0_ = p;
    integral_.setZero();
    r_.setZero();
    started_ = true;
  } else {
    integral_ += interval_s * (tau_applied - bias_prev_ + r_) + (mass - mass_prev_) * state.dq;
    r_ = gain_.cwiseProduct(p - p0_ - integral_);
    if (interval_s * gain_.maxCoeff() > 1.0) bridge_gap(p, state.dq, tau_applied, interval_s);
  }
  dq_prev_ = state.dq;
  mass_prev_ = mass;
  bias_prev_ = dyn_->bias();
  return r_;
}

void MomentumObserver::bridge_gap(const JointVector& p, const JointVector& dq, const JointVector& tau_applied,
                                  double interval_s) {
  // the momentum the external torque delivered over the interval, as its mean torque
  const JointVector mean_external = (mass_prev_ * (dq - dq_prev_)) / interval_s - (tau_applied - bias_prev_);
  for (int i = 0; i < kDof; ++i) {
    if (interval_s * gain_[i] <= 1.0) continue;
    r_[i] = mean_external[i];
    integral_[i] = p[i] - p0_[i] - r_[i] / gain_[i];  // so that eq. 7 holds on from here
  }
}

DirectEstimator::DirectEstimator(ArmDynamics& dynamics, double cycle_s, double gamma)
    : dyn_(&dynamics), h_(cycle_s), gamma_(gamma) {}

const JointVector& DirectEstimator::update(const ArmState& state, const JointVector& tau_applied, double interval_s) {
  if (started_ && interval_s == 0.0) return estimate_;
  if (!(interval_s > 0.0)) started_ = false;
  dyn_->update(state);
  if (!started_) {
    estimate_.setZero();
    started_ = true;
  } else {
    const JointVector ddq = (state.dq - dq_prev_) / interval_s;
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
